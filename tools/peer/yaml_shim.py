"""make peer's PyYAML shim: installed as ``sitecustomize.py`` on PYTHONPATH for the runs of
gazebo_ros's ros_network tests only (tools/peer/run_peer.py copies this file into the scratch
workspace, catkin_ws/peer/python_shims/).

Their test node, gazebo_ros/test/ros_network/ros_api_checker, calls ``yaml.load(f)`` without a
Loader. PyYAML 6 (Debian 12's) refuses that (``load() missing 1 required positional argument:
'Loader'``); PyYAML 5, Noetic's, warned and used FullLoader. This gives ``yaml.load`` that
default back, so the checker runs unmodified. Every other call is passed on as it is.

Being sitecustomize, it stands in for Debian's own /etc/python3.X/sitecustomize.py (apport's
exception hook) in those runs only.
"""


def install(yaml):
    """Make ``yaml.load``'s Loader default to FullLoader (once); return the module."""
    if getattr(yaml.load, "peer_shim", False):
        return yaml
    original = yaml.load

    def load(stream, Loader=None):
        return original(stream, Loader=Loader if Loader is not None else yaml.FullLoader)

    load.peer_shim = True
    yaml.load = load
    return yaml


if __name__ == "sitecustomize":
    try:
        import yaml as _yaml
    except ImportError:   # nothing to mend
        pass
    else:
        install(_yaml)
