#!/usr/bin/env python3
"""Benchmark helper: a process apart from the sim that subscribes to sim topics and reports.

    subscribers.py [TOPIC[:N] ...]     e.g.  subscribers.py /scan:4 /odom /imu /tb3_0/scan
Subscribes N times (default 1) to each topic with a callback that only counts, and prints one
line per wall second: ``wall_time sim_time total_messages topics_heard`` (sim_time from
/clock; topics_heard: how many of the topics have delivered a message so far). A topic's type
is found by the last part of its name (``/tb3_0/scan`` is a LaserScan like ``/scan``).
"""
import sys
import time

import rospy
from gazebo_msgs.msg import ModelStates
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Image, Imu, JointState, LaserScan
from tf2_msgs.msg import TFMessage

TYPES = {"scan": LaserScan, "odom": Odometry, "imu": Imu, "joint_states": JointState,
         "tf": TFMessage, "image_raw": Image, "image": Image, "model_states": ModelStates}


def topic_type(topic):
    """The message class of ``topic`` by its last name part; SystemExit with one line if none."""
    last = topic.rstrip("/").rsplit("/", 1)[-1]
    if last not in TYPES:
        sys.exit("subscribers.py: no type known for %s (known: %s)"
                 % (topic, ", ".join(sorted(TYPES))))
    return TYPES[last]


class Counter:
    """Counts messages of all subscriptions, the topics heard, and keeps the latest /clock."""

    def __init__(self):
        self.messages = 0
        self.heard = set()
        self.clock = 0.0

    def counter_of(self, topic):
        def count(_msg):
            self.messages += 1
            if topic not in self.heard:
                self.heard.add(topic)
        return count

    def on_clock(self, msg):
        self.clock = msg.clock.to_sec()


def main():
    subscriptions = []
    for arg in sys.argv[1:]:
        topic, _, times = arg.partition(":")
        subscriptions.append((topic, topic_type(topic), int(times or 1)))
    rospy.init_node("bench_subscribers", anonymous=True, disable_signals=True)
    counter = Counter()
    rospy.Subscriber("/clock", Clock, counter.on_clock, queue_size=1)
    for topic, msg_type, times in subscriptions:
        for _ in range(times):
            rospy.Subscriber(topic, msg_type, counter.counter_of(topic), queue_size=1)
    while True:
        print("%.3f %.3f %d %d" % (time.time(), counter.clock, counter.messages,
                                   len(counter.heard)), flush=True)
        time.sleep(1.0)


if __name__ == "__main__":
    main()
