"""Errors that reach the user as one readable line (never a traceback)."""


def one_line(err: BaseException) -> str:
    """An unexpected exception as one short line: "OverflowError: float too large to pack"."""
    return "%s: %s" % (type(err).__name__, " ".join(str(err).split())[:300])


class UserError(Exception):
    """Bad input from the user: a wrong argument, parameter, model, world or file.

    ``str(err)`` is the whole message, one line, saying what is wrong and what would be right.
    """


class ModelError(UserError):
    """Unknown robot model name."""


class WorldError(UserError):
    """Unknown world name, missing or malformed world (SDF) file."""


class UrdfError(UserError):
    """Missing or malformed robot description (URDF) file."""


class RequestError(UserError):
    """A world request Gazebo would refuse: ``str(err)`` is its status message, one line."""
