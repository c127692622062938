"""The files a mesh names (an OBJ's ``mtllib`` and textures, a Collada's images), read through
file_read, and the log of every file read while one mesh is read (the disk cache, mesh_cache,
checks them again before it gives that mesh back). No ROS and no pybullet here.
"""
import contextlib
import hashlib
import os
import threading
from typing import Dict, Iterator, List, Optional, Tuple

from ....errors import UserError
from .. import file_read
from ..file_read import MAX_MESH_SIDE_FILE_BYTES
from .mesh_types import MeshError

# File name endings of images: an OBJ's map_Kd is read by texture_images, not by trimesh.
IMAGE_SUFFIXES = (".png", ".jpg", ".jpeg", ".tga", ".bmp", ".gif", ".tif", ".tiff", ".dds",
                  ".psd", ".hdr", ".exr", ".webp")

_reads = threading.local()   # .log: [(real path, sha256)] of the files read, while logging


@contextlib.contextmanager
def read_log() -> Iterator[List[Tuple[str, str]]]:
    """While in it, every ``read_file`` of this thread is noted as (real path, sha256 hex) in
    the list it gives."""
    _reads.log = log = []
    try:
        yield log
    finally:
        _reads.log = None


def read_file(path: str, limit: int, what: str, error=UserError) -> bytes:
    """file_read.read_file, noting the file in the ``read_log`` of this thread, if any."""
    data = file_read.read_file(path, limit, what, error)
    log = getattr(_reads, "log", None)
    if log is not None:
        log.append((os.path.realpath(path), hashlib.sha256(data).hexdigest()))
    return data


class SideFiles:
    """The files a mesh names, read beside it (the name as written, else its last part, as
    trimesh looks) through ``read_file``. One that is missing is left out (a mesh without its
    colours, as in Gazebo); the first one refused is kept in ``refused`` (trimesh swallows what
    a resolver raises)."""

    def __init__(self, mesh_path: str):
        self.mesh_path = mesh_path
        self.folder = os.path.dirname(mesh_path)
        self.refused: Optional[str] = None
        self.texts: Dict[str, bytes] = {}   # name as asked -> bytes, of the files read

    def read(self, name: str) -> bytes:
        for candidate in (name.strip(), os.path.basename(name.strip())):
            path = os.path.normpath(os.path.join(self.folder, candidate))
            if candidate and os.path.lexists(path):
                try:
                    data = read_file(path, MAX_MESH_SIDE_FILE_BYTES, "a file the mesh names",
                                     MeshError)
                    self.texts[name] = data
                    return data
                except MeshError as err:
                    self.refused = self.refused or str(err)
                    raise
        raise FileNotFoundError(name)
