"""ROS glue shared by the lab nodes: checked parameters, the robot model, safe cmd_vel."""
import os
import signal
import sys
import threading
import time
from typing import Optional

import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan

from ..errors import UserError
from ..node_params import checked_number
from ..robot_models import MODEL_NAMES
from ..ros_names import is_legal_name
from ..node_output import line_buffered

# Wall-clock seconds the zero Twist is given to leave on shutdown (sim time may have stopped).
SHUTDOWN_GRACE = 0.3

# Seconds of ROS time between two checks for missing scans.
SCAN_CHECK_PERIOD = 0.1


def fatal(message: str) -> None:
    """One readable rospy.logfatal line, then exit status 2 (no traceback)."""
    rospy.logfatal(message)
    sys.exit(2)


def number_param(name: str, default: float, unit: str, above: Optional[float] = None,
                 at_least: Optional[float] = None, at_most: Optional[float] = None,
                 given: Optional[object] = None) -> float:
    """The parameter ``name`` (or the value ``given`` for it on the command line) as a float,
    or a fatal error unless it is a finite number with ``value > above``, ``value >= at_least``
    and ``value <= at_most`` (where given)."""
    value = rospy.get_param(name, default) if given is None else given
    try:
        return checked_number(rospy.resolve_name(name), value, unit, above, at_least, at_most)
    except UserError as err:
        fatal(str(err))


def init_node(name: str, **kwargs) -> None:
    """rospy.init_node(name, **kwargs), after checking the namespace the node runs in (from
    ROS_NAMESPACE, ``__ns:=`` or a launch file's ``ns``): one line on stderr and exit status 2
    if it is not a legal ROS name, which the master would refuse for every topic while the node
    waited forever."""
    namespace = rospy.get_namespace()
    if not is_legal_name(namespace):
        sys.stderr.write("%s: namespace %r is not a legal ROS name: use letters, digits, _ and /, "
                         "starting with a letter (e.g. tb3_1)\n" % (name, namespace))
        sys.exit(2)
    line_buffered()
    rospy.init_node(name, **kwargs)


def model_name() -> str:
    """The TurtleBot3 model: parameter ``~model``, else ``model`` looked up from the node's
    namespace upward (for a node in /tb3_2: /tb3_2/model, then /model; set by the launch
    files), else $TURTLEBOT3_MODEL, else burger. An unknown name gets a warning naming the valid
    ones."""
    found = rospy.resolve_name("~model") if rospy.has_param("~model") else None
    if found is None:
        found = rospy.search_param("model")
    if found is not None:
        model, source = rospy.get_param(found), "parameter " + found
    else:
        model, source = os.environ.get("TURTLEBOT3_MODEL", "burger"), "TURTLEBOT3_MODEL"
    if model not in MODEL_NAMES:
        rospy.logwarn("unknown TurtleBot3 model %r from %s: valid models are %s"
                      % (model, source, ", ".join(MODEL_NAMES)))
    return str(model)


def shut_down_on_signals() -> None:
    """Ctrl-C and SIGTERM shut ROS down from a thread of their own, for a node started with
    ``init_node(..., disable_signals=True)`` that publishes from its main thread. rospy's own
    handler runs the shutdown hooks inside the interrupted main thread: if that thread was in
    the middle of CommandPublisher.publish, the hook's zero Twist waited for the lock it held,
    forever. From another thread it waits only until the interrupted publish is done."""
    def handler(signum, _frame):
        threading.Thread(target=rospy.signal_shutdown,
                         args=("signal %d" % signum,), name="shutdown").start()
    signal.signal(signal.SIGINT, handler)
    signal.signal(signal.SIGTERM, handler)


class CommandPublisher:
    """Publisher of geometry_msgs/Twist on ``cmd_vel`` that, when the node shuts down, publishes
    one zero Twist, gives it a moment to leave, and ignores any later command (from callbacks
    still running in other threads)."""

    def __init__(self, queue_size: int = 1):
        self._publisher = rospy.Publisher("cmd_vel", Twist, queue_size=queue_size)
        self._lock = threading.Lock()
        self._stopped = False
        rospy.on_shutdown(self._stop)

    @property
    def topic(self) -> str:
        """The resolved topic name (after remapping)."""
        return self._publisher.resolved_name

    def publish(self, linear: float, angular: float) -> None:
        """Command ``linear`` m/s along +x and ``angular`` rad/s counter-clockwise."""
        msg = Twist()
        msg.linear.x = linear
        msg.angular.z = angular
        with self._lock:
            if not self._stopped:
                self._publisher.publish(msg)

    def _stop(self) -> None:
        with self._lock:
            self._stopped = True
            self._publisher.publish(Twist())
        time.sleep(SHUTDOWN_GRACE)


class ScanToCommand:
    """Calls ``decide(scan)`` -> (linear m/s, angular rad/s) on every sensor_msgs/LaserScan from
    ``scan`` and publishes the command on ``cmd_vel``. When no scan has come for
    ``scan_timeout`` s of ROS time it publishes one zero Twist and warns: no driving blind."""

    def __init__(self, decide, scan_timeout: float):
        self.decide = decide
        self.scan_timeout = rospy.Duration.from_sec(scan_timeout)
        self.publisher = CommandPublisher()
        self._lock = threading.Lock()
        self._last_scan = None   # ROS time of the last scan
        self._blind = True       # no fresh scan: the robot was told to stop
        self._waited = 0.0       # s of ROS time before the first scan
        self.subscriber = rospy.Subscriber("scan", LaserScan, self._on_scan, queue_size=1)
        self.timer = rospy.Timer(rospy.Duration.from_sec(SCAN_CHECK_PERIOD), self._on_timer,
                                 reset=True)

    def _on_scan(self, msg: LaserScan) -> None:
        with self._lock:
            self._last_scan = rospy.Time.now()
            self._blind = False
            self.publisher.publish(*self.decide(msg))

    def _on_timer(self, _event) -> None:
        with self._lock:
            if self._last_scan is None:
                self._waited += SCAN_CHECK_PERIOD
                if self._waited > self.scan_timeout.to_sec():
                    rospy.logwarn_throttle(10.0, "no scan on %s yet: waiting"
                                           % self.subscriber.resolved_name)
            elif not self._blind and rospy.Time.now() - self._last_scan > self.scan_timeout:
                self._blind = True
                self.publisher.publish(0.0, 0.0)
                rospy.logwarn("no scan on %s for %g s: stopped until scans come again"
                              % (self.subscriber.resolved_name, self.scan_timeout.to_sec()))
