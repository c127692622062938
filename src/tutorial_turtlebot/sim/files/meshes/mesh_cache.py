"""Converted meshes kept on disk, so that a world's meshes are read once, not at every start.

No ROS and no pybullet here. An entry is one ``.npz`` file (numpy arrays and a JSON header,
no pickle) holding a file's ``mesh_types.Mesh`` as read, unscaled. Its name is a digest of
the converter's own source (CONVERTER_SOURCES: any change of them is a new cache),
the mesh file's real path and the sha256 of its bytes; the header lists every file the reader
read beside it (an OBJ's .mtl, a Collada's images) with the sha256 of its bytes, any file a
part names (a texture) the same way, and the names in the mesh's folder (a texture that was
missing and is now there), all checked at every hit. The Mesh and its parts are stored
field by field, whatever their fields are (arrays, strings, None, numbers, tuples).

Where: ``$ROS_HOME/tutorial_turtlebot/mesh_cache``, else
``${XDG_CACHE_HOME:-~/.cache}/tutorial_turtlebot/mesh_cache``. At most MAX_CACHE_BYTES in all,
the entries used least recently removed first (a hit renews an entry's time). Files are
written to a temporary name and renamed, so that a reader never sees half an entry. A cache
that is corrupt, truncated, of another version or not writable never fails a load: the mesh is
read from its file, and one line (``warning_sink``: stderr, or the node's log) says so, once
per process.

``obj_parts`` keeps the Wavefront files of obj_writer.write_obj_parts the same way (a folder an
entry, by a digest of the mesh's content), so that pybullet reads files written once;
``visual_obj_parts`` those of a visual, its textures halved as the texture budget says.
mesh_prefetch fills the cache with a world's meshes before the world is read.
"""
import dataclasses
import hashlib
import json
import os
import shutil
import sys
import tempfile
import threading
from typing import Callable, Dict, Iterable, List, Optional, Sequence, Tuple

import numpy as np

from .mesh_types import Mesh, MeshPart
from .obj_writer import texture_copy, write_obj_parts

MAX_CACHE_BYTES = 1024 ** 3      # 1 GiB of entries and OBJ folders, least recently used out
MAX_WARNING_CHARS = 200          # a warning line is at most this long
FORMAT = 1                       # the header's "format"

_lock = threading.RLock()
_warned = False
_total: Optional[int] = None     # bytes in the cache, known after the first store
_digests: Dict[tuple, str] = {}  # (real path, mtime ns, size) -> sha256 of the bytes
_converter: Optional[str] = None


def cache_dir(environ=os.environ) -> str:
    """The cache folder (not made here)."""
    ros_home = environ.get("ROS_HOME")
    if ros_home:
        base = ros_home
    else:
        base = environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "tutorial_turtlebot", "mesh_cache")


def _to_stderr(line: str) -> None:
    sys.stderr.write("tutorial_turtlebot: %s\n" % line)


# Where warn_once's line goes: stderr, unless the process says otherwise (the /gazebo node:
# rospy's log).
warning_sink: Callable[[str], None] = _to_stderr


def warn_once(message: str) -> None:
    """One line (at most MAX_WARNING_CHARS characters) to ``warning_sink``, the first time
    only."""
    global _warned
    with _lock:
        if _warned:
            return
        _warned = True
    head = "mesh cache %s: " % cache_dir()
    tail = "; meshes are read from their files"
    room = max(MAX_WARNING_CHARS - len(head) - len(tail), 40)
    text = " ".join(str(message).split())
    warning_sink(head + (text if len(text) <= room else text[:room - 3] + "...") + tail)


# The modules whose code makes a cached Mesh or OBJ file (any change of them is a new cache).
CONVERTER_SOURCES = ("mesh_types.py", "mesh_file.py", "mesh_lru.py", "mesh_side_files.py",
                     "collada_reader.py", "stl_obj_reader.py", "texture_images.py",
                     "obj_writer.py", "mesh_cache.py")


