"""pybullet, imported once for the whole package without the build-date line its C++ code
prints on import; and a way to silence what its loaders print straight to the terminal."""
import contextlib
import ctypes
import os

_LIBC = ctypes.CDLL(None)


@contextlib.contextmanager
def quiet_output():
    """Silence what pybullet's C++ code prints straight to file descriptors 1 and 2 (its build
    date, the URDF importer's notes, the EGL plugin's GL version); Python's own output is
    unaffected afterwards."""
    saved = []
    try:
        with open(os.devnull, "w") as null:
            for fd in (1, 2):
                saved.append((fd, os.dup(fd)))
                os.dup2(null.fileno(), fd)
            yield
    finally:
        _LIBC.fflush(None)  # what C buffered goes to /dev/null too
        for fd, copy in saved:
            os.dup2(copy, fd)
            os.close(copy)


with quiet_output():
    import pybullet  # noqa: E402,F401  (re-exported)
