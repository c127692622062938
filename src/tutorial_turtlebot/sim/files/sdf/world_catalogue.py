"""The worlds this package ships: their names, files in ``worlds/`` and spawn poses, and how a
world named on the command line (a catalogue name or a path) becomes a file. No ROS, no
pybullet, no SDF reading (world_sdf reads the file).

Units: metres, radians; a spawn is (x, y, yaw) of the robot's base_footprint in the world frame.
"""
import os
from typing import Dict, NamedTuple, Optional, Tuple

from ....errors import WorldError
from ....package_data import data_dir

Spawn = Tuple[float, float, float]                       # x, y (m), yaw (rad) of base_footprint


class WorldEntry(NamedTuple):
    """A world this package ships: its file in ``WORLD_DIR`` and where the robot spawns."""

    file: str
    spawn: Spawn


WORLD_DIR = data_dir("worlds")

# The spawn poses of the turtlebot3_gazebo launch files (doc/turtlebot3.md 4.1); the robot faces +x.
_CATALOGUE = (
    ("empty", WorldEntry("empty.world", (0.0, 0.0, 0.0))),
    ("turtlebot3_world", WorldEntry("turtlebot3_world.world", (-2.0, -0.5, 0.0))),
    ("turtlebot3_house", WorldEntry("turtlebot3_house.world", (-3.0, 1.0, 0.0))),
    ("turtlebot3_autorace", WorldEntry("turtlebot3_autorace.world", (0.245, -1.787, 0.0))),
    # The learning stages of turtlebot3_machine_learning (doc/turtlebot3.md 4.6).
    ("turtlebot3_stage_1", WorldEntry("turtlebot3_stage_1.world", (0.0, 0.0, 0.0))),
    ("turtlebot3_stage_2", WorldEntry("turtlebot3_stage_2.world", (0.0, 0.0, 0.0))),
    ("turtlebot3_stage_3", WorldEntry("turtlebot3_stage_3.world", (0.0, 0.0, 0.0))),
    ("turtlebot3_stage_4", WorldEntry("turtlebot3_stage_4.world", (-0.7, 0.0, 0.0))),
)
WORLDS: Dict[str, WorldEntry] = {name: entry for name, entry in _CATALOGUE
                                 if os.path.isfile(os.path.join(WORLD_DIR, entry.file))}
# a world file's endings; ".model" too: Gazebo loads any SDF file it is given, and published
# worlds are named so (`gazebo room.model`)
WORLD_SUFFIXES = (".world", ".sdf", ".model")


def world_from_command_line(world: str, environ=os.environ) -> str:
    """``world`` with a relative file path made absolute against the directory the user typed
    the command in (roslaunch runs the sim in ~/.ros, but leaves the shell's $PWD as it was).
    Where no such file is there, the world is looked for as gzserver looks for its world
    (``gazebo_world``); found nowhere, the path from $PWD (named by the error)."""
    if world.endswith(WORLD_SUFFIXES) and not os.path.isabs(os.path.expanduser(world)):
        typed = os.path.join(environ.get("PWD") or os.getcwd(), world)
        return typed if os.path.isfile(typed) else gazebo_world(world, environ) or typed
    return world


def gazebo_world(relative: str, environ=os.environ) -> Optional[str]:
    """The file gzserver would load for the ``relative`` world path: in a folder of
    GAZEBO_RESOURCE_PATH, else Gazebo's own ``worlds/NAME.world`` as this package's
    worlds/NAME.world (``worlds/empty.world``, as gazebo_ros's empty_world.launch names it);
    None where there is none."""
    places = [os.path.join(f, relative)
              for f in environ.get("GAZEBO_RESOURCE_PATH", "").split(":") if f]
    if relative.startswith("worlds/"):
        places.append(os.path.join(WORLD_DIR, relative[len("worlds/"):]))
    return next((p for p in places if os.path.isfile(p)), None)


def resolve_world(name_or_path: str) -> Tuple[str, Optional[Spawn]]:
    """(absolute path, spawn) for a catalogue name or a path to a .world/.sdf/.model file.

    A path to a catalogue file gets that world's spawn; any other path gets None.
    """
    if name_or_path in WORLDS:
        entry = WORLDS[name_or_path]
        return os.path.join(WORLD_DIR, entry.file), entry.spawn
    if not name_or_path.endswith(WORLD_SUFFIXES):
        raise WorldError("unknown world %r: valid worlds are %s, or a path to a %s file"
                         % (name_or_path, ", ".join(WORLDS), " or ".join(WORLD_SUFFIXES)))
    path = os.path.abspath(os.path.expanduser(name_or_path))
    if not os.path.isfile(path):
        raise WorldError("world file not found: %s" % path)
    for entry in WORLDS.values():
        known = os.path.join(WORLD_DIR, entry.file)
        if os.path.isfile(known) and os.path.samefile(known, path):
            return path, entry.spawn
    return path, None
