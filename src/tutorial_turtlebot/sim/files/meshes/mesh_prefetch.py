"""A world's meshes read ahead, in parallel, before the world is read: the first start of a world
of many meshes fills the disk cache (mesh_cache) in one process a core, and the world's reading
then finds them there. No ROS and no pybullet here.

``convert_world`` reads the world once with load_mesh noting the files it is asked for
(mesh_file.noting), ``convert_ahead`` reads those not in the cache yet in a pool of fresh
Python processes (``_worker``), and the failures they met are kept for load_mesh to raise
(mesh_file.note_failure), so that a bad file gives the same one line as without the pool.
"""
import json
import os
import subprocess
import sys
import tempfile
from typing import Callable, Dict, Iterable, List, Optional

from .. import file_read
from . import mesh_cache, mesh_file
from .mesh_types import MeshError

# A pool starts only for at least this many meshes to convert: a worker costs about 0.2 s of
# CPU to start (a fresh Python importing numpy), the time to read a few small meshes.
MIN_POOL_FILES = 4


def _convert(items) -> Dict[str, List[str]]:
    """Read each (path, [scale]) of ``items`` into the cache, and write the OBJ files of each
    scale as a visual drawn in the file's own colours and textures would need them (a visual
    with an SDF <material>, or a collision, makes no use of them: they are written when built).
    Returns path -> [error class name, line] of the files that could not be read."""
    failed = {}
    for path, scales in items:
        try:
            mesh_file.load_mesh(path)
        except MeshError as err:
            failed[path] = [type(err).__name__, str(err)]
            continue
        except Exception:   # the world's reading meets it again and names it
            continue
        for scale in scales:
            try:
                mesh = mesh_file.load_mesh(path, scale)
                full = {p.texture: 0 for p in mesh.parts if p.texture is not None}
                with tempfile.TemporaryDirectory() as folder:
                    mesh_cache.visual_obj_parts(mesh, folder, full if full else None)
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
            entry = mesh_cache.entry_path(path, mesh_cache.file_digest(path))
        except OSError:
            continue   # missing or unreadable: its reading says so
        if not os.path.isfile(entry):
            todo.append(path)
    workers = workers or os.cpu_count() or 1
    if len(todo) < MIN_POOL_FILES or workers < 2:
        return {}
    # the folder that holds tutorial_turtlebot/ (this file is tutorial_turtlebot/sim/files/meshes/)
    package_root = os.path.abspath(os.path.join(os.path.dirname(__file__), *[os.pardir] * 4))
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
                [sys.executable, "-c", "from tutorial_turtlebot.sim.files.meshes.mesh_prefetch "
                 "import _worker; _worker()"],
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
    with mesh_file.noting() as paths:
        try:
            read()
        except Exception:   # noqa: BLE001 - the real reading meets it and names it
            pass
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
            mesh_file.note_failure((os.path.realpath(path), st.st_mtime_ns, st.st_size),
                                   failure)
