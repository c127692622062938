"""``robot_description MODEL [CAMERA] [--new-sim]``: print the URDF that sim.launch loads as
/robot_description (CAMERA true on a burger gives the AutoRace burger; empty or false: the
model's own URDF). With ``--new-sim`` it
first makes sure no simulator runs on the ROS master yet: sim.launch runs it while roslaunch is
still reading the launch file, so a second sim.launch stops before it changes anything of the
first. Bad arguments, or a running simulator: one line on stderr, exit status 2."""
import sys

from ..errors import UrdfError, UserError
from ..sim.files import xml_reader
from ..robot_models import urdf_path
from .single_instance import refuse_if_running

USAGE = ("usage: robot_description MODEL [CAMERA] [--new-sim]  (MODEL: burger, waffle, "
         "waffle_pi; CAMERA: true/false/empty; --new-sim: fail if a simulator already runs)")


def description_text(model: str, camera: str = "false") -> str:
    """The checked URDF text of ``model``; UserError for a bad model, camera flag or file."""
    if camera.lower() not in ("true", "false", "", "auto"):
        raise UserError("camera must be true, false or auto (the URDF's), got %r" % camera)
    path = urdf_path(model, camera.lower() == "true")
    # a file that is not XML is named here, not deep inside robot_state_publisher; the sim
    # checks the rest. (No URDF reader here: it needs numpy, 0.1 s of every start-up.)
    xml_reader.parse_file(path, "URDF file", UrdfError)
    with open(path, encoding="utf-8") as f:
        return f.read()


def main(argv=None) -> None:
    """Entry point of ``scripts/robot_description``."""
    args = sys.argv[1:] if argv is None else list(argv)
    new_sim = "--new-sim" in args
    args = [arg for arg in args if arg != "--new-sim"]
    if not 1 <= len(args) <= 2:
        print(USAGE, file=sys.stderr)
        sys.exit(2)
    try:
        if new_sim:
            refuse_if_running()
        sys.stdout.write(description_text(*args))
    except UserError as err:
        print("robot_description: %s" % err, file=sys.stderr)
        sys.exit(2)
