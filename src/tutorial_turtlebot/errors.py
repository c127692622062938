"""Errors that reach the user as one readable line (never a traceback)."""


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
