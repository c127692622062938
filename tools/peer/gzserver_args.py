"""gzserver's command line as the sim's: what the stand-in gazebo_ros package's ``gzserver``,
``gazebo`` and ``debug`` executables run (tools/peer/run_peer.py writes them into the scratch
workspace; each is three lines calling ``main`` here).

Gazebo 11's ``gzserver [options] [WORLD] [ROS remaps]`` becomes ``rosrun tutorial_turtlebot sim``
with the world and no robot of its own (``_spawn_robot:=false``: robots come by spawn_model, as
in Gazebo), the private parameters the options stand for, and roslaunch's remaps (``__name:=``,
``__log:=``) passed on. ``/use_sim_time`` is left to whoever starts it: the .test files and
gazebo_ros's empty_world.launch set it, gzserver does not.

  WORLD            an existing file (made absolute against the working directory), else the
                   first GAZEBO_RESOURCE_PATH folder holding it, else, for Gazebo's own
                   ``worlds/NAME.world``, this repository's worlds/NAME.world (the sim's
                   ``empty`` world is Gazebo's empty.world); without one, worlds/empty.world as
                   gzserver. A world found nowhere is passed on as it is: the sim refuses it
                   in one line, as gzserver does.
  -u, --pause      ``_paused:=true``
  --seed N         ``_seed:=N`` (the laser noise seed)
  --verbose, -e/--physics E, -s/--server-plugin LIB, -r/--record and the --record_* options,
  --minimal_comms, --lockstep, -q/--quiet, -o/--profile P, -g/--gui-plugin LIB
                   dropped: the sim logs to the screen anyway, its engine is pybullet, gazebo_ros's
                   api and paths plugins are built in
  -p/--play LOG, --iters N, --initial_sim_time T
                   dropped, each with a warning line: the sim has no log playback, no iteration
                   limit, no initial sim time
The ``gazebo`` entry (gzserver and gzclient in one) adds ``_gui:=true``: the sim's own window
where a display exists (the sim runs headless without one, and says so).
"""
import os
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
PROJECT_WORLDS = os.path.join(ROOT, "worlds")
DEFAULT_WORLD = "worlds/empty.world"

# gzserver's options: (names, takes a value, private parameter it becomes or None, warning)
OPTIONS = [
    (("-u", "--pause"), False, ("paused", "true"), None),
    (("--seed",), True, ("seed", None), None),
    (("--verbose",), False, None, None),
    (("-q", "--quiet"), False, None, None),
    (("-e", "--physics"), True, None, None),
    (("-s", "--server-plugin"), True, None, None),
    (("-g", "--gui-plugin"), True, None, None),
    (("-r", "--record"), False, None, None),
    (("--record_encoding", "--record_path", "--record_period", "--record_filter",
      "--record_resources"), True, None, None),
    (("--minimal_comms", "--lockstep"), False, None, None),
    (("-o", "--profile"), True, None, None),
    (("-p", "--play"), True, None, "the sim has no log playback"),
    (("--iters",), True, None, "the sim has no iteration limit"),
    (("--initial_sim_time",), True, None, "the sim starts at sim time 0"),
]


class GzArgsError(ValueError):
    """A command line gzserver itself would refuse (one line)."""


def _option(word):
    for names, takes_value, param, warning in OPTIONS:
        if word in names:
            return takes_value, param, warning
    return None


def find_world(world, environ=None, cwd=None):
    """The world file gzserver would load for ``world`` (see the module docstring)."""
    environ = os.environ if environ is None else environ
    cwd = cwd or environ.get("PWD") or os.getcwd()
    if os.path.isabs(world):
        return world
    here = os.path.join(cwd, world)
    if os.path.isfile(here):
        return os.path.normpath(here)
    for folder in environ.get("GAZEBO_RESOURCE_PATH", "").split(":"):
        if folder and os.path.isfile(os.path.join(folder, world)):
            return os.path.normpath(os.path.join(folder, world))
    parts = world.split("/")
    if len(parts) == 2 and parts[0] == "worlds":
        ours = os.path.join(PROJECT_WORLDS, parts[1])
        if os.path.isfile(ours):
            return ours
    return world


def translate(argv, entry="gzserver", environ=None, cwd=None):
    """(the sim's command line as a list, [warning lines]) for gzserver's ``argv`` (without the
    program name); ``entry`` is the executable called (gzserver, gazebo or debug)."""
    params, remaps, worlds, warnings = [], [], [], []
    words = list(argv)
    i = 0
    while i < len(words):
        word = words[i]
        i += 1
        if ":=" in word and not word.startswith("-"):
            remaps.append(word)     # roslaunch's __name:=, __log:=, and any remap, last
            continue
        if word.startswith("-"):
            name, inline = (word.split("=", 1) + [None])[:2] if word.startswith("--") \
                else (word, None)
            known = _option(name)
            if known is None:
                raise GzArgsError("%s: unknown option %s (gzserver's options: %s)"
                                  % (entry, word, " ".join(sorted(
                                      n for names, _, _, _ in OPTIONS for n in names))))
            takes_value, param, warning = known
            value = inline
            if takes_value and value is None:
                if i >= len(words):
                    raise GzArgsError("%s: option %s needs a value" % (entry, name))
                value = words[i]
                i += 1
            if warning:
                warnings.append("%s: %s %s ignored: %s" % (entry, name, value or "", warning))
            if param:
                key, fixed = param
                params.append("_%s:=%s" % (key, fixed if fixed is not None else value))
            continue
        if word:
            worlds.append(word)
    if len(worlds) > 1:
        raise GzArgsError("%s: one world file at most, got %s" % (entry, " ".join(worlds)))
    world = find_world(worlds[0] if worlds else DEFAULT_WORLD, environ, cwd)
    command = ["rosrun", "tutorial_turtlebot", "sim", "_world:=%s" % world,
               "_spawn_robot:=false"] + params
    if entry == "gazebo":
        command.append("_gui:=true")
    return command + remaps, warnings


def main(argv=None, entry="gzserver"):
    """Replace this process with the sim (os.execvp), or exit 255 with one line, as gzserver
    does on a bad command line."""
    argv = sys.argv[1:] if argv is None else argv
    try:
        command, warnings = translate(argv, entry)
    except GzArgsError as err:
        sys.stderr.write("%s\n" % err)
        sys.exit(255)
    for line in warnings:
        sys.stderr.write(line + "\n")
    sys.stdout.write("%s (stand-in): %s\n" % (entry, " ".join(command)))
    sys.stdout.flush()
    os.execvp(command[0], command)
