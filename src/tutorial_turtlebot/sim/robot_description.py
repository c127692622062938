"""``robot_description MODEL [CAMERA]``: print the URDF that sim.launch loads as
/robot_description (CAMERA true on a burger gives the AutoRace burger). Bad arguments: one line
on stderr naming the valid values, exit status 2."""
import sys

from ..errors import UserError
from .urdf_file import read_urdf, urdf_path

USAGE = "usage: robot_description MODEL [CAMERA]  (MODEL: burger, waffle, waffle_pi; CAMERA: true/false)"


def description_text(model: str, camera: str = "false") -> str:
    """The checked URDF text of ``model``; UserError for a bad model, camera flag or file."""
    if camera.lower() not in ("true", "false"):
        raise UserError("camera must be true or false, got %r" % camera)
    path = urdf_path(model, camera.lower() == "true")
    read_urdf(path)  # a broken file is named here, not deep inside robot_state_publisher
    with open(path, encoding="utf-8") as f:
        return f.read()


def main(argv=None) -> None:
    """Entry point of ``scripts/robot_description``."""
    args = sys.argv[1:] if argv is None else argv
    if not 1 <= len(args) <= 2:
        print(USAGE, file=sys.stderr)
        sys.exit(2)
    try:
        sys.stdout.write(description_text(*args))
    except UserError as err:
        print("robot_description: %s" % err, file=sys.stderr)
        sys.exit(2)
