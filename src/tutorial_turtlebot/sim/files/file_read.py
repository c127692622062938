"""Reading a file a world or a robot names: a regular file only, and at most its kind's size.

A world, an ``<include>``, a model folder's model.config and SDF file, a URDF, a mesh and the
files a mesh names (an OBJ's ``mtllib`` and textures, a Collada's images) are read only if the
path, links followed, is a regular file: a FIFO or ``/dev/stdin`` would stop the simulation
for good, ``/dev/zero`` would fill its memory. Each kind of file is read up to its size below,
never further, whatever the file claims or grows to while it is read. Every refusal is one
line naming the file. No ROS and no pybullet here.
"""
import os
import stat
from typing import Optional, Type

from ...errors import UserError

# bytes; a model_xml of a spawn request is held to spawn_request.MAX_XML_BYTES (1 MB)
MAX_XML_FILE_BYTES = 16_000_000          # a world, SDF or URDF file (the house world: 82 kB)
MAX_MODEL_CONFIG_BYTES = 1_000_000       # a model folder's model.config
MAX_MESH_FILE_BYTES = 256_000_000        # a Collada, STL or OBJ file
MAX_MESH_SIDE_FILE_BYTES = 64_000_000    # a file a mesh names: materials, textures

_KINDS = ((stat.S_ISDIR, "a directory"), (stat.S_ISFIFO, "a FIFO"),
          (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
          (stat.S_ISSOCK, "a socket"))


def _kind(mode: int) -> Optional[str]:
    """None for a regular file; else "it is a FIFO, not a regular file" and the like."""
    if stat.S_ISREG(mode):
        return None
    kind = next((name for test, name in _KINDS if test(mode)), "something else")
    return "it is %s, not a regular file" % kind


def not_regular(path: str) -> Optional[str]:
    """Why ``path`` (links followed) is no regular file ("it is a FIFO, not a regular file",
    "No such file or directory"); None if it is one."""
    try:
        return _kind(os.stat(path).st_mode)
    except OSError as err:
        return err.strerror or "it cannot be looked at"


def read_file(path: str, limit: int, what: str, error: Type[UserError] = UserError) -> bytes:
    """The bytes of the regular file at ``path``, at most ``limit`` of them; ``error`` in one
    line ("<path>: cannot read <what>: <why>") for a file that does not exist or is not a
    regular file (a FIFO, a device, a directory), or is larger than ``limit``. Nothing that is
    not a regular file is opened."""
    why = not_regular(path)
    if why is None:
        try:   # O_NONBLOCK: a FIFO put in its place since the look above does not stop us
            fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_CLOEXEC", 0))
        except OSError as err:
            why = err.strerror
    if why is not None:
        raise error("%s: cannot read %s: %s" % (path, what, why))
    try:
        status = os.fstat(fd)
        why = _kind(status.st_mode)
        if why is None and status.st_size > limit:
            why = "it is %d bytes, more than the %d allowed" % (status.st_size, limit)
        chunks, size = [], 0
        while why is None:
            chunk = os.read(fd, min(1 << 20, limit + 1 - size))
            if not chunk:
                return b"".join(chunks)
            chunks.append(chunk)
            size += len(chunk)
            if size > limit:
                why = "it grew past the %d bytes allowed while it was read" % limit
    except OSError as err:
        why = err.strerror
    finally:
        os.close(fd)
    raise error("%s: cannot read %s: %s" % (path, what, why))
