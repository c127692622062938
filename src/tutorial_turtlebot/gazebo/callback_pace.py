"""At most so many messages a second from each connection of a subscribed topic: the sleep that
keeps a flooding publisher from taking the loop's time.

rospy reads each publisher's connection in a thread of its own and runs the callback there; a
publisher that sends as fast as it can keeps that thread busy, holding Python's GIL between its
reads, and three of them left the loop a fraction of it (sim time fell to 0.8 of wall time with
the requests already bounded). ``CallbackPace.wait()``, called first in a callback, sleeps (the
GIL released) until 1 / max_rate s have passed since that thread's last message: the thread
reads no faster, TCP holds the rest back, and rospy's publisher drops what its queue cannot
hold, as it does for any slow subscriber.
"""
import threading
import time
from typing import Callable

MAX_RATE = 1000.0   # messages per wall second from one connection


class CallbackPace:
    """Per-thread (per-connection) pacing of a topic callback; ``clock()`` in s, ``sleep(s)``."""

    def __init__(self, max_rate: float = MAX_RATE,
                 clock: Callable[[], float] = time.monotonic,
                 sleep: Callable[[float], None] = time.sleep):
        self.period = 1.0 / max_rate
        self._clock, self._sleep = clock, sleep
        self._last = threading.local()

    def wait(self) -> None:
        """Sleep until this thread's last message is a period old; note this one."""
        now = self._clock()
        last = getattr(self._last, "at", None)
        if last is not None and now - last < self.period:
            self._sleep(self.period - (now - last))
            now = self._clock()
        self._last.at = now
