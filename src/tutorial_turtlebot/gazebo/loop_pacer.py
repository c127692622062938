"""When the /gazebo loop's next step may run against the wall clock, and its sleeps until then.

``LoopPacer`` is sim/world/pacing's ``Pacer`` (the real-time factor ``rtf``, sim s per wall s,
0 = as fast as possible; ``batch_end``: physics runs ``Pacer.MIN_SLEEP`` wall s of steps at
once, then sleeps; ``Pacer.MAX_LAG``: the most wall s it catches up after a stall) plus what
the loop needs around it:
  sleep_until(t)   sleep until the wall clock reads ``t``, cut short by a request (the loop's
                   wake event) or a stop; replaces ``Pacer.sleep_until`` (uninterruptible)
  clock_due(sim)   Gazebo's ~pub_clock_frequency: whether /clock of sim time ``sim`` may go
  frame_in_time(sim)  whether a camera frame due at sim time ``sim`` is drawn (at a pace: not
                   while the loop is behind the wall clock)
Units: wall times and durations in seconds of ``time.monotonic``; sim times in seconds.
"""
import math
import threading
import time
from typing import Callable

from .part_times import TIMES
from ..sim.world.pacing import Pacer

# The longest the loop sleeps (wall s) without looking at Ctrl-C and ROS shutdown; a request
# (a service call, a topic's command) wakes it at once, however slow the pace.
WAKE_CHECK = 0.1
# Sleeps shorter than this (wall s) are plain sleeps, which a request does not cut short (it
# waits at most this long): at real time every sleep is one, and costs half the CPU of a wait.
SHORT_SLEEP = 0.025
# A sleep is not started for less than this (wall s): the sleep's own overshoot is larger.
SHORTEST_SLEEP = 0.0002


class LoopPacer(Pacer):
    """A Pacer whose sleeps a request or a stop cuts short, and the /clock throttle."""

    def __init__(self, rtf: float, wake: threading.Event, stopping: Callable[[], bool],
                 pub_clock_frequency: float = 0.0):
        """``wake``: set when a request is queued (LoopRequests.wake); ``stopping()``: whether
        the node is to stop (looked at once every WAKE_CHECK wall s of a long sleep);
        ``pub_clock_frequency``: at most this many /clock messages a wall second (0 = no
        limit)."""
        super().__init__(rtf)
        self._wake = wake
        self._stopping = stopping
        # /clock's least wall-time gap (s); 0 = none
        self.clock_gap = 1.0 / pub_clock_frequency if pub_clock_frequency > 0 else 0.0
        self._next_clock_wall = -math.inf

    def sleep_until(self, wall_time: float) -> bool:
        """Sleep (counted as "idle") until the clock reads ``wall_time``: True then; False as
        soon as a request is queued (the wake event is set) or ``stopping()``."""
        return TIMES.run("idle", self._wait_until, wall_time)

    def _wait_until(self, wall_time: float) -> bool:
        wake = self._wake
        while True:
            delay = wall_time - time.monotonic()
            if delay < SHORTEST_SLEEP:
                return True
            if delay < SHORT_SLEEP:
                time.sleep(delay)
                return True
            if wake.wait(delay if delay < WAKE_CHECK else WAKE_CHECK):
                return False
            if delay >= WAKE_CHECK and self._stopping():
                return False

    def clock_due(self, sim_time: float) -> bool:
        """Whether /clock at ``sim_time`` (s) may go: at least ``clock_gap`` wall s after the
        last one that went, by the wall time it leaves at (its due time when paced, now as fast
        as possible). At real time it never bites."""
        if not self.clock_gap:
            return True
        wall = self.wall_of(sim_time) if self.rtf > 0 else time.monotonic()
        if wall < self._next_clock_wall:
            return False
        self._next_clock_wall = wall + self.clock_gap
        return True

    def clock_anew(self) -> None:
        """The next /clock goes whatever the gap (after reset_simulation: time went back)."""
        self._next_clock_wall = -math.inf

    def frame_in_time(self, sim_time: float) -> bool:
        """Whether a camera frame due at ``sim_time`` (s) is drawn: as fast as possible always
        (clients wait for it); at a pace only while the loop is not behind the wall clock. A
        frame drawn late makes the loop later still, and every frame after it: it is skipped
        instead, the image topics' rate falls and the sim keeps its pace."""
        return self.rtf <= 0 or self.ahead(sim_time) >= 0.0
