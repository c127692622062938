"""Says once when a robot's camera keeps fewer images than its declared rate.

At a pace (real time, or any real-time factor), a camera frame due while the loop is behind the
wall clock is skipped (LoopPacer.frame_in_time): the image topics' rate falls and the sim keeps
its pace. ``CameraRateWatch`` counts a camera's due frames while somebody subscribes, in windows
of WINDOW_SECONDS of sim time, and the first window that keeps less than KEPT_SHARE of them
gives the rate kept (images per sim second), for one warning line; it says nothing after.
"""
from typing import Optional

WINDOW_SECONDS = 5.0   # sim s of a camera's due frames judged together
KEPT_SHARE = 0.9       # a camera keeping fewer of its due frames than this says so


class CameraRateWatch:
    """One camera's due and skipped frames (subscribed ones only)."""

    def __init__(self, rate_hz: float):
        self.rate_hz = rate_hz      # the declared rate, Hz of sim time
        self.due = 0
        self.skipped = 0
        self.said = False

    def count(self, skipped: bool) -> Optional[float]:
        """One due frame, skipped or drawn. The rate kept (Hz of sim time) when this completes
        the first window that kept too few; else None."""
        if self.said:
            return None
        self.due += 1
        self.skipped += skipped
        if self.due < self.rate_hz * WINDOW_SECONDS:
            return None
        kept = (self.due - self.skipped) / self.due
        self.due = self.skipped = 0
        if kept >= KEPT_SHARE:
            return None
        self.said = True
        return kept * self.rate_hz
