"""``laser_data``: log what the lidar sees, one line per scan (node ``laser_data``).

Each line gives the range straight ahead (the ray at bearing 0, found from angle_min and
angle_increment), the handout's five readings at 0, 90, 180, 270 and 359 degrees
counter-clockwise (90 is left, 270 right), and the closest valid reading with its bearing.
Ranges are in metres; inf, -inf, NaN, 0.0 and values outside [range_min, range_max] show as
"no reading". The format:
``ahead: R | 0 deg: R  90 deg: R  180 deg: R  270 deg: R  359 deg: R | closest: D m at B deg``
where R is "D m" or "no reading", D a distance with two decimals and B a whole degree.

Subscribes:
    scan (sensor_msgs/LaserScan): frame base_scan.

Parameters: none.
"""
import rospy
from sensor_msgs.msg import LaserScan

from .lab_node import init_node
from .scan_reading import report


class LaserData:
    """Logs :func:`scan_reading.report` of each scan."""

    def __init__(self):
        self.subscriber = rospy.Subscriber("scan", LaserScan, self.on_scan, queue_size=1)

    @staticmethod
    def on_scan(msg: LaserScan) -> None:
        rospy.loginfo(report(msg))


def main() -> None:
    """Entry point of scripts/laser_data."""
    init_node("laser_data")
    LaserData()
    rospy.loginfo("waiting for scans on %s", rospy.resolve_name("scan"))
    rospy.spin()
