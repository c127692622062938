"""pybullet, imported once for the whole package without the build-date line its C++ code
prints on import; and a way to silence what its loaders print straight to the terminal."""
import contextlib
import ctypes
import os
import threading

_LIBC = ctypes.CDLL(None)


@contextlib.contextmanager
def quiet_output():
    """Silence what pybullet's C++ code prints straight to file descriptors 1 and 2 (its build
    date, the URDF importer's notes, the EGL plugin's GL version); Python's own output is
    unaffected afterwards. The context's value is a function that tells what was printed so
    far (bytes), for a caller that must wait for another thread's chatter to end."""
    saved = []
    read_end, write_end = os.pipe()
    printed = bytearray()

    def drain():
        while True:
            chunk = os.read(read_end, 65536)
            if not chunk:
                return
            if len(printed) < 1 << 20:           # what it says, not kept without end
                printed.extend(chunk)
    reader = threading.Thread(target=drain, name="quiet_output", daemon=True)
    reader.start()
    try:
        for fd in (1, 2):
            saved.append((fd, os.dup(fd)))
            os.dup2(write_end, fd)

        def so_far() -> bytes:
            _LIBC.fflush(None)
            return bytes(printed)
        yield so_far
    finally:
        _LIBC.fflush(None)  # what C buffered goes to the pipe too
        for fd, copy in saved:
            os.dup2(copy, fd)
            os.close(copy)
        os.close(write_end)
        reader.join(5.0)
        os.close(read_end)


with quiet_output():
    import pybullet  # noqa: E402,F401  (re-exported)
