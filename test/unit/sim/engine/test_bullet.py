"""quiet_output (engine/bullet.py): what C code writes to file descriptors 1 and 2 inside it
reaches neither the terminal nor pytest's fd capture, the context's value tells what was written,
and both descriptors work as before afterwards. No ROS master."""
import ctypes
import os
import subprocess
import sys
import time

import pytest

from tutorial_turtlebot.sim.engine.bullet import pybullet, quiet_output

LIBC = ctypes.CDLL(None)


def open_fds():
    return sorted(os.listdir("/proc/self/fd"))


def test_fd_1_and_2_are_silenced_and_told(capfd):
    capfd.readouterr()
    with quiet_output() as printed:
        os.write(1, b"raw to fd 1\n")
        os.write(2, b"raw to fd 2\n")
        LIBC.printf(b"C printf, buffered\n")        # stdio's buffer: flushed into the sink
        LIBC.write(2, b"C write to fd 2\n", 16)
    out, err = capfd.readouterr()
    assert "raw to fd" not in out + err and "C " not in out + err
    said = printed()
    for text in (b"raw to fd 1\n", b"raw to fd 2\n", b"C printf, buffered\n",
                 b"C write to fd 2\n"):
        assert text in said


def test_output_is_seen_again_afterwards(capfd):
    with quiet_output():
        os.write(1, b"hidden\n")
    os.write(1, b"seen on 1\n")
    os.write(2, b"seen on 2\n")
    LIBC.printf(b"printf seen\n")
    LIBC.fflush(None)
    out, err = capfd.readouterr()
    assert "hidden" not in out
    assert "seen on 1" in out and "printf seen" in out and "seen on 2" in err


def test_what_was_printed_so_far_while_inside():
    """The value tells what has been printed up to now, before the context ends (a caller waits
    on it for another thread's chatter)."""
    with quiet_output() as printed:
        assert printed() == b""
        os.write(1, b"first")
        deadline = time.monotonic() + 5.0
        while b"first" not in printed() and time.monotonic() < deadline:
            time.sleep(0.01)
        assert printed() == b"first"
        os.write(2, b" second")
    assert printed() == b"first second"


def test_descriptors_restored_and_closed_after_an_error(capfd):
    before = open_fds()
    with pytest.raises(RuntimeError):
        with quiet_output():
            os.write(1, b"lost\n")
            raise RuntimeError("inside")
    assert open_fds() == before                       # the sink and the copies are closed
    os.write(1, b"after the error\n")
    out, _ = capfd.readouterr()
    assert "after the error" in out and "lost" not in out


def test_megabytes_written_while_holding_the_gil_never_block():
    """A loader that prints more than a pipe holds (64 KB) while Python's GIL is held (as
    pybullet's does) must not wait for a reader: a child process writes 8 MB from C through
    ctypes' PyDLL (which keeps the GIL during the call) inside quiet_output, and ends."""
    code = ("import ctypes\n"
            "from tutorial_turtlebot.sim.engine.bullet import quiet_output\n"
            "libc = ctypes.PyDLL(None)\n"
            "block = b'\\t' * (1 << 20)\n"
            "with quiet_output() as printed:\n"
            "    for _ in range(8):\n"
            "        libc.write(1, block, len(block))\n"
            "    kept = len(printed())\n"
            "print('done', kept)\n")
    child = subprocess.run([sys.executable, "-c", code], stdin=subprocess.DEVNULL,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
    assert child.returncode == 0, child.stderr
    assert child.stdout.split() == [b"done", b"1048576"]     # KEPT_OUTPUT of it is kept


def test_pybullet_is_imported_without_its_build_date():
    """Imported first through this module, pybullet prints nothing (imported plainly, its C++
    code prints "pybullet build time: ..." to fd 1); the module re-exports it."""
    quiet = subprocess.run(
        [sys.executable, "-c", "from tutorial_turtlebot.sim.engine.bullet import pybullet; "
         "import sys; sys.exit(0 if hasattr(pybullet, 'loadURDF') else 5)"],
        stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
    assert quiet.returncode == 0, quiet.stderr
    assert b"build time" not in quiet.stdout + quiet.stderr
    plain = subprocess.run([sys.executable, "-c", "import pybullet"], stdin=subprocess.DEVNULL,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=60)
    assert b"build time" in plain.stdout + plain.stderr         # what is silenced
    assert pybullet.__name__ == "pybullet"
