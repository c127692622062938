"""pybullet, imported once for the whole package without the build-date line its C++ code
prints on import; and a way to silence what its loaders print straight to the terminal."""
import contextlib
import ctypes
import os
import tempfile

_LIBC = ctypes.CDLL(None)
KEPT_OUTPUT = 1 << 20    # bytes of what was printed that ``so_far`` gives back, at most


@contextlib.contextmanager
def quiet_output():
    """Silence what pybullet's C++ code prints straight to file descriptors 1 and 2 (its build
    date, the URDF importer's notes, the EGL plugin's GL version); Python's own output is
    unaffected afterwards. The context's value is a function that tells what was printed so
    far (bytes, the first KEPT_OUTPUT of them), for a caller that must wait for another
    thread's chatter to end.

    The output goes to an unlinked temporary file, never to a pipe: a write to a file does not
    wait for a reader. (A pipe needs a thread to drain it, which needs Python's GIL, which
    pybullet holds while it loads: a URDF of a 400-link chain, whose importer prints a tab per
    level of depth, filled a pipe's 64 KB and the sim froze for good.)"""
    saved = []
    sink = tempfile.TemporaryFile(prefix="tutorial_turtlebot_output_")
    final = []   # what was printed, once the context has ended
    try:
        _LIBC.fflush(None)   # what C buffered before goes where it was going
        for fd in (1, 2):
            saved.append((fd, os.dup(fd)))
            os.dup2(sink.fileno(), fd)

        def so_far() -> bytes:
            if final:
                return final[0]
            _LIBC.fflush(None)
            return os.pread(sink.fileno(), KEPT_OUTPUT, 0)
        yield so_far
    finally:
        _LIBC.fflush(None)  # what C buffered goes to the file too
        for fd, copy in saved:
            os.dup2(copy, fd)
            os.close(copy)
        final.append(os.pread(sink.fileno(), KEPT_OUTPUT, 0))
        sink.close()


with quiet_output():
    import pybullet  # noqa: E402
REEXPORTED = (pybullet,)  # imported from here by the engine's modules, quietly imported once
