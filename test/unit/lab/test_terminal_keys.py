"""TerminalKeys on a real pseudo-terminal: keys one at a time with a timeout, the terminal's
settings restored on every way out (normal, exception, signals), and the no-terminal error, also
from the teleop_key script. No ROS master needed."""
import io
import os
import pty
import signal
import subprocess
import sys
import termios
import textwrap
import time

import pytest

from tutorial_turtlebot.errors import UserError
from tutorial_turtlebot.lab.terminal_keys import TerminalKeys
import unit_paths

ROOT = unit_paths.ROOT
LFLAG = 3  # index of the local modes in termios.tcgetattr()


@pytest.fixture
def terminal():
    """(master fd, slave file): a pseudo-terminal in its default (cooked) mode."""
    master, slave = pty.openpty()
    stream = os.fdopen(slave, "rb", buffering=0)
    yield master, stream
    stream.close()
    try:
        os.close(master)
    except OSError:
        pass  # a test closed it already


def test_cbreak_inside_restored_after(terminal):
    master, stream = terminal
    before = termios.tcgetattr(stream)
    assert before[LFLAG] & termios.ICANON and before[LFLAG] & termios.ECHO
    with TerminalKeys(stream):
        inside = termios.tcgetattr(stream)
        assert not inside[LFLAG] & termios.ICANON   # keys come one at a time ...
        assert not inside[LFLAG] & termios.ECHO     # ... unechoed
        assert inside[LFLAG] & termios.ISIG         # and Ctrl-C still interrupts
    assert termios.tcgetattr(stream) == before


def test_reads_single_keys_with_a_timeout(terminal):
    master, stream = terminal
    with TerminalKeys(stream) as keys:
        os.write(master, b"i, \x1b")
        assert [keys.read_key(1.0) for _ in range(4)] == ["i", ",", " ", "\x1b"]
        start = time.monotonic()
        assert keys.read_key(0.1) is None
        assert 0.09 <= time.monotonic() - start < 1.0


def test_restored_after_an_exception(terminal):
    master, stream = terminal
    before = termios.tcgetattr(stream)
    with pytest.raises(KeyboardInterrupt):
        with TerminalKeys(stream):
            raise KeyboardInterrupt
    assert termios.tcgetattr(stream) == before


def test_restored_before_a_signal_handler_runs(terminal):
    master, stream = terminal
    before = termios.tcgetattr(stream)
    seen = []

    def handler(signum, frame):
        seen.append((signum, termios.tcgetattr(stream) == before))
    previous = signal.signal(signal.SIGTERM, handler)
    try:
        with TerminalKeys(stream):
            os.kill(os.getpid(), signal.SIGTERM)
        assert seen == [(signal.SIGTERM, True)]
        assert signal.getsignal(signal.SIGTERM) is handler  # put back on leaving
    finally:
        signal.signal(signal.SIGTERM, previous)


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP])
def test_restored_and_unwound_when_a_signal_would_kill_the_process(terminal, signum):
    master, stream = terminal
    before = termios.tcgetattr(stream)
    child = textwrap.dedent("""
        import os, signal, sys, termios
        from tutorial_turtlebot.lab.terminal_keys import TerminalKeys
        signal.signal(%d, signal.SIG_DFL)   # (a child of nohup inherits SIGHUP ignored)
        try:
            with TerminalKeys(sys.stdin):
                assert not termios.tcgetattr(sys.stdin)[3] & termios.ICANON
                os.kill(os.getpid(), %d)
                print("not reached", flush=True)
        finally:
            print("cleaned up", flush=True)
    """ % (signum, signum))
    done = subprocess.run([sys.executable, "-c", child], stdin=stream, capture_output=True,
                          env=dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src")),
                          timeout=30, start_new_session=True)
    assert done.returncode == 128 + signum, done.stderr
    assert done.stdout == b"cleaned up\n"
    assert termios.tcgetattr(stream) == before


def test_closed_terminal_is_end_of_file(terminal):
    master, stream = terminal
    with TerminalKeys(stream) as keys:
        os.close(master)
        with pytest.raises(EOFError):
            keys.read_key(1.0)


def test_no_terminal_is_a_user_error():
    read_end, write_end = os.pipe()
    os.close(write_end)
    with io.StringIO("i") as text, open(os.devnull) as null, os.fdopen(read_end) as pipe:
        for stream in (text, null, pipe):
            with pytest.raises(UserError, match="no terminal"):
                TerminalKeys(stream)


def test_teleop_key_without_a_terminal():
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"),
               ROS_MASTER_URI="http://127.0.0.1:1")  # nothing there: it must not get that far
    done = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "teleop_key")],
                          stdin=subprocess.DEVNULL, capture_output=True, text=True, env=env,
                          timeout=30)
    assert done.returncode == 2
    assert done.stderr.startswith("teleop_key: no terminal")
    assert len(done.stderr.splitlines()) == 1
    assert "Traceback" not in done.stderr
