"""The /gazebo loop's send queue: each step's messages made at once, written when they are due.

``SendQueue`` holds the node's Backlog of gazebo/impl/nonblocking_publisher (``backlog``: every
publisher of the node writes through it without blocking, each write timed as the loop's
"sending" part) and passes on the Backlog's ``held`` (a publish between ``hold`` and
``keep_until`` goes there), ``next_due``, ``send_due``, ``flush`` and truth (whether a
subscriber's socket left bytes for ``flush`` to retry), plus the two ways the loop sends what a
step made:
  send_due_now()           paced: write what is due by now on the wall clock
  keep(publish, due, t)    paced: made now, kept, written by ``send_due(now)`` once the wall
                           clock reads ``t`` (the step's sim time on the wall clock)
  send_gathered(publish, due)  as fast as possible: written at most once every SEND_GAP wall
                           s, all together; what clients wait for (SEND_AT_ONCE) at once
Units: wall times and durations in seconds of ``time.monotonic``.
"""
import functools
import math
import time
from typing import Optional

from .impl.nonblocking_publisher import Backlog
from .part_times import TIMES

# As fast as possible, what the steps make leaves at most this long (wall s) after it is made,
# a subscriber's messages of that time in one write: a write and a wake-up of the subscriber
# per message cost more than the physics. What clients wait for, step by step (a scan, a camera
# frame), leaves at once, with everything made before it.
SEND_GAP = 0.002
SEND_AT_ONCE = ("scan", "camera")


class SendQueue:
    """The messages made and not yet written, by the wall time they are due."""

    def __init__(self):
        # make_nonblocking(publisher, backlog) writes every publisher of the node through it
        self.backlog = Backlog(timed=functools.partial(TIMES.run, "sending"))
        self._next_send = -math.inf   # as fast as possible: the wall time of the next write

    # --- the Backlog's, as the loop (and a publish between hold and keep) uses them ----------

    def __bool__(self) -> bool:
        """Whether a subscriber's socket left bytes for ``flush`` to retry."""
        return bool(self.backlog)

    @property
    def held(self):
        """What is published while held ([(connection, bytes)]), else None (Backlog.held)."""
        return self.backlog.held

    def next_due(self) -> Optional[float]:
        """Wall time of the first kept group of messages, None if none is kept."""
        return self.backlog.next_due()

    def send_due(self, now: float = math.inf) -> None:
        """Write the kept groups due at ``now`` or before (all by default)."""
        self.backlog.send_due(now)

    def flush(self) -> None:
        """Write what the subscribers' sockets now take of what they left."""
        self.backlog.flush()

    # --- the loop's ways of sending a step's messages ------------------------------------------

    def send_due_now(self) -> None:
        """Paced: write what is due by now (nothing to do, no clock read, when nothing is
        kept)."""
        backlog = self.backlog
        if backlog.next_due() is not None:
            backlog.send_due(time.monotonic())

    def keep(self, publish, due, wall_time: float) -> None:
        """``publish(due)`` (a step's outputs), its messages kept until ``wall_time``."""
        backlog = self.backlog
        backlog.hold()
        publish(due)
        backlog.keep_until(wall_time)

    def send_gathered(self, publish, due) -> None:
        """As fast as possible: ``publish(due)`` if anything is due, then write everything kept
        if SEND_GAP wall s have passed since the last write or ``due`` names a SEND_AT_ONCE
        output."""
        backlog = self.backlog
        at_once = False
        if due:
            backlog.hold()
            publish(due)
            backlog.keep_until(0.0)
            at_once = any(name in SEND_AT_ONCE for _, name in due)
        TIMES.switch("other")
        if backlog.next_due() is not None:
            now = time.monotonic()
            if at_once or now >= self._next_send:
                backlog.send_due()
                self._next_send = now + SEND_GAP
