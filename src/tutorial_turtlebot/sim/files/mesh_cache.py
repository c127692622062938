"""Converted meshes kept on disk, so that a world's meshes are read once, not at every start.

No ROS and no pybullet here. An entry is one ``.npz`` file (numpy arrays and a JSON header,
no pickle) holding a file's ``mesh_file.Mesh`` as read, unscaled. Its name is a digest of
the converter's own source (mesh_file.py and this file: any change of them is a new cache),
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
read from its file, and one line on stderr says so, once per process.

``obj_parts`` keeps the Wavefront files of mesh_file.write_obj_parts the same way (a folder an
entry, by a digest of the mesh's content), so that pybullet reads files written once.

``convert_ahead`` converts the meshes a world names in a process pool of one worker a core
before the world is read, filling the cache; the world's reading then finds them there.
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

from . import file_read

MAX_CACHE_BYTES = 1024 ** 3      # 1 GiB of entries and OBJ folders, least recently used out
FORMAT = 1                       # the header's "format"
# A pool starts only for at least this many meshes to convert: a worker costs about 0.2 s of
# CPU to start (a fresh Python importing numpy), the time to read a few small meshes.
MIN_POOL_FILES = 4

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


def warn_once(message: str) -> None:
    """One line on stderr, the first time only."""
    global _warned
    with _lock:
        if _warned:
            return
        _warned = True
    sys.stderr.write("tutorial_turtlebot: mesh cache %s: %s; meshes are read from their "
                     "files\n" % (cache_dir(), " ".join(str(message).split())[:200]))


def converter_digest() -> str:
    """sha256 of the source of mesh_file.py and mesh_cache.py (the converter)."""
    global _converter
    if _converter is None:
        from . import mesh_file
        h = hashlib.sha256(b"tutorial_turtlebot mesh cache %d\0" % FORMAT)
        for module in (mesh_file.__file__, __file__):
            with open(module, "rb") as f:
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
    from . import mesh_file
    if isinstance(value, dict):
        if "array" in value:
            array = arrays["a%d" % value["array"]]
            array.setflags(write=False)
            return array
        if "tuple" in value:
            return tuple(_decode(v, arrays) for v in value["tuple"])
        cls = {"Mesh": mesh_file.Mesh, "MeshPart": mesh_file.MeshPart}[value["class"]]
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

def load(path: str, digest: str):
    """The Mesh stored for the file ``path`` of sha256 ``digest``, or None (not there, stale,
    or unreadable: then one warning)."""
    entry = os.path.join(cache_dir(), _entry_name(path, digest) + ".npz")
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
    """``write(mesh, folder)``'s answer (mesh_file.write_obj_parts: [(file, rgba)]) for files
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
    _failures.clear()


# --- converting a world's meshes ahead, in parallel ---------------------------------------------

def visual_obj_parts(mesh, directory: str, textured: bool) -> List[Tuple[str, Optional[tuple]]]:
    """``obj_parts`` of a visual mesh, drawn with its textures or not (world_bullet)."""
    from .mesh_file import write_obj_parts
    return obj_parts(mesh, directory, lambda m, d: write_obj_parts(m, d, textures=textured),
                     options=["textures", bool(textured)])


def _convert(items) -> Dict[str, List[str]]:
    """Read each (path, [scale]) of ``items`` into the cache, and write the OBJ files of each
    scale as a visual drawn in the file's own colours and textures would need them (a visual
    with an SDF <material>, or a collision, makes no use of them: they are written when built).
    Returns path -> [error class name, line] of the files that could not be read."""
    from . import mesh_file
    failed = {}
    for path, scales in items:
        try:
            mesh_file.load_mesh(path)
        except mesh_file.MeshError as err:
            failed[path] = [type(err).__name__, str(err)]
            continue
        except Exception:   # the world's reading meets it again and names it
            continue
        for scale in scales:
            try:
                mesh = mesh_file.load_mesh(path, scale)
                textured = any(getattr(p, "texture", None) is not None for p in mesh.parts)
                with tempfile.TemporaryDirectory() as folder:
                    visual_obj_parts(mesh, folder, textured)
            except Exception:   # a scale refused, no OBJ: the world's building meets it
                continue
    return failed


def _worker() -> None:
    """A pool worker (``python3 -c``): reads a JSON list of mesh files on stdin, reads each
    into the cache, writes a JSON object of path -> [error class name, line] of those that
    failed on stdout."""
    sys.stdout.write(json.dumps(_convert(json.loads(sys.stdin.read()))))


