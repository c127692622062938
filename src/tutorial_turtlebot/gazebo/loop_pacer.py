"""When the /gazebo loop's next step may run against the wall clock, and its sleeps until then.

``LoopPacer`` holds a sim/world/pacing ``Pacer`` (``pacer``) and passes on what the loop asks
of it: the real-time factor ``rtf`` (sim s per wall s, 0 = as fast as possible; ``set_rtf``),
``restart``, ``wall_of``, ``ahead``, ``batch_end`` (physics runs ``Pacer.MIN_SLEEP`` wall s of
steps at once, then sleeps; ``Pacer.MAX_LAG``: the most wall s it catches up after a stall) and
``achieved``; plus what the loop needs around it:
  sleep_until(t)   sleep until the wall clock reads ``t``, cut short by a request (the loop's
                   wake event) or a stop
  clock_due(sim)   Gazebo's ~pub_clock_frequency: whether /clock of sim time ``sim`` may go
  frame_in_time(sim)  whether a camera frame due at sim time ``sim`` is drawn (at a pace: not
                   while the loop is behind the wall clock)
Units: wall times and durations in seconds of ``time.monotonic``; sim times in seconds.
"""
import math
import threading
import time
from typing import Callable, Optional

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


class LoopPacer:
    """A Pacer's pace, sleeps that a request or a stop cuts short, and the /clock throttle."""

    def __init__(self, rtf: float, wake: threading.Event, stopping: Callable[[], bool],
                 pub_clock_frequency: float = 0.0):
        """``wake``: set when a request is queued (LoopRequests.wake); ``stopping()``: whether
        the node is to stop (looked at once every WAKE_CHECK wall s of a long sleep);
        ``pub_clock_frequency``: at most this many /clock messages a wall second (0 = no
        limit)."""
        self.pacer = Pacer(rtf)
        self._wake = wake
        self._stopping = stopping
        # /clock's least wall-time gap (s); 0 = none
        self.clock_gap = 1.0 / pub_clock_frequency if pub_clock_frequency > 0 else 0.0
        self._next_clock_wall = -math.inf

    # --- the Pacer's, as the loop uses them --------------------------------------------------

    @property
    def rtf(self) -> float:
        """The real-time factor (sim s per wall s; 0 = as fast as possible)."""
        return self.pacer.rtf

    def set_rtf(self, rtf: float, sim_time: float) -> None:
        """A new factor from now on, at ``sim_time`` (ValueError if too slow: Pacer.set_rtf)."""
        self.pacer.set_rtf(rtf, sim_time)

    def restart(self, sim_time: float) -> None:
        """Re-anchor at ``sim_time`` now (after a pause, a reset or at start)."""
        self.pacer.restart(sim_time)

    def wall_of(self, sim_time: float) -> float:
        """The wall time at which ``sim_time`` is due; only for ``rtf`` > 0."""
        return self.pacer.wall_of(sim_time)

    def ahead(self, sim_time: float) -> float:
        """Wall s by which ``sim_time`` runs ahead of the clock (Pacer.ahead)."""
        return self.pacer.ahead(sim_time)

    def batch_end(self, sim_time: float) -> Optional[float]:
        """The wall time to sleep until once the batch of steps is done, else None
        (Pacer.batch_end)."""
        return self.pacer.batch_end(sim_time)

    def achieved(self, sim_time: float) -> Optional[float]:
        """The factor achieved since the last call, or None (Pacer.achieved)."""
        return self.pacer.achieved(sim_time)

    # --- the loop's own -------------------------------------------------------------------------

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
        pacer = self.pacer
        wall = pacer.wall_of(sim_time) if pacer.rtf > 0 else time.monotonic()
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
        pacer = self.pacer
        return pacer.rtf <= 0 or pacer.ahead(sim_time) >= 0.0
