#!/usr/bin/env python3
"""Benchmark helper: a bare rospy node, no sim, publishing 24-ray LaserScans on /scan at
1000 Hz of wall time (stamped with wall time), until interrupted. Against it, a client that
waits for one scan per step shows its own bound (run_bench.py's stage-client floor)."""
import time

import rospy
from sensor_msgs.msg import LaserScan

RATE_HZ = 1000.0


def main():
    rospy.init_node("bench_scan_source", anonymous=True)   # SIGINT: rospy shuts down
    pub = rospy.Publisher("/scan", LaserScan, queue_size=1)
    scan = LaserScan()
    scan.header.frame_id = "base_scan"
    scan.angle_max, scan.angle_increment = 6.02138592, 0.26179939
    scan.range_min, scan.range_max = 0.12, 3.5
    scan.ranges = [1.0] * 24
    next_time = time.monotonic()
    while not rospy.is_shutdown():
        scan.header.stamp = rospy.Time.from_sec(time.time())
        try:
            pub.publish(scan)
        except rospy.ROSException:   # shut down between the check and the publish
            break
        next_time += 1.0 / RATE_HZ
        time.sleep(max(0.0, next_time - time.monotonic()))


if __name__ == "__main__":
    main()