def converter_digest() -> str:
    """sha256 of the source of the converter (CONVERTER_SOURCES, beside this file)."""
    global _converter
    if _converter is None:
        h = hashlib.sha256(b"tutorial_turtlebot mesh cache %d\0" % FORMAT)
        here = os.path.dirname(os.path.abspath(__file__))
        for name in CONVERTER_SOURCES:
            with open(os.path.join(here, name), "rb") as f:
                h.update(f.read())
            h.update(b"\0")
        _converter = h.hexdigest()
    return _converter


def file_digest(path: str, data: Optional[bytes] = None) -> str:
    """sha256 (hex) of a file's bytes, remembered for its (real path, mtime, size)."""
    st = os.stat(path)
    key = (os.path.realpath(path), st.st_mtime_ns, st.st_size)
    digest = _digests.get(key)
    if digest is None:
        if data is None:
            with open(path, "rb") as f:
                data = f.read()
        digest = _digests[key] = hashlib.sha256(data).hexdigest()
    return digest


def _entry_name(path: str, digest: str) -> str:
    h = hashlib.sha256()
    for text in (converter_digest(), os.path.realpath(path), digest):
        h.update(text.encode("utf-8", "surrogateescape") + b"\0")
    return h.hexdigest()


# --- the Mesh, field by field -----------------------------------------------------------------

def _encode(value, arrays: List[np.ndarray]):
    """JSON of a field value; arrays go to ``arrays``."""
    if isinstance(value, np.ndarray):
        arrays.append(np.ascontiguousarray(value))
        return {"array": len(arrays) - 1}
    if dataclasses.is_dataclass(value):
        return {"class": type(value).__name__,
                "fields": {f.name: _encode(getattr(value, f.name), arrays)
                           for f in dataclasses.fields(value)}}
    if isinstance(value, (tuple, list)):
        return {"tuple": [_encode(v, arrays) for v in value]}
    if isinstance(value, np.generic):
        return value.item()
    if value is None or isinstance(value, (str, bool, int, float)):
        return value
    raise TypeError("cannot store a %s" % type(value).__name__)


def _decode(value, arrays):
    if isinstance(value, dict):
        if "array" in value:
            array = arrays["a%d" % value["array"]]
            array.setflags(write=False)
            return array
        if "tuple" in value:
            return tuple(_decode(v, arrays) for v in value["tuple"])
        cls = {"Mesh": Mesh, "MeshPart": MeshPart}[value["class"]]
        return cls(**{k: _decode(v, arrays) for k, v in value["fields"].items()})
    return value


def _named_files(mesh) -> List[str]:
    """Files a stored mesh's parts name by path (a texture): checked at every hit."""
    out = []
    for part in mesh.parts:
        for field in dataclasses.fields(part):
            value = getattr(part, field.name)
            if isinstance(value, str) and value and os.path.isfile(value):
                out.append(value)
    return out


def _listings(path: str) -> Dict[str, Optional[List[str]]]:
    """The names in the folders a reader looks for a mesh's side files in (the mesh's own, and
    a model folder's materials/textures): a file added there (a missing texture or .mtl put
    in place) makes a cached mesh stale."""
    folder = os.path.dirname(os.path.realpath(path))
    out: Dict[str, Optional[List[str]]] = {}
    for place in (folder, os.path.join(os.path.dirname(folder), "materials", "textures")):
        try:
            out[place] = sorted(os.listdir(place))
        except OSError:
            out[place] = None
    return out


def _side_ok(side: Sequence) -> bool:
    for path, digest in side:
        try:
            if file_digest(path) != digest:
                return False
        except OSError:
            return False
    return True


# --- entries ----------------------------------------------------------------------------------

def entry_path(path: str, digest: str) -> str:
    """The entry of the mesh file ``path`` of sha256 ``digest`` (it may not exist)."""
    return os.path.join(cache_dir(), _entry_name(path, digest) + ".npz")


