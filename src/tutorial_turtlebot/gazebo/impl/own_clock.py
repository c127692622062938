"""The /gazebo node is the clock: its own rospy time is set from the sim, not from /clock.

Replaces: rospy.impl.simtime's /clock subscription and the time it sets. Under /use_sim_time
``rospy.init_node`` subscribes every node to /clock (``rospy.impl.simtime._clock_sub``), and
each message sets the node's time through ``rospy.rostime._set_rostime``: the node would
deserialize every clock message it publishes itself, and its time would lag its own clock by
that round trip.

``own_the_clock()`` (after ``rospy.init_node``) unregisters that subscription;
``set_time(stamp)`` then sets the node's rospy time (``rospy.get_rostime``, ``rospy.Time.now``,
``rospy.sleep``, timers) to ``stamp`` directly, as the subscription's callback would have.
"""
import rospy.impl.simtime
from rospy.rostime import _set_rostime


def own_the_clock() -> None:
    """Unregister rospy's own /clock subscription, if it made one (only under /use_sim_time)."""
    subscription = getattr(rospy.impl.simtime, "_clock_sub", None)
    if subscription is not None:
        subscription.unregister()
        rospy.impl.simtime._clock_sub = None


def set_time(stamp) -> None:
    """This process's rospy time is ``stamp`` (a rospy.Time) from now on, and whoever sleeps on
    it is woken (what rospy does with each /clock message)."""
    _set_rostime(stamp)
