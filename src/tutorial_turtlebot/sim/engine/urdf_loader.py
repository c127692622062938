"""The one way a URDF robot becomes a pybullet body (a plain URDF spawned is converted to SDF
instead: files/urdf/urdf_to_sdf).

The text is what ``files.urdf_meshes.bullet_urdf_text`` writes (meshes as Wavefront files,
bare frames next to massless, one element a line); it is loaded with ``URDF_FLAGS``:
- fixed joints merged, as Gazebo lumps fixed links into their parent;
- the inertia as the file gives it (pybullet would otherwise compute one from the collision
  shapes);
- cylinders as true cylinders (Gazebo's ODE collides with cylinders, not with their hulls).
"""
import os
import tempfile

from ...errors import UserError
from ..files.urdf.urdf_meshes import textured_urdf
from .bullet import pybullet, quiet_output
from .client import Client
from .rendering import note_textures

URDF_FLAGS = (pybullet.URDF_MERGE_FIXED_LINKS | pybullet.URDF_USE_INERTIA_FROM_FILE
              | pybullet.URDF_USE_IMPLICIT_CYLINDER)


def load_urdf(client: Client, urdf: str) -> int:
    """A new body of URDF text ``urdf`` in pybullet ``client`` (its root link at the
    origin): the body id. UserError (one line) when pybullet cannot load it. A URDF with a
    textured mesh makes the client's cameras draw textures from then on."""
    if textured_urdf(urdf):
        note_textures(client)
    fd, path = tempfile.mkstemp(suffix=".urdf", prefix="tutorial_turtlebot_")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(urdf)
        try:
            with quiet_output():   # the importer's notes go straight to the terminal
                return client.loadURDF(path, flags=URDF_FLAGS)
        except pybullet.error as err:
            raise UserError("pybullet could not load the URDF: %s" % err) from None
    finally:
        os.unlink(path)