def load(path: str, digest: str):
    """The Mesh stored for the file ``path`` of sha256 ``digest``, or None (not there, stale,
    or unreadable: then one warning)."""
    entry = entry_path(path, digest)
    try:
        with np.load(entry, allow_pickle=False) as npz:
            header = json.loads(bytes(npz["header"]).decode("utf-8"))
            if header.get("format") != FORMAT or header.get("converter") != converter_digest():
                return None
            if not _side_ok(header["side_files"]) or header["folders"] != _listings(path):
                return None
            arrays = {name: npz[name] for name in npz.files if name != "header"}
        mesh = _decode(header["mesh"], arrays)
        mesh = dataclasses.replace(mesh, path=path)
    except FileNotFoundError:
        return None
    except Exception as err:   # truncated, corrupt, foreign: read the file instead
        warn_once("%s: %s" % (os.path.basename(entry), err))
        _remove(entry)
        return None
    _touch(entry)
    return mesh


def store(path: str, digest: str, mesh, side_files: Iterable[Tuple[str, str]]) -> None:
    """Keep ``mesh`` (read from ``path``) with the side files it was read with ((path,
    sha256) pairs); a failure is one warning, nothing else."""
    try:
        side = dict(side_files)
        for named in _named_files(mesh):
            side.setdefault(named, file_digest(named))
        side.pop(os.path.realpath(path), None)
        side.pop(path, None)
        arrays: List[np.ndarray] = []
        header = {"format": FORMAT, "converter": converter_digest(), "source": path,
                  "side_files": sorted(side.items()), "folders": _listings(path),
                  "mesh": _encode(mesh, arrays)}
        folder = _made_dir()
        entry = os.path.join(folder, _entry_name(path, digest) + ".npz")
        fd, temp = tempfile.mkstemp(prefix=".tmp-", suffix=".npz", dir=folder)
        try:
            with os.fdopen(fd, "wb") as f:
                np.savez(f, header=np.frombuffer(json.dumps(header).encode("utf-8"),
                                                 dtype=np.uint8),
                         **{"a%d" % i: a for i, a in enumerate(arrays)})
            size = os.path.getsize(temp)
            os.replace(temp, entry)
        except BaseException:
            _remove(temp)
            raise
        _added(size)
    except Exception as err:
        warn_once(err)


def obj_parts(mesh, directory: str, write: Callable,
              options=()) -> List[Tuple[str, Optional[tuple]]]:
    """``write(mesh, folder)``'s answer (obj_writer.write_obj_parts: [(file, rgba)]) for files
    kept in the cache, written once for the mesh's content and ``options`` (what else ``write``
    depends on: JSON values); in ``directory`` if the cache cannot be used."""
    try:
        arrays: List[np.ndarray] = []
        header = json.dumps([_encode(dataclasses.replace(mesh, path=""), arrays), options],
                            sort_keys=True)
        h = hashlib.sha256((converter_digest() + "obj\0" + os.path.basename(mesh.path)
                            + "\0" + header).encode("utf-8", "surrogateescape"))
        for a in arrays:
            h.update(str((a.dtype.str, a.shape)).encode() + a.tobytes())
        for named in _named_files(mesh):
            h.update(file_digest(named).encode())
        folder = os.path.join(_made_dir(), "obj", h.hexdigest())
        parts = _listed(folder)
        if parts is not None:
            _touch(folder)
            return parts
        temp = tempfile.mkdtemp(prefix=".tmp-", dir=os.path.dirname(folder))
        try:
            written = write(mesh, temp)
            names = [os.path.relpath(p, temp) for p, _ in written]
            with open(os.path.join(temp, "parts.json"), "w") as f:
                json.dump([[n, None if rgba is None else list(rgba)]
                           for n, (_, rgba) in zip(names, written)], f)
            size = _tree_size(temp)
            try:
                os.replace(temp, folder)       # fails if another process made it meanwhile
            except OSError:
                parts = _listed(folder)
                if parts is None:
                    raise
                shutil.rmtree(temp, ignore_errors=True)
                return parts
        except BaseException:
            shutil.rmtree(temp, ignore_errors=True)
            raise
        _added(size)
        return [(os.path.join(folder, n), rgba) for n, (_, rgba) in zip(names, written)]
    except Exception as err:
        warn_once(err)
        return write(mesh, directory)


