"""rospy.init_node without its tenth of a second of waiting for the master's answer.

Replaces: the poll in ``rospy.impl.init.start_node``. ``rospy.init_node`` starts the node's
XML-RPC server, whose own thread then registers the node with the master; meanwhile
``start_node`` looks whether that is done every 0.1 s (``time.sleep(0.1)``), so a registration
that takes a few ms still costs the whole 0.1 s: a tenth of the sim's own start-up.

``install()`` (before ``rospy.init_node``) hands that module a ``time`` whose sleeps last at
most ``POLL`` wall s: the same wait, looked at more often. ``start_node`` is the module's only
user of ``time``; its other poll (for the server's address) sleeps 10 µs already.
"""
import time

import rospy.impl.init

POLL = 0.002   # wall s between two looks at the registration


class _ShortSleeps:
    """The ``time`` module as rospy.impl.init sees it: each sleep at most POLL s."""

    def __getattr__(self, name):
        return getattr(time, name)

    @staticmethod
    def sleep(seconds: float) -> None:
        time.sleep(min(seconds, POLL))


def install() -> None:
    """start_node's sleeps (while it waits for the registration) last at most POLL s."""
    rospy.impl.init.time = _ShortSleeps()
