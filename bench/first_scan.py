#!/usr/bin/env python3
"""Benchmark helper: waits for the master, then for the first /scan; prints the wall time
(time.time()) at which it arrived and exits."""
import threading
import time

import rospy
from sensor_msgs.msg import LaserScan


def main():
    rospy.init_node("bench_first_scan", anonymous=True, disable_signals=True)
    arrived = threading.Event()
    stamp = []

    def on_scan(_msg):
        if not arrived.is_set():
            stamp.append(time.time())
            arrived.set()
    rospy.Subscriber("/scan", LaserScan, on_scan, queue_size=1)
    arrived.wait(60.0)
    print("%.3f" % stamp[0] if stamp else "nan", flush=True)


if __name__ == "__main__":
    main()
