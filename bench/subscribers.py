#!/usr/bin/env python3
"""Benchmark helper: a process apart from the sim that subscribes to sim topics and reports.

    subscribers.py [TOPIC[:N] ...]     e.g.  subscribers.py /scan:4 /odom /imu
Subscribes N times (default 1) to each topic with a callback that only counts, and prints one
line per wall second: ``wall_time sim_time total_messages`` (sim_time from /clock).
"""
import sys
import time

import rospy
from gazebo_msgs.msg import ModelStates
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Image, Imu, JointState, LaserScan
from tf2_msgs.msg import TFMessage

TYPES = {"/scan": LaserScan, "/odom": Odometry, "/imu": Imu, "/joint_states": JointState,
         "/tf": TFMessage, "/camera/rgb/image_raw": Image, "/camera/image": Image,
         "/gazebo/model_states": ModelStates}


class Counter:
    """Counts messages of all subscriptions and keeps the latest /clock."""

    def __init__(self):
        self.messages = 0
        self.clock = 0.0

    def count(self, _msg):
        self.messages += 1

    def on_clock(self, msg):
        self.clock = msg.clock.to_sec()


def main():
    rospy.init_node("bench_subscribers", anonymous=True, disable_signals=True)
    counter = Counter()
    rospy.Subscriber("/clock", Clock, counter.on_clock, queue_size=1)
    for arg in sys.argv[1:]:
        topic, _, times = arg.partition(":")
        for _ in range(int(times or 1)):
            rospy.Subscriber(topic, TYPES[topic], counter.count, queue_size=1)
    while True:
        print("%.3f %.3f %d" % (time.time(), counter.clock, counter.messages), flush=True)
        time.sleep(1.0)


if __name__ == "__main__":
    main()
