"""gazebo/impl/registration_poll.py: rospy.init_node's wait for the master's answer is looked
at every POLL s, not every 0.1 s. No ROS master."""
import time

import rospy.impl.init

from tutorial_turtlebot.gazebo.impl import registration_poll


def test_start_nodes_sleeps_are_short_and_its_time_is_still_time(monkeypatch):
    monkeypatch.setattr(rospy.impl.init, "time", rospy.impl.init.time)   # put back afterwards
    registration_poll.install()
    start = time.monotonic()
    rospy.impl.init.time.sleep(0.1)   # start_node's poll for the registration
    assert time.monotonic() - start < 0.05
    assert rospy.impl.init.time.monotonic is time.monotonic


def test_start_node_still_looks_at_time_sleep():
    """The replaced poll: start_node waits for the registration with time.sleep of 0.1 s (a
    rospy whose start_node no longer does would make install() pointless, not wrong)."""
    import inspect
    assert "time.sleep(0.1)" in inspect.getsource(rospy.impl.init.start_node)
