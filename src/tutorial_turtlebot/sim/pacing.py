"""Pacing simulated time against the wall clock, and measuring the achieved real-time factor.

The simulator owns the clock: it steps physics as fast as it can and, with a real-time factor
``rtf`` > 0, sleeps once sim time runs ``MIN_SLEEP`` ahead of ``rtf`` x wall time, until wall
time has caught up. ``rtf`` 0 means never sleep. Times in seconds (float) from
``time.monotonic``.
"""
import time
from typing import Callable, Optional


class Pacer:
    """Keeps sim time at ``rtf`` times wall time, and reports the factor achieved."""

    # Sleep only once this far ahead (s of wall time). Each wake-up costs far more than a step
    # (caches are cold again), so the sim runs 20 ms of wall time's worth of steps at once and
    # sleeps 20 ms: at real time that halves its CPU against sleeping after every 2.5 ms step.
    # Messages then arrive in bursts of at most 20 ms, each with its exact sim-time stamp.
    MIN_SLEEP = 0.02
    # Never try to catch up more than this much wall time (s) after a stall.
    MAX_LAG = 0.25

    def __init__(self, rtf: float, clock: Callable[[], float] = time.monotonic,
                 sleep: Callable[[float], None] = time.sleep, min_sleep: float = MIN_SLEEP):
        if not rtf >= 0:
            raise ValueError("real_time_factor must be >= 0 (0 = as fast as possible), got %r"
                             % rtf)
        self.rtf = rtf
        self._clock = clock
        self._sleep = sleep
        self._min_sleep = min_sleep
        self.restart(0.0)

    def restart(self, sim_time: float) -> None:
        """Re-anchor at ``sim_time`` now (after a pause, a reset or at start)."""
        now = self._clock()
        self._anchor_wall, self._anchor_sim = now, sim_time
        self._window_wall, self._window_sim = now, sim_time

    def wait(self, sim_time: float) -> None:
        """Sleep until wall time has caught up with ``sim_time`` at the target factor."""
        if self.rtf <= 0:
            return
        target_wall = self._anchor_wall + (sim_time - self._anchor_sim) / self.rtf
        ahead = target_wall - self._clock()
        if ahead >= self._min_sleep:
            self._sleep(ahead)
        elif ahead < -self.MAX_LAG:
            # Too far behind (machine busy): forget the debt instead of racing to repay it.
            self._anchor_wall, self._anchor_sim = self._clock(), sim_time

    def achieved(self, sim_time: float) -> Optional[float]:
        """Factor achieved since the last call (None if no wall time passed); starts a new window."""
        now = self._clock()
        wall = now - self._window_wall
        if wall <= 0:
            return None
        factor = (sim_time - self._window_sim) / wall
        self._window_wall, self._window_sim = now, sim_time
        return factor
