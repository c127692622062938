"""Helpers for the rostest nodes: wait on wall time (a stalled /clock must fail a test, never
hang it), collect messages, read poses. Imported by the test_*.py nodes beside it."""
import math
import threading
import time

import rospy
from geometry_msgs.msg import Twist, Vector3
from nav_msgs.msg import Odometry
from std_srvs.srv import Empty


def yaw_of(q) -> float:
    """Heading (rad) of a geometry_msgs/Quaternion."""
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def wait_for(predicate, timeout: float, step: float = 0.02) -> bool:
    """Poll ``predicate`` until true or ``timeout`` wall seconds pass."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if predicate():
            return True
        time.sleep(step)
    return predicate()


class Recorder:
    """Keeps every message of a topic (with its arrival) for later questions."""

    def __init__(self, topic, msg_type):
        self.msgs = []
        self._lock = threading.Lock()
        self.sub = rospy.Subscriber(topic, msg_type, self._on_msg, queue_size=100)

    def _on_msg(self, msg):
        with self._lock:
            self.msgs.append(msg)

    def clear(self):
        """Forget what was received (e.g. after the sim's time was reset)."""
        with self._lock:
            self.msgs = []

    def between(self, start: rospy.Time, end: rospy.Time):
        """Messages stamped within [start, end], in arrival order."""
        with self._lock:
            return [m for m in self.msgs if start <= m.header.stamp <= end]

    def latest(self, timeout: float = 10.0):
        """The newest message, waiting up to ``timeout`` wall s for a first one (None if none)."""
        wait_for(lambda: self.msgs, timeout)
        with self._lock:
            return self.msgs[-1] if self.msgs else None

    def after(self, stamp: rospy.Time, timeout: float):
        """The first message stamped at or after ``stamp`` (None if none within ``timeout``)."""
        def find():
            with self._lock:
                return next((m for m in self.msgs if m.header.stamp >= stamp), None)
        wait_for(lambda: find() is not None, timeout)
        return find()


class Driver:
    """Publishes cmd_vel and calls the /gazebo services."""

    def __init__(self):
        self.pub = rospy.Publisher("cmd_vel", Twist, queue_size=1)
        self.odom = Recorder("odom", Odometry)
        wait_for(lambda: self.pub.get_num_connections() > 0, 20.0)

    def send(self, linear: float, angular: float) -> None:
        """Publish one Twist (the sim keeps it until the next)."""
        self.pub.publish(Twist(linear=Vector3(linear, 0, 0), angular=Vector3(0, 0, angular)))

    @staticmethod
    def call(service: str) -> None:
        """Call a std_srvs/Empty service such as /gazebo/reset_world."""
        rospy.wait_for_service(service, timeout=20.0)
        rospy.ServiceProxy(service, Empty)()
