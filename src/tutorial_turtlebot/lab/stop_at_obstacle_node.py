"""``stop_at_obstacle``: drive straight on, stop before an obstacle (node ``stop_at_obstacle``).

Drives forward at ~speed until the nearest obstacle within +-~sector_deg of straight ahead is
under ~stop_distance, rests, and drives on once it is ~stop_distance + ~clear_margin or more
away. Distances are from the lidar (base_scan). Invalid readings (inf, NaN, 0.0, out of range)
are ignored, except -inf, which means "closer than range_min".

Subscribes:
    scan (sensor_msgs/LaserScan)

Publishes:
    cmd_vel (geometry_msgs/Twist): linear.x ~speed m/s or 0, once per scan; a zero Twist when
        no scan has come for ~scan_timeout, and on shutdown.

Parameters:
    ~speed (float, m/s, default 0.15): forward speed; at 0.15 it moves 3 cm between two
        scans (5 Hz), and it is well inside both models' limits (0.22 and 0.26 m/s).
    ~stop_distance (float, m, default 0.5): stop when something is nearer than this.
    ~sector_deg (float, degrees, default 15): half-width of the front sector.
    ~clear_margin (float, m, default 0.05): drive on only beyond stop_distance + this, so
        that range noise (sigma 0.01 m) does not make it creep forward in steps.
    ~scan_timeout (float, s, default 1.0): stop when scans stop coming for this long.
    ~model, else model (str, default $TURTLEBOT3_MODEL or burger): for the speed warning.
"""
import math

import rospy

from .lab_node import ScanToCommand, init_node, model_name, number_param
from .obstacle_logic import StopAtObstacle
from ..robot_models import model_limits


class StopAtObstacleNode:
    """Runs a StopAtObstacle on each scan and logs when it stops or drives on."""

    def __init__(self, logic: StopAtObstacle, scan_timeout: float):
        self.logic = logic
        self.driver = ScanToCommand(self.decide, scan_timeout)

    def decide(self, scan):
        was_stopped = self.logic.stopped
        command = self.logic.update(scan)
        if self.logic.stopped and not was_stopped:
            rospy.loginfo("obstacle %.2f m ahead: stopping" % self.logic.front)
        elif was_stopped and not self.logic.stopped:
            rospy.loginfo("way clear: driving on")
        return command


def main() -> None:
    """Entry point of scripts/stop_at_obstacle."""
    init_node("stop_at_obstacle")
    speed = number_param("~speed", 0.15, "m/s", above=0.0)
    stop_distance = number_param("~stop_distance", 0.5, "m", above=0.0)
    sector_deg = number_param("~sector_deg", 15.0, "degrees", above=0.0, at_most=180.0)
    clear_margin = number_param("~clear_margin", 0.05, "m", at_least=0.0)
    scan_timeout = number_param("~scan_timeout", 1.0, "s", above=0.0)
    model = model_name()
    max_linear, _ = model_limits(model)
    if speed > max_linear:
        rospy.logwarn("~speed %g m/s is beyond the %s's limit of %g m/s"
                      % (speed, model, max_linear))
    logic = StopAtObstacle(speed, stop_distance, math.radians(sector_deg), clear_margin)
    StopAtObstacleNode(logic, scan_timeout)
    rospy.loginfo("driving at %g m/s until something is within %g m, +-%g degrees ahead"
                  % (speed, stop_distance, sector_deg))
    rospy.spin()
