"""Pacing simulated time against the wall clock, and measuring the achieved real-time factor.

The simulator owns the clock: it steps physics as fast as it can and, with a real-time factor
``rtf`` > 0, sleeps once sim time runs ``MIN_SLEEP`` ahead of ``rtf`` x wall time, until wall
time has caught up (``batch_end``). ``wall_of`` says when (wall) a sim time is due, so the loop
sends what it made ahead at its moment while physics itself runs in batches. The sleeping is
the loop's (gazebo/loop_pacer.py: a request cuts it short).
``rtf`` 0 means never sleep. Times in seconds (float) from ``time.monotonic``.

A factor between 0 and ``MIN_REAL_TIME_FACTOR`` is refused: at 1e-9 one physics step would be
due days of wall time later, and /clock would look stopped for good.
"""
import time
from typing import Callable, Optional

# The slowest pace (sim s per wall s) run: 100 times slower than real time, where a 100 Hz /clock
# still ticks once a wall second. 0 (as fast as possible) is allowed.
MIN_REAL_TIME_FACTOR = 0.01


def too_slow(rtf: float) -> bool:
    """Whether ``rtf`` is above 0 but below MIN_REAL_TIME_FACTOR (give or take rounding, so that
    a max_update_rate of exactly MIN_REAL_TIME_FACTOR / time_step passes)."""
    return 0 < rtf < MIN_REAL_TIME_FACTOR * (1 - 1e-9)


def check_rtf(rtf: float) -> None:
    """ValueError (one line) unless ``rtf`` is 0 or within MIN_REAL_TIME_FACTOR..inf."""
    if not rtf >= 0:
        raise ValueError("real_time_factor must be >= 0 (0 = as fast as possible), got %r" % rtf)
    if too_slow(rtf):
        raise ValueError("real_time_factor %r is below the slowest pace %g (0 = as fast as "
                         "possible)" % (rtf, MIN_REAL_TIME_FACTOR))


class Pacer:
    """Keeps sim time at ``rtf`` times wall time, and reports the factor achieved."""

    # Sleep only once this far ahead (s of wall time). Each wake-up that steps physics costs
    # far more than a step (caches are cold again), so physics runs 20 ms of wall time's worth
    # of steps at once: at real time that halves its CPU against sleeping after every step.
    MIN_SLEEP = 0.02
    # Never try to catch up more than this much wall time (s) after a stall.
    MAX_LAG = 0.25

    def __init__(self, rtf: float, clock: Callable[[], float] = time.monotonic,
                 min_sleep: float = MIN_SLEEP):
        check_rtf(rtf)
        self.rtf = rtf
        self._clock = clock
        self._min_sleep = min_sleep
        self.restart(0.0)

    def set_rtf(self, rtf: float, sim_time: float) -> None:
        """A new factor (0 = as fast as possible) from now on, at ``sim_time``."""
        check_rtf(rtf)
        self.rtf = rtf
        self.restart(sim_time)

    def restart(self, sim_time: float) -> None:
        """Re-anchor at ``sim_time`` now (after a pause, a reset or at start)."""
        now = self._clock()
        self._anchor_wall, self._anchor_sim = now, sim_time
        self._window_wall, self._window_sim = now, sim_time

    def wall_of(self, sim_time: float) -> float:
        """The wall time (clock) at which ``sim_time`` is due; only for ``rtf`` > 0."""
        return self._anchor_wall + (sim_time - self._anchor_sim) / self.rtf

    def ahead(self, sim_time: float) -> float:
        """Wall seconds by which ``sim_time`` runs ahead of the clock (0 at ``rtf`` 0). When
        far behind (a busy machine), the debt is forgiven instead of raced to repay."""
        if self.rtf <= 0:
            return 0.0
        ahead = self.wall_of(sim_time) - self._clock()
        if ahead < -self.MAX_LAG:
            self._anchor_wall, self._anchor_sim = self._clock(), sim_time
            return 0.0
        return ahead

    def batch_end(self, sim_time: float) -> Optional[float]:
        """The wall time to sleep until once ``sim_time`` runs ``min_sleep`` or more ahead of
        the clock (the batch of steps is done), else None: step on."""
        if self.ahead(sim_time) >= self._min_sleep:
            return self.wall_of(sim_time)
        return None

    def achieved(self, sim_time: float) -> Optional[float]:
        """Factor achieved since the last call (None if no wall time passed); starts a new
        window."""
        now = self._clock()
        wall = now - self._window_wall
        if wall <= 0:
            return None
        factor = (sim_time - self._window_sim) / wall
        self._window_wall, self._window_sim = now, sim_time
        return factor
