"""``teleop_key``: drive a TurtleBot3 from the keyboard (node ``turtlebot3_teleop_keyboard``).

The lab handout's keys: ``u i o / j k l / m , .`` move, ``q/z``, ``w/x``, ``e/c`` scale speed
and turn by 10 %, space or ``k`` stop at once, any other key (or half a second without a
movement key) stops smoothly, Ctrl-C quits. It starts at "speed 0.2 turn 1" (m/s, rad/s) and
ramps the output by at most 0.02 m/s and 0.1 rad/s per loop, within the model's limits.
The banner and status lines are printed on stdout (a terminal UI). The terminal's settings are
restored however it exits; with no terminal on stdin it prints one line and exits with status 2.
In a namespace (``ROS_NAMESPACE=tb3_1 rosrun tutorial_turtlebot teleop_key``) it drives that
robot, /tb3_1/cmd_vel, and the banner's first line names the topic.

Publishes:
    cmd_vel (geometry_msgs/Twist, queue 10): linear.x m/s, angular.z rad/s, once per loop
        (each key, or every 0.1 s of wall time without one); a zero Twist on exit.

Parameters:
    ~model, else model from the node's namespace upward (/tb3_1/model, then /model) (str,
        default $TURTLEBOT3_MODEL or burger): sets the limits, burger
        0.22 m/s and 2.84 rad/s, waffle and waffle_pi 0.26 m/s and 1.82 rad/s (unknown: burger).
"""
import sys

import rospy

from ..errors import UserError
from .lab_node import CommandPublisher, init_node, model_name
from ..robot_models import model_limits
from .teleop_keys import Teleop
from .terminal_keys import TerminalKeys

KEY_TIMEOUT = 0.1  # s of wall time to wait for a key in each loop


class TeleopKey:
    """Feeds keys from ``keys`` (a TerminalKeys) to ``teleop`` (a Teleop), publishes the result."""

    def __init__(self, teleop: Teleop, keys: TerminalKeys):
        self.teleop = teleop
        self.keys = keys
        self.publisher = CommandPublisher(queue_size=10)
        self.teleop.topic = self.publisher.topic

    def run(self) -> None:
        """Loop until shutdown; call inside ``with self.keys``."""
        print(self.teleop.banner(), flush=True)
        print(self.teleop.status(), flush=True)
        while not rospy.is_shutdown():
            out = self.teleop.step(self.keys.read_key(KEY_TIMEOUT))
            if out.text:
                print(out.text, flush=True)
            self.publisher.publish(out.linear, out.angular)


def main() -> None:
    """Entry point of scripts/teleop_key."""
    try:
        keys = TerminalKeys(sys.stdin)
    except UserError as err:
        sys.stderr.write("teleop_key: %s\n" % err)
        sys.exit(2)
    init_node("turtlebot3_teleop_keyboard")
    model = model_name()
    max_linear, max_angular = model_limits(model)
    node = TeleopKey(Teleop(max_linear, max_angular, model), keys)
    try:
        with keys:
            node.run()
    except EOFError as err:
        rospy.logerr("%s: stopping", err)
