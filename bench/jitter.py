#!/usr/bin/env python3
"""Benchmark helper: how evenly the sim's messages arrive, in a process apart from the sim.

    jitter.py SECONDS TOPIC [TOPIC ...]      e.g.  jitter.py 10 /odom /imu /scan /clock
Subscribes to each topic, notes every message's wall arrival time and its stamp (sim time), and
after SECONDS of wall time (counted from the first message) prints one line per topic:
``TOPIC COUNT p50 p99 max`` of the arrival-interval error in ms of wall time: the gap between two
arrivals minus the gap between their stamps (at real-time factor 1, a message arriving exactly
when its stamp is due has error 0). Run it with the sim at real_time_factor 1.
"""
import sys
import time

import rospy
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import Imu, JointState, LaserScan
from tf2_msgs.msg import TFMessage

TYPES = {"/scan": LaserScan, "/odom": Odometry, "/imu": Imu, "/joint_states": JointState,
         "/tf": TFMessage, "/clock": Clock}


def stamp_of(msg) -> float:
    if isinstance(msg, Clock):
        return msg.clock.to_sec()
    if isinstance(msg, TFMessage):
        return msg.transforms[0].header.stamp.to_sec()
    return msg.header.stamp.to_sec()


def interval_errors_ms(arrivals):
    """|arrival gap - stamp gap| in ms for consecutive (wall, stamp) pairs, sorted."""
    return sorted(abs((a1 - a0) - (s1 - s0)) * 1000.0
                  for (a0, s0), (a1, s1) in zip(arrivals, arrivals[1:]))


def percentile(sorted_values, fraction):
    if not sorted_values:
        return float("nan")
    return sorted_values[min(len(sorted_values) - 1, int(fraction * len(sorted_values)))]


def main():
    seconds = float(sys.argv[1])
    topics = sys.argv[2:]
    rospy.init_node("bench_jitter", anonymous=True, disable_signals=True)
    arrivals = {topic: [] for topic in topics}

    def recorder(topic):
        log = arrivals[topic]
        return lambda msg: log.append((time.monotonic(), stamp_of(msg)))
    for topic in topics:
        rospy.Subscriber(topic, TYPES[topic], recorder(topic), queue_size=100)
    while not any(arrivals.values()):
        time.sleep(0.01)
    time.sleep(seconds)
    for topic in topics:
        log = list(arrivals[topic])[1:]  # the first may have queued while connecting
        errors = interval_errors_ms(log)
        print("%s %d %.2f %.2f %.2f" % (topic, len(log), percentile(errors, 0.5),
                                        percentile(errors, 0.99), errors[-1] if errors else
                                        float("nan")), flush=True)


if __name__ == "__main__":
    main()