def _shares(paths: List[str], count: int) -> List[List[str]]:
    """``paths`` in ``count`` lists of about the same bytes, the biggest file first."""
    shares: List[List[str]] = [[] for _ in range(count)]
    loads = [0] * count
    for path in sorted(paths, key=lambda p: -os.path.getsize(p)):
        least = loads.index(min(loads))
        shares[least].append(path)
        loads[least] += os.path.getsize(path)
    return [share for share in shares if share]


def convert_ahead(paths: Iterable[str], workers: Optional[int] = None,
                  scales: Optional[Dict[str, list]] = None) -> Dict[str, tuple]:
    """Read the mesh files ``paths`` not in the cache yet into it, in ``workers`` processes
    (default: one a core): this one and new ones, each a fresh Python (no fork of a process
    with threads), the files shared out by size; with the OBJ files of ``scales[path]``
    (scales the world uses the file at) as ``_convert`` says. Returns
    path -> (error class name, line) of the files that failed (load_mesh raises those
    again). Fewer than MIN_POOL_FILES files to read, or one core: nothing is done here (the
    world's reading reads them one by one)."""
    todo = []
    for path in dict.fromkeys(paths):
        try:
            entry = os.path.join(cache_dir(), _entry_name(path, file_digest(path)) + ".npz")
        except OSError:
            continue   # missing or unreadable: its reading says so
        if not os.path.isfile(entry):
            todo.append(path)
    workers = workers or os.cpu_count() or 1
    if len(todo) < MIN_POOL_FILES or workers < 2:
        return {}
    import subprocess
    package_root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [package_root] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]))
    procs = []
    failed: Dict[str, tuple] = {}
    scales = scales or {}
    own, *shares = [[(path, scales.get(path, [])) for path in share]   # this process reads
                    for share in _shares(todo, min(workers, len(todo)))]   # a share too
    try:
        for share in shares:
            proc = subprocess.Popen(
                [sys.executable, "-c",
                 "from tutorial_turtlebot.sim.files.mesh_cache import _worker; _worker()"],
                stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                env=env)
            proc.stdin.write(json.dumps(share).encode("utf-8"))
            proc.stdin.close()
            procs.append(proc)
        failed.update((k, tuple(v)) for k, v in _convert(own).items())
        for proc in procs:
            out = proc.stdout.read()
            proc.wait()
            try:
                failed.update((k, tuple(v)) for k, v in json.loads(out or b"{}").items())
            except (ValueError, TypeError, AttributeError):
                pass   # a worker that died: the world's reading reads its files
    except OSError:
        pass           # no process could start: the same
    finally:
        for proc in procs:
            if proc.poll() is None:
                proc.kill()
                proc.wait()
    return failed


# --- noting a world's meshes --------------------------------------------------------------------

_noting = threading.local()


def noted_paths() -> Optional[list]:
    """While ``convert_world`` reads a world first: the list load_mesh notes (file, scale) in
    (and reads nothing); else None."""
    return getattr(_noting, "paths", None)


def convert_world(read: Callable[[], object], path: Optional[str] = None) -> None:
    """Call ``read()`` (a world's reading) with load_mesh noting the mesh files it is asked
    for instead of reading them (its errors are left to the real reading), then
    ``convert_ahead`` them; their failures are kept for load_mesh to raise. Nothing is done
    if the world file ``path`` names no ``<mesh>`` and no ``<include>``."""
    if path is not None:
        if file_read.not_regular(path) is not None:
            return     # a FIFO would hang here; the real reading refuses it
        try:
            with open(path, "rb") as f:
                text = f.read(file_read.MAX_XML_FILE_BYTES)
            if b"<mesh" not in text and b"<include" not in text:
                return
        except OSError:
            return     # the real reading names the fault
    _noting.paths = paths = []
    try:
        read()
    except Exception:
        pass
    finally:
        _noting.paths = None
    if paths:
        scales: Dict[str, list] = {}
        for path, scale in paths:
            if list(scale) not in scales.setdefault(path, []):
                scales[path].append(list(scale))
        for path, failure in convert_ahead(list(scales), scales=scales).items():
            try:
                st = os.stat(path)
            except OSError:
                continue
            _failures[(os.path.realpath(path), st.st_mtime_ns, st.st_size)] = failure


_failures: Dict[tuple, Tuple[str, str]] = {}


def failure(file_key: tuple) -> Optional[Tuple[str, str]]:
    """(error class name, line) a pool worker met reading the file of ``file_key`` ((real
    path, mtime ns, size)), once; None if none."""
    return _failures.pop(file_key, None)
