"""The /gazebo loop's send queue: each step's messages made at once, written when they are due.

``SendQueue`` is the Backlog of gazebo/impl/nonblocking_publisher (every publisher of the node
writes through it without blocking; ``flush`` retries what a subscriber's socket did not take)
plus the two ways the loop sends what a step made:
  send_due_now()           paced: write what is due by now on the wall clock
  keep(publish, due, t)    paced: made now, kept, written by ``send_due(now)`` once the wall
                           clock reads ``t`` (the step's sim time on the wall clock)
  send_gathered(publish, due)  as fast as possible: written at most once every SEND_GAP wall
                           s, all together; what clients wait for (SEND_AT_ONCE) at once
Units: wall times and durations in seconds of ``time.monotonic``.
"""
import math
import time

from .impl.nonblocking_publisher import Backlog
from .part_times import TIMES

# As fast as possible, what the steps make leaves at most this long (wall s) after it is made,
# a subscriber's messages of that time in one write: a write and a wake-up of the subscriber
# per message cost more than the physics. What clients wait for, step by step (a scan, a camera
# frame), leaves at once, with everything made before it.
SEND_GAP = 0.002
SEND_AT_ONCE = ("scan", "camera")


class SendQueue(Backlog):
    """The messages made and not yet written, by the wall time they are due."""

    def __init__(self):
        super().__init__()
        self._next_send = -math.inf   # as fast as possible: the wall time of the next write

    def send_due_now(self) -> None:
        """Paced: write what is due by now (nothing to do, no clock read, when nothing is
        kept)."""
        if self._due:   # (Backlog's kept groups)
            self.send_due(time.monotonic())

    def keep(self, publish, due, wall_time: float) -> None:
        """``publish(due)`` (a step's outputs), its messages kept until ``wall_time``."""
        self.hold()
        publish(due)
        self.keep_until(wall_time)

    def send_gathered(self, publish, due) -> None:
        """As fast as possible: ``publish(due)`` if anything is due, then write everything kept
        if SEND_GAP wall s have passed since the last write or ``due`` names a SEND_AT_ONCE
        output."""
        at_once = False
        if due:
            self.hold()
            publish(due)
            self.keep_until(0.0)
            at_once = any(name in SEND_AT_ONCE for _, name in due)
        TIMES.switch("other")
        if self._due:   # (Backlog's kept groups)
            now = time.monotonic()
            if at_once or now >= self._next_send:
                self.send_due()
                self._next_send = now + SEND_GAP
