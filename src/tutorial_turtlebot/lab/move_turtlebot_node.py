"""``move_turtlebot LINEAR ANGULAR``: drive with one constant Twist (node ``move_turtlebot``).

Usage: ``rosrun tutorial_turtlebot move_turtlebot 0.2 0.5`` drives a circle of radius
0.2 / 0.5 = 0.4 m. Bad arguments print a usage line on stderr and exit with status 2 before any
contact with ROS.

Publishes:
    cmd_vel (geometry_msgs/Twist): linear.x = LINEAR m/s, angular.z = ANGULAR rad/s, at ~rate;
        a zero Twist on shutdown (Ctrl-C, or the end of ~duration).

Parameters (``_rate:=5`` on the command line holds for that run only: unlike rospy's habit, it
is not left on the parameter server for the next run):
    ~rate (float, Hz, default 10): publishing rate, in ROS time.
    ~duration (float, s, default 0): stop after this long in ROS time; 0 runs until Ctrl-C.
    ~model, else model (str, default $TURTLEBOT3_MODEL or burger): whose speed limits to warn
        about (burger 0.22 m/s and 2.84 rad/s; waffle, waffle_pi 0.26 m/s and 1.82 rad/s).
"""
import sys

import rospy

from ..errors import UserError
from .lab_node import (CommandPublisher, init_node, model_name, number_param,
                       shut_down_on_signals)
from .move_args import (SETTINGS, USAGE, command_line_settings, parse, user_args,
                        wants_help)
from ..robot_models import model_limits


class MoveTurtlebot:
    """Publishes one Twist over and over."""

    def __init__(self, linear: float, angular: float):
        self.linear = linear
        self.angular = angular
        self.publisher = CommandPublisher()

    def run(self, rate_hz: float, duration: float) -> bool:
        """Publish at ``rate_hz`` until shutdown, or for ``duration`` s of ROS time if > 0;
        True when the duration is done."""
        rate = rospy.Rate(rate_hz, reset=True)
        rospy.sleep(0)  # under /use_sim_time: wait for the first /clock
        start = rospy.get_time()
        while not rospy.is_shutdown():
            now = rospy.get_time()
            start = min(start, now)  # the simulation was reset: count again
            if 0 < duration <= now - start:
                rospy.loginfo("%g s done, stopping", duration)
                return True
            self.publisher.publish(self.linear, self.angular)
            rate.sleep()
        return False


def main(argv=None) -> None:
    """Entry point of scripts/move_turtlebot."""
    argv = sys.argv if argv is None else argv
    args = user_args(argv[1:])
    if wants_help(args):
        print(USAGE)
        return
    try:
        linear, angular = parse(args)
    except UserError as err:
        sys.stderr.write("%s\nmove_turtlebot: error: %s\n" % (USAGE, err))
        sys.exit(2)

    settings, ros_argv = command_line_settings(argv)
    init_node("move_turtlebot", argv=ros_argv, disable_signals=True)
    shut_down_on_signals()
    for name in sorted(set(settings) - set(SETTINGS)):
        rospy.logwarn("_%s:=%s ignored: move_turtlebot's settings are %s"
                      % (name, settings[name], ", ".join("_%s" % s for s in SETTINGS)))
    rate_hz = number_param("~rate", 10.0, "Hz", above=0.0, given=settings.get("rate"))
    duration = number_param("~duration", 0.0, "s", at_least=0.0, given=settings.get("duration"))
    model = model_name()
    max_linear, max_angular = model_limits(model)
    if abs(linear) > max_linear or abs(angular) > max_angular:
        rospy.logwarn("%g m/s, %g rad/s is beyond the %s's limits of %g m/s and %g rad/s: "
                      "the real robot would not go that fast"
                      % (linear, angular, model, max_linear, max_angular))
    node = MoveTurtlebot(linear, angular)
    rospy.loginfo("publishing linear.x %g m/s, angular.z %g rad/s on %s at %g Hz%s"
                  % (linear, angular, node.publisher.topic, rate_hz,
                     " for %g s" % duration if duration else "; Ctrl-C stops"))
    try:
        done = node.run(rate_hz, duration)
    except rospy.ROSInterruptException:
        return  # Ctrl-C: the shutdown hook publishes the zero Twist
    if done:
        rospy.signal_shutdown("duration done")
