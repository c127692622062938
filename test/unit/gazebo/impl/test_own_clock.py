"""gazebo/impl/own_clock.py: the node's rospy time is set from the sim, and rospy's own /clock
subscription (made under /use_sim_time) is dropped. No ROS master."""
import rospy
import rospy.impl.simtime
import rospy.rostime

from tutorial_turtlebot.gazebo.impl.own_clock import own_the_clock, set_time


class Subscription:
    def __init__(self):
        self.unregistered = False

    def unregister(self):
        self.unregistered = True


def test_own_the_clock_unregisters_rospys_clock_subscription(monkeypatch):
    subscription = Subscription()
    monkeypatch.setattr(rospy.impl.simtime, "_clock_sub", subscription, raising=False)
    own_the_clock()
    assert subscription.unregistered and rospy.impl.simtime._clock_sub is None
    own_the_clock()   # none left (or never made, without /use_sim_time): nothing to do


def test_set_time_is_the_nodes_rospy_time(monkeypatch):
    # as after init_node under /use_sim_time; both are put back after the test
    monkeypatch.setattr(rospy.rostime, "_rostime_initialized", True)
    monkeypatch.setattr(rospy.rostime, "_rostime_current", None)
    set_time(rospy.Time(12, 345))
    assert rospy.get_rostime() == rospy.Time(12, 345)
