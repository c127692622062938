"""Where the package's data folders (urdf/, worlds/, ...) are, wherever the code runs from.

In the source tree and a catkin devel space the modules sit in ``src/tutorial_turtlebot/sim/`` three
levels below the package root; in an install space the data is in ``share/tutorial_turtlebot``,
which rospkg finds.
"""
import os

PACKAGE = "tutorial_turtlebot"
_SOURCE_ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                             os.pardir, os.pardir, os.pardir))


def data_dir(name: str) -> str:
    """Absolute path of the package's data folder ``name`` (e.g. "urdf", "worlds")."""
    candidate = os.path.join(_SOURCE_ROOT, name)
    if os.path.isdir(candidate):
        return candidate
    try:
        import rospkg
    except ImportError:
        return candidate
    try:
        return os.path.join(rospkg.RosPack().get_path(PACKAGE), name)
    except rospkg.ResourceNotFound:
        return candidate
