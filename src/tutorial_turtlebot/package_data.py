"""Where the package's data folders (urdf/, worlds/, ...) are, wherever the code runs from.

In the source tree and a catkin devel space this module sits in ``src/tutorial_turtlebot/``, two
levels below the package root; in an install space the data is in ``share/tutorial_turtlebot``,
which rospkg finds (it walks all of ROS_PACKAGE_PATH, some 20 ms: once per process).
"""
import functools
import os

PACKAGE = "tutorial_turtlebot"
_SOURCE_ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                             os.pardir, os.pardir))


def data_dir(name: str) -> str:
    """Absolute path of the package's data folder ``name`` (e.g. "urdf", "worlds")."""
    candidate = os.path.join(_SOURCE_ROOT, name)
    if os.path.isdir(candidate):
        return candidate
    root = _installed_root()
    return candidate if root is None else os.path.join(root, name)


@functools.lru_cache(maxsize=1)
def _installed_root():
    """The package's folder as rospkg finds it (an install space's share/...); None if not."""
    try:
        import rospkg
    except ImportError:
        return None
    try:
        return rospkg.RosPack().get_path(PACKAGE)
    except rospkg.ResourceNotFound:
        return None
