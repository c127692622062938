"""``wander``: the wander-bot made right for a TurtleBot3 (node ``wander``).

Drives forward until something is under ~stop_distance ahead, then turns in place toward the
more open side until the way ahead is ~stop_distance + ~clear_margin or more, then drives on.
"Ahead" is the front sector (+-~sector_deg) plus the corridor the robot sweeps (~robot_radius
either side of its line of travel), so it never drives into anything, nor turns into anything.
Distances are from the lidar (base_scan); invalid readings are ignored, except -inf ("closer
than range_min"), and +inf counts as open space when choosing a side.

Subscribes:
    scan (sensor_msgs/LaserScan)

Publishes:
    cmd_vel (geometry_msgs/Twist): (~speed, 0) or (0, +-~turn_speed), once per scan; a zero
        Twist when no scan has come for ~scan_timeout, and on shutdown.

Parameters:
    ~speed (float, m/s, default 0.2): forward speed; under both models' limits (0.22, 0.26 m/s)
        and only 4 cm between two scans (5 Hz), far less than the 0.5 m stop distance.
    ~turn_speed (float, rad/s, default 1.0): turning speed; under both models' limits (2.84,
        1.82 rad/s) and 11 degrees between two scans, less than the front sector's half-width.
    ~stop_distance (float, m, default 0.5): turn away when something ahead is nearer.
    ~sector_deg (float, degrees, default 15): half-width of the front sector.
    ~clear_margin (float, m, default 0.1): turn until the way ahead is this much beyond
        stop_distance, so that it does not stop again at once.
    ~robot_radius (float, m, default 0.15 burger, 0.26 waffle, waffle_pi): half-width of the
        corridor kept clear: the radius the robot sweeps turning in place. Must be less than
        ~stop_distance.
    ~scan_timeout (float, s, default 1.0): stop when scans stop coming for this long.
    ~model, else model from the node's namespace upward (/tb3_2/model, then /model) (str,
        default $TURTLEBOT3_MODEL or burger): for the defaults and warnings.
"""
import math

import rospy

from .lab_node import ScanToCommand, fatal, init_node, model_name, number_param
from ..robot_models import turn_radius
from .obstacle_logic import FORWARD, Wander
from ..robot_models import model_limits


class WanderNode:
    """Runs a Wander on each scan and logs its turns."""

    def __init__(self, logic: Wander, scan_timeout: float):
        self.logic = logic
        self.driver = ScanToCommand(self.decide, scan_timeout)

    def decide(self, scan):
        before = self.logic.state
        command = self.logic.update(scan)
        if self.logic.state != before:
            if self.logic.state == FORWARD:
                rospy.loginfo("way clear: forward")
            else:
                rospy.loginfo("%.2f m ahead: %s" % (self.logic.front, self.logic.state))
        return command


def main() -> None:
    """Entry point of scripts/wander."""
    init_node("wander")
    model = model_name()
    speed = number_param("~speed", 0.2, "m/s", above=0.0)
    turn_speed = number_param("~turn_speed", 1.0, "rad/s", above=0.0)
    stop_distance = number_param("~stop_distance", 0.5, "m", above=0.0)
    sector_deg = number_param("~sector_deg", 15.0, "degrees", above=0.0, at_most=180.0)
    clear_margin = number_param("~clear_margin", 0.1, "m", at_least=0.0)
    robot_radius = number_param("~robot_radius", turn_radius(model), "m", at_least=0.0)
    scan_timeout = number_param("~scan_timeout", 1.0, "s", above=0.0)
    if robot_radius >= stop_distance:
        fatal("parameter %s (%g m) must be more than %s (%g m), or wander could turn into "
              "what it stopped before" % (rospy.resolve_name("~stop_distance"), stop_distance,
                                          rospy.resolve_name("~robot_radius"), robot_radius))
    max_linear, max_angular = model_limits(model)
    if speed > max_linear or turn_speed > max_angular:
        rospy.logwarn("~speed %g m/s or ~turn_speed %g rad/s is beyond the %s's limits of "
                      "%g m/s and %g rad/s" % (speed, turn_speed, model, max_linear, max_angular))
    logic = Wander(speed, turn_speed, stop_distance, math.radians(sector_deg), clear_margin,
                   robot_radius)
    WanderNode(logic, scan_timeout)
    rospy.loginfo("wandering at %g m/s, turning at %g rad/s, keeping %g m ahead and %g m either "
                  "side clear" % (speed, turn_speed, stop_distance, robot_radius))
    rospy.spin()