def _listed(folder: str) -> Optional[List[Tuple[str, Optional[tuple]]]]:
    """The [(file, rgba)] an OBJ folder of the cache lists, if it and its files are there."""
    try:
        with open(os.path.join(folder, "parts.json")) as f:
            parts = [(os.path.join(folder, name), None if rgba is None else tuple(rgba))
                     for name, rgba in json.load(f)]
    except (OSError, ValueError, TypeError):
        return None
    return parts if all(os.path.isfile(p) for p, _ in parts) else None


# --- the folder -------------------------------------------------------------------------------

def _made_dir() -> str:
    folder = cache_dir()
    os.makedirs(os.path.join(folder, "obj"), exist_ok=True)
    return folder


def _remove(path: str) -> None:
    try:
        if os.path.isdir(path) and not os.path.islink(path):
            shutil.rmtree(path, ignore_errors=True)
        else:
            os.unlink(path)
    except OSError:
        pass


def _touch(path: str) -> None:
    """Mark ``path`` used now (the least recently used go first)."""
    try:
        os.utime(path)
    except OSError:
        pass


def _tree_size(path: str) -> int:
    if not os.path.isdir(path):
        return os.path.getsize(path)
    return sum(os.path.getsize(os.path.join(d, f)) for d, _, files in os.walk(path)
               for f in files)


def _entries() -> List[Tuple[float, int, str]]:
    """(time last used, bytes, path) of every entry and OBJ folder."""
    folder = cache_dir()
    out = []
    for base in (folder, os.path.join(folder, "obj")):
        try:
            names = os.listdir(base)
        except OSError:
            continue
        for name in names:
            path = os.path.join(base, name)
            if name == "obj" and base == folder:
                continue
            try:
                out.append((os.stat(path).st_mtime, _tree_size(path), path))
            except OSError:
                continue
    return out


def _added(size: int) -> None:
    """Count ``size`` new bytes; beyond MAX_CACHE_BYTES remove the least recently used."""
    global _total
    with _lock:
        if _total is None:
            _total = sum(s for _, s, _ in _entries())
        else:
            _total += size
        if _total <= MAX_CACHE_BYTES:
            return
        entries = sorted(_entries())
        _total = sum(s for _, s, _ in entries)
        for _, size_of, path in entries:
            if _total <= MAX_CACHE_BYTES:
                break
            _remove(path)
            _total -= size_of


def clear() -> None:
    """Remove the whole cache folder (as ``rm -r`` of it would)."""
    global _total
    shutil.rmtree(cache_dir(), ignore_errors=True)
    _total = None
    _digests.clear()


def forget_state() -> None:
    """Forget what this process knows of the cache (for tests)."""
    global _total, _warned, _converter
    _total, _warned, _converter = None, False, None
    _digests.clear()


# --- visuals ------------------------------------------------------------------------------------

def visual_obj_parts(mesh, directory: str, halvings: Optional[Dict[str, int]] = None
                     ) -> List[Tuple[str, Optional[tuple]]]:
    """``obj_parts`` of a visual mesh (world_bullet): without textures for ``halvings`` None,
    else with each texture of ``halvings`` (texture path -> times halved: the texture budget,
    rendering.plan_textures), the others left out."""
    if halvings is None:
        return obj_parts(mesh, directory, lambda m, d: write_obj_parts(m, d, textures=False),
                         options=["textures", False])

    def write(m, folder):
        copies: Dict[str, Optional[str]] = {}    # texture -> its image file in folder

        def images(texture):
            if texture not in copies:
                copies[texture] = (texture_copy(texture, folder, halvings[texture])
                                   if texture in halvings else None)
            return copies[texture]
        return write_obj_parts(m, folder, images=images)
    drawn = [halvings.get(part.texture) if part.texture else None for part in mesh.parts]
    return obj_parts(mesh, directory, write, options=["halvings", drawn])
