"""Fixed-rate schedules on the simulation clock, in integer nanoseconds (no float drift).

A ``RateSchedule`` of 30 Hz fires at the first physics step at or after each multiple of
1/30 s; the average rate is exact, each firing late by less than one physics step.
"""

import math

NS_PER_S = 1_000_000_000


def seconds_to_ns(seconds: float) -> int:
    """Seconds (float) to integer nanoseconds, rounded."""
    return int(round(seconds * NS_PER_S))


class RateSchedule:
    """Says when something running at ``rate_hz`` of sim time is due."""

    def __init__(self, rate_hz: float):
        if not rate_hz > 0:
            raise ValueError("rate must be > 0 Hz, got %r" % rate_hz)
        self.rate_hz = rate_hz
        self._period_ns = NS_PER_S / rate_hz  # float: exact mean rate over many periods
        self._count = 0
        self._origin_ns = 0
        self.next_ns = 0  # the first time (ns) at which due() will say True

    def reset(self, now_ns: int) -> None:
        """Start over: the next firing is at ``now_ns``."""
        self._origin_ns = now_ns
        self._count = 0
        self.next_ns = now_ns

    def due(self, now_ns: int) -> bool:
        """True (once) when a firing is due at ``now_ns``; skips firings missed while paused."""
        if now_ns < self._origin_ns + self._count * self._period_ns:
            return False
        # max(): the floor division may round one period short of what the test above saw.
        self._count = max(self._count + 1,
                          int((now_ns - self._origin_ns) // self._period_ns) + 1)
        self.next_ns = math.ceil(self._origin_ns + self._count * self._period_ns)
        return True
