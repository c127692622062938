"""Single key presses from a terminal, with a timeout (POSIX termios; no ROS here)."""
import errno
import os
import select
import signal
import sys
import termios
import threading
import tty
from typing import Optional

from ..errors import UserError

# Signals whose default action ends the process without unwinding the stack (kill, a closed
# terminal window, Ctrl-\): they restore the terminal and unwind instead. (Ctrl-C raises
# KeyboardInterrupt, which unwinds anyway.)
FATAL_SIGNALS = (signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT)


class TerminalKeys:
    """Context manager that puts the terminal on ``stream`` (default stdin) in cbreak mode:
    each key arrives at once and is not echoed, while Ctrl-C still interrupts.

    The saved settings come back on leaving the block, whether normally, by an exception, or by
    one of FATAL_SIGNALS (whose previous Python handler then runs; with none, SystemExit).
    Raises UserError at construction when ``stream`` is not a terminal.
    """

    def __init__(self, stream=None):
        stream = sys.stdin if stream is None else stream
        try:
            fd = stream.fileno()
        except (AttributeError, ValueError, OSError):
            fd = None
        if fd is None or not os.isatty(fd):
            raise UserError("no terminal: standard input is not a tty, so there are no keys to "
                            "read; run it in a terminal (rosrun, or roslaunch in the foreground)")
        self._fd = fd
        self._saved = None
        self._previous = {}

    def __enter__(self) -> "TerminalKeys":
        self._saved = termios.tcgetattr(self._fd)
        if threading.current_thread() is threading.main_thread():
            for signum in FATAL_SIGNALS:
                previous = signal.getsignal(signum)
                if previous != signal.SIG_IGN:
                    self._previous[signum] = signal.signal(signum, self._on_signal)
        try:
            tty.setcbreak(self._fd, termios.TCSANOW)
        except termios.error:
            self.__exit__(*sys.exc_info())
            raise
        return self

    def __exit__(self, *exc_info) -> bool:
        try:
            self.restore()
        finally:
            for signum, previous in self._previous.items():
                signal.signal(signum, previous)
            self._previous.clear()
        return False

    def restore(self) -> None:
        """Put the saved settings back, dropping keys typed but not read (no-op on a terminal
        that has gone away)."""
        if self._saved is None:
            return
        try:
            termios.tcsetattr(self._fd, termios.TCSAFLUSH, self._saved)
        except termios.error:
            pass  # the terminal was closed (hang-up): there is nothing left to restore

    def read_key(self, timeout: float) -> Optional[str]:
        """The next key as a one-character string, or None if none came within ``timeout`` s
        (wall time). A key sending several bytes (arrows, non-ASCII) arrives as several keys.
        Raises EOFError when the terminal is closed."""
        ready, _, _ = select.select([self._fd], [], [], timeout)
        if not ready:
            return None
        try:
            data = os.read(self._fd, 1)
        except OSError as err:
            if err.errno != errno.EIO:  # EIO: the terminal (a pty's master side) went away
                raise
            data = b""
        if not data:
            raise EOFError("the terminal was closed")
        return data.decode("latin-1")

    def _on_signal(self, signum, frame) -> None:
        """Restore the terminal, then run the previous handler, or where there was none, exit
        with status 128 + signum by SystemExit, so that the program still cleans up (a robot
        node publishes its zero Twist)."""
        self.restore()
        previous = self._previous.get(signum)
        if callable(previous):
            previous(signum, frame)
        else:
            raise SystemExit(128 + signum)
