"""The ``gazebo`` node: a pybullet stand-in for gzserver + gazebo_ros with a TurtleBot3.

It owns the clock: physics runs at ``~max_step_size`` of sim time per step, paced to
``~real_time_factor`` x wall time, and ``/clock`` is published for every node under
``/use_sim_time``. Every message of one step carries that step's sim time as its stamp.

Publications (relative names resolve in the node's namespace, as Gazebo's plugins do):
  /clock (rosgraph_msgs/Clock)          ~clock_rate Hz of sim time (100), at most
                                        ~pub_clock_frequency a wall second (1000)
  /tf (tf2_msgs/TFMessage)              every robot's odom -> base_footprint, 30 Hz
  each robot's topics, made from its URDF's <gazebo> plugins: see robot_topics
  (sim.launch's robot in the node's namespace: odom, joint_states, scan, imu, camera/...,
  subscribing cmd_vel; one spawned with robot_namespace tb3_0: /tb3_0/odom, ...)
  A message type nobody subscribes to is not even computed.
Services (std_srvs/Empty):
  ~reset_simulation (time back to 0, robot to spawn), ~reset_world (robot to spawn),
  ~pause_physics, ~unpause_physics
Parameters (private):
  ~model (burger)             burger, waffle or waffle_pi
  ~spawn_robot (true)         false: no robot of its own; robots come by spawn_urdf_model
  ~world (turtlebot3_world)   a name from worlds/ or a path to an SDF file
  ~x_pos, ~y_pos, ~yaw        spawn of base_footprint (m, m, rad); empty = the world's spawn
  ~z_pos (0.0)                m
  ~camera (empty)             empty: the camera the URDF declares (waffle, waffle_pi); false:
                              none; true on a burger: the AutoRace burger's URDF and camera
  ~lidar_model (gazebo)       gazebo (as the URDF declares) or lds01 (the real driver: 0.0)
  ~lidar_samples (empty)      rays per scan over the same sweep; empty = the URDF's (360)
  ~robot_name (empty)         the robot's model name; empty = turtlebot3_gazebo's for the world
  ~model_states_rate (100.0)  Hz of sim time of ~model_states, ~link_states (see world_api)
  ~odom_source (empty)        world (ground truth from the spawn pose) or encoders (from 0);
                              empty = the URDF's odometrySource (world)
  ~clamp_cmd_vel (true)       hold cmd_vel to the model's limits, as the real firmware does
  (lidar_model, lidar_samples, odom_source, clamp_cmd_vel apply to spawned robots too)
  ~gui (false)                open pybullet's 3D window (only where a display exists)
  ~real_time_factor (1.0)     sim seconds per wall second; 0 = as fast as possible
  ~paused (false)             start with physics paused
  ~max_step_size (0.0025)     s of sim time per physics step
  ~clock_rate (100.0)         Hz of sim time
  ~pub_clock_frequency (1000.0)  Gazebo's: at most this many /clock messages a wall second
                              (0 = no limit). At real time it never bites; as fast as
                              possible it spares every node under /use_sim_time the clock
                              messages it could not tell apart (1 ms of wall time each)
  ~status_period (10.0)       wall s between status lines (sim time, factor, pose); 0 = never
  ~seed (0)                   laser noise seed
"""
import math
import os
import signal
import sys
import time

import rosgraph.names
import rospy
import rospy.impl.simtime
from rosgraph_msgs.msg import Clock
from tf2_msgs.msg import TFMessage
from rospy.rostime import _set_rostime
from std_srvs.srv import Empty, EmptyResponse

from .impl import tcpros_guard, unreachable_publishers
from .loop_requests import ANSWER_TIMEOUT, LoopRequests, NotAnswered
from .impl.master_watch import MasterWatch
from .world_api import WorldApi
from ..errors import UserError, one_line
from ..node_output import line_buffered
from ..sim.kinematics import yaw_from_quat
from .impl.nonblocking_publisher import Backlog, make_nonblocking
from .impl.packed_messages import PackedClock
from . import part_times
from .part_times import TIMES
from ..sim.world.pacing import Pacer, check_rtf
from .robot_topics import RobotTopics
from .single_instance import refuse_if_running
from ..sim.world.simulation import SimConfig, Simulation
from ..sim.world.world_models import RequestError
from ..sim.files.world_sdf import world_from_command_line

SHUTDOWN_CHECK_STEPS = 200
# The longest the loop sleeps (wall s) without looking at Ctrl-C and ROS shutdown; a request
# (a service call, a topic's command) wakes it at once, however slow the pace.
WAKE_CHECK = 0.1
# Sleeps shorter than this (wall s) are plain sleeps, which a request does not cut short (it
# waits at most this long): at real time every sleep is one, and costs half the CPU of a wait.
SHORT_SLEEP = 0.025
# The longest (wall s) the loop keeps the GIL while another thread of the node waits for it:
# rospy's threads (a subscriber's handshake, a service call, the master's calls) take their
# turn this soon, as fast as possible too, when the loop no longer lets go of the GIL at every
# socket write (Python's default: 5 ms).
GIL_SWITCH_INTERVAL = 0.0005
# As fast as possible, what the steps make leaves at most this long (wall s) after it is made,
# a subscriber's messages of that time in one write: a write and a wake-up of the subscriber
# per message cost more than the physics. What clients wait for, step by step (a scan, a camera
# frame), leaves at once, with everything made before it.
SEND_GAP = 0.002
SEND_AT_ONCE = ("scan", "camera")
# As fast as possible, pybullet casts a laser's rays on this many threads (WorldPhysics.
# ray_threads): the same hits, a 360-ray scan in about 60 % of the wall time.
FAST_RAY_THREADS = 2
# A robot output that fails (an exception making a scan, an image ...) is skipped and named in
# one line, at most once this many wall seconds per robot and output.
OUTPUT_ERROR_PERIOD = 10.0


_private_params = None   # the node's private parameters, read from the master once


def _param(name, default, kind, allow_empty=False):
    """A private param converted to ``kind`` (float, int, bool, str); UserError if it cannot be.
    With ``allow_empty`` an empty value gives None. All of them come in one master call."""
    global _private_params
    if _private_params is None:
        params = rospy.get_param("~", {})
        _private_params = params if isinstance(params, dict) else {}
    value = _private_params.get(name, default)
    if allow_empty and (value is None or (isinstance(value, str) and value.strip() == "")):
        return None
    try:
        if kind is bool:
            if isinstance(value, str) and value.lower() in ("true", "false"):
                return value.lower() == "true"
            if isinstance(value, bool):
                return value
            raise ValueError
        if kind is float and isinstance(value, bool):
            raise ValueError
        if kind is int and not float(value).is_integer():
            raise ValueError
        return kind(value)
    except (TypeError, ValueError):
        raise UserError("parameter ~%s: %r is not a %s" % (name, value, kind.__name__)) from None


def read_config() -> SimConfig:
    """The SimConfig named by the node's private params (raises UserError when one is bad)."""
    return SimConfig(
        model=_param("model", "burger", str),
        world=world_from_command_line(_param("world", "turtlebot3_world", str)),
        x=_param("x_pos", None, float, allow_empty=True),
        y=_param("y_pos", None, float, allow_empty=True),
        z=_param("z_pos", 0.0, float),
        yaw=_param("yaw", None, float, allow_empty=True),
        camera=_param("camera", None, bool, allow_empty=True),
        lidar_model=_param("lidar_model", "gazebo", str),
        lidar_samples=_param("lidar_samples", None, int, allow_empty=True),
        robot_name=_param("robot_name", None, str, allow_empty=True),
        odom_source=_param("odom_source", None, str, allow_empty=True),
        spawn_robot=_param("spawn_robot", True, bool),
        clamp_cmd_vel=_param("clamp_cmd_vel", True, bool),
        gui=_param("gui", False, bool),
        time_step=_param("max_step_size", 0.0025, float),
        clock_rate=_param("clock_rate", 100.0, float),
        seed=_param("seed", 0, int),
    )


class SimNode:
    """Converts between the Simulation and ROS messages, and runs the stepping loop."""

    def __init__(self, sim: Simulation, real_time_factor: float, paused: bool,
                 status_period: float, pub_clock_frequency: float = 1000.0):
        self.sim = sim
        self.pacer = Pacer(real_time_factor)
        self.paused = paused
        self.status_period = status_period
        # /clock's least wall-time gap (s): Gazebo's ~pub_clock_frequency; 0 = none
        self.clock_gap = 1.0 / pub_clock_frequency if pub_clock_frequency > 0 else 0.0
        self._next_clock_wall = -math.inf
        self.clock_packed = PackedClock()
        self.part_times_path = part_times.report_path()
        self.requests = LoopRequests()   # what callbacks hand to the loop, and its wake-up
        self.stop_requested = False  # set by the SIGINT/SIGTERM handler of main()
        # Every message is written from this loop without a thread switch, and a subscriber
        # that stops reading loses old messages instead of stalling the simulation.
        self.backlog = Backlog()
        self.clock_pub = self._publisher("/clock", Clock)
        # tf2_ros.TransformBroadcaster's publisher (the transforms are packed_messages')
        self.tf_pub = self._publisher("/tf", TFMessage, queue_size=100)
        self.publishers = {"clock": self._publish_clock}   # the world's outputs
        self.robot_topics = {}                               # robot name -> RobotTopics
        self._topics = []
        self._output_errors = {}   # (robot, output) -> the wall time its next error is logged
        self.sync_robots()
        for name, action in (("reset_simulation", sim.reset_simulation),
                             ("reset_world", sim.reset_world),
                             ("pause_physics", self._pause), ("unpause_physics", self._unpause)):
            rospy.Service("~" + name, Empty, self._service_handler(name, action))
        # Gazebo's world API: model/link states, spawn, delete, physics (gazebo/world_api.py);
        # advertised after every sensor topic (test_camera.py waits for it as the last).
        self.world_api = WorldApi(self, _param("model_states_rate", 100.0, float))

    def _publisher(self, topic, msg_type, queue_size=1) -> rospy.Publisher:
        publisher = rospy.Publisher(topic, msg_type, queue_size=queue_size)
        make_nonblocking(publisher, self.backlog)
        return publisher

    def sync_robots(self) -> None:
        """Give every robot of the simulation its topics, and take them from robots that are
        gone (after spawn_urdf_model and delete_model; run in the loop). A robot whose topics
        cannot be made is taken out of the world again, whatever of it was made (RobotTopics
        takes its own topics back), and RequestError says why in one line."""
        for name in [n for n in self.robot_topics if n not in self.sim.robots]:
            self.robot_topics.pop(name).close()
        failed = None
        for name, robot in list(self.sim.robots.items()):
            if name not in self.robot_topics:
                try:
                    self.robot_topics[name] = RobotTopics(robot, self._publisher, self.tf_pub)
                except Exception as err:  # noqa: BLE001 - one robot must not end the node
                    self.sim.models.remove(name)
                    failed = failed or RequestError("robot %r: its topics could not be made: %s"
                                                    % (name, one_line(err)))
                    continue
                for warning in robot.warnings:
                    rospy.logwarn("%s: %s", name, warning)
        self._topics = list(self.robot_topics.values())   # what the loop walks every step
        if failed is not None:
            raise failed

    # --- messages --------------------------------------------------------------------------------

    def _publish_due(self, due) -> None:
        """Publish what is due at this step, all with this step's stamp. /clock runs on its own
        fixed rate; a stamp may be ahead of it by less than one clock period (or, as fast as
        possible, than ~pub_clock_frequency's wall gap), never behind, so tf lookups at the
        current time never need to extrapolate."""
        if not due:
            return
        TIMES.switch("other")
        stamp = rospy.Time(*divmod(self.sim.time_ns, 1_000_000_000))
        for robot, name in due:
            if robot is None:
                self.publishers[name](stamp)
                continue
            topics = self.robot_topics.get(robot.name)
            if topics is None:   # (its topics could not be made: it is being taken out)
                continue
            try:
                topics.publishers[name](stamp)
            except Exception as err:  # noqa: BLE001 - one robot's output must not end the node
                self._output_failed(robot.name, name, err)

    def _output_failed(self, robot: str, output: str, err: Exception) -> None:
        """One line about a robot's output that failed, at most once every OUTPUT_ERROR_PERIOD
        wall seconds per robot and output; the loop goes on."""
        key, now = (robot, output), time.monotonic()
        if now < self._output_errors.get(key, -math.inf):
            return
        self._output_errors[key] = now + OUTPUT_ERROR_PERIOD
        rospy.logerr("gazebo: robot %s: its %s failed and was skipped: %s", robot, output,
                     one_line(err))

    def _publish_clock(self, stamp) -> None:
        # The sim's own rospy time follows its clock directly (see main: no /clock round trip).
        _set_rostime(stamp)
        if self.clock_gap:   # Gazebo's throttle, by the wall time the message leaves at
            pacer = self.pacer
            wall = pacer.wall_of(self.sim.time) if pacer.rtf > 0 else time.monotonic()
            if wall < self._next_clock_wall:
                return
            self._next_clock_wall = wall + self.clock_gap
        TIMES.switch("serializing")
        self.clock_packed.write(stamp.secs, stamp.nsecs)
        self.clock_pub.publish_packed(self.clock_packed)

    # --- input -----------------------------------------------------------------------------------

    def _service_handler(self, name, action):
        """An Empty service (reset, pause) whose action runs in the loop. A failure is a
        service error that says what happened: the loop did not start it in time (then it never
        runs), or the action raised (named in one line)."""
        def handle(_request):
            try:
                self.requests.call(action, ANSWER_TIMEOUT)
            except NotAnswered:
                raise rospy.ServiceException(
                    "%s: the simulation loop did not answer within %g s; nothing was done"
                    % (name, ANSWER_TIMEOUT)) from None
            except Exception as err:  # noqa: BLE001 - named to the caller, the loop goes on
                rospy.logerr("%s: internal error: %s", name, one_line(err))
                raise rospy.ServiceException("%s: internal error: %s"
                                             % (name, one_line(err))) from None
            return EmptyResponse()
        return handle

    def _pause(self) -> None:
        self.paused = True

    def _unpause(self) -> None:
        self.paused = False
        self.pacer.restart(self.sim.time)  # paused time is not owed

    def _handle_requests(self) -> None:
        """Run the requests queued by service and topic callbacks, between two steps."""
        before = [self.sim.time_ns]

        def after_each():
            if self.sim.time_ns != before[0]:  # reset_simulation: everyone sees the new time now
                self.backlog.send_due()          # after what was made before it
                self.pacer.restart(self.sim.time)
                self._next_clock_wall = -math.inf
                self._publish_due([(None, "clock")])
                before[0] = self.sim.time_ns
        self.requests.run_pending(after_each)

    # --- loop ------------------------------------------------------------------------------------

    def spin(self) -> None:
        """Step, publish and pace until ROS shuts down."""
        sim, pacer, backlog, times = self.sim, self.pacer, self.backlog, TIMES
        pacer.restart(sim.time)
        self._publish_due([(None, "clock")])
        next_status = time.monotonic() + self.status_period
        next_report = next_send = time.monotonic()
        steps = 0
        while True:
            steps += 1
            if self.stop_requested:
                break
            if steps % SHUTDOWN_CHECK_STEPS == 0 or self.paused:
                if rospy.is_shutdown():
                    break
                if self.status_period > 0 and time.monotonic() >= next_status:
                    next_status = time.monotonic() + self.status_period
                    self._log_status()
                if self.part_times_path and time.monotonic() >= next_report:
                    next_report = time.monotonic() + 1.0
                    self._report_part_times()
            if self.requests:
                backlog.send_due()   # a caller sees every message made before its answer
                self._handle_requests()
            if backlog:
                backlog.flush()
            paced = pacer.rtf > 0  # set_physics_properties may change it at any request
            # as fast as possible a scan's rays use the second core too (the wall time is what
            # counts); at a pace, one thread (the CPU is what counts)
            sim.physics.ray_threads = 1 if paced else FAST_RAY_THREADS
            if paced and backlog.next_due() is not None:
                backlog.send_due(time.monotonic())
            if self.paused:
                backlog.send_due()
                self.requests.wake.wait(0.1)
                self.requests.wake.clear()
                pacer.restart(sim.time)
                continue
            times.switch("physics")
            for topics in self._topics:
                if topics.command is not None:
                    topics.apply_command()
            due = sim.step()
            if not paced:   # as fast as possible: sent together, once a SEND_GAP
                at_once = False
                if due:
                    backlog.hold()
                    self._publish_due(due)
                    backlog.keep_until(0.0)
                    at_once = any(name in SEND_AT_ONCE for _, name in due)
                times.switch("other")
                if backlog.next_due() is not None:
                    now = time.monotonic()
                    if at_once or now >= next_send:
                        backlog.send_due()
                        next_send = now + SEND_GAP
                continue
            if due:  # made now, sent when due on the wall clock
                backlog.hold()
                self._publish_due(due)
                backlog.keep_until(pacer.wall_of(sim.time))
            times.switch("other")
            batch_end = pacer.batch_end(sim.time)
            if batch_end is not None:
                self._send_on_time_until(batch_end)

    def _send_on_time_until(self, wall_time: float) -> None:
        """Sleep until ``wall_time`` (the clock), sending each kept group of messages at its
        moment on the way: physics runs in batches, messages leave when their stamps are due.
        Requests that come meanwhile are run at once, and the batch's end is worked out again
        after them (they may pause, reset or change the pace); Ctrl-C ends the sleep."""
        pacer, backlog = self.pacer, self.backlog
        while True:
            next_due = backlog.next_due()
            if next_due is not None and next_due < wall_time:
                if self._sleep_until(next_due):
                    backlog.send_due(next_due)
                    continue
            elif self._sleep_until(wall_time):
                return
            if self.stop_requested:
                return
            self.requests.wake.clear()  # before the queue is read: a later request wakes again
            self._handle_requests()
            if self.paused:
                return
            wall_time = pacer.batch_end(self.sim.time)
            if wall_time is None:
                return

    def _sleep_until(self, wall_time: float) -> bool:
        """Sleep until the clock reads ``wall_time``: True then; False as soon as a request is
        queued or the node is to stop."""
        return TIMES.run("idle", self._sleep, wall_time)

    def _sleep(self, wall_time: float) -> bool:
        wake = self.requests.wake
        while True:
            delay = wall_time - time.monotonic()
            if delay < Pacer.SHORTEST_SLEEP:
                return True
            if delay < SHORT_SLEEP:
                time.sleep(delay)
                return True
            if wake.wait(delay if delay < WAKE_CHECK else WAKE_CHECK):
                return False
            if delay >= WAKE_CHECK and (self.stop_requested or rospy.is_shutdown()):
                self.stop_requested = True
                return False

    def _report_part_times(self) -> None:
        """The loop's time by part so far, into the file TUTORIAL_TURTLEBOT_PART_TIMES names
        (part_times; make bench reads it)."""
        try:
            with open(self.part_times_path, "w") as f:
                f.write(TIMES.line(self.sim.time))
        except OSError as err:
            rospy.logwarn("gazebo: cannot write the part times to %s: %s; not writing them "
                          "again", self.part_times_path, err)
            self.part_times_path = None

    def _log_status(self) -> None:
        factor = self.pacer.achieved(self.sim.time)
        poses = []
        for robot in list(self.sim.robots.values())[:4]:
            (x, y, _), orn = robot.ground_truth()
            poses.append("%s x %.2f y %.2f yaw %.2f" % (robot.name, x, y, yaw_from_quat(orn)))
        if len(self.sim.robots) > 4:
            poses.append("%d more robots" % (len(self.sim.robots) - 4))
        rospy.loginfo("sim time %.1f s, real-time factor %s, %s%s",
                      self.sim.time, "n/a" if factor is None else "%.2f" % factor,
                      "; ".join(poses) or "no robot", " (paused)" if self.paused else "")


def _own_the_clock() -> None:
    """The sim is the clock: under /use_sim_time rospy would subscribe this node to /clock and
    deserialize every message it publishes itself; instead its rospy time is set directly in
    _publish_clock. (rospy.impl.simtime keeps that subscription as ``_clock_sub``.)"""
    subscription = getattr(rospy.impl.simtime, "_clock_sub", None)
    if subscription is not None:
        subscription.unregister()
        rospy.impl.simtime._clock_sub = None


def main() -> None:
    """Entry point of ``scripts/sim``."""
    # A second /gazebo would make the master shut the running one down: look before registering.
    try:
        refuse_if_running(rosgraph.names.ns_join(rospy.names.get_namespace(), "gazebo"))
    except UserError as err:
        sys.stderr.write("gazebo: %s\n" % err)
        sys.exit(2)
    # rospy's own SIGINT handler shuts ROS down from inside whatever the loop is doing (often a
    # publish, holding its locks) and could hang there; here the signal only asks the loop to
    # stop, and the loop shuts ROS down when it is between steps.
    sys.setswitchinterval(GIL_SWITCH_INTERVAL)
    line_buffered()
    rospy.init_node("gazebo", disable_signals=True)
    # Before the first topic and service: a client that stalls in its handshake (or is not a
    # ROS client at all) must not keep the others out.
    tcpros_guard.install()
    # Before the first subscription: a publisher it cannot reach is named in one line.
    unreachable_publishers.install()
    _own_the_clock()
    try:
        config = read_config()
        real_time_factor = _param("real_time_factor", 1.0, float)
        try:
            if not math.isfinite(real_time_factor):
                raise ValueError("real_time_factor must be finite, got %r" % real_time_factor)
            check_rtf(real_time_factor)
        except ValueError as err:
            raise UserError("parameter ~%s" % err) from None
        paused = _param("paused", False, bool)
        status_period = _param("status_period", 10.0, float)
        pub_clock_frequency = _param("pub_clock_frequency", 1000.0, float)
        if not (pub_clock_frequency >= 0 and math.isfinite(pub_clock_frequency)):
            raise UserError("parameter ~pub_clock_frequency: %r is not a frequency of 0 (no "
                            "limit) or more Hz" % pub_clock_frequency)
        if config.gui and not os.environ.get("DISPLAY"):
            rospy.logwarn("gazebo: gui:=true but there is no display (DISPLAY is unset): "
                          "running headless")
            config.gui = False
        sim = Simulation(config)
    except UserError as err:
        rospy.logfatal("gazebo: %s", err)
        sys.exit(2)
    for warning in sim.world.warnings:      # what the world file names but Gazebo would skip
        rospy.logwarn("gazebo: %s", warning)
    if sim.robot is not None:
        rospy.loginfo("%s in %s at (%.2f, %.2f) yaw %.2f, physics step %g s, real-time factor %s",
                      config.model, config.world, sim.spawn[0], sim.spawn[1], sim.spawn[3],
                      config.time_step, real_time_factor or "max")
    else:
        rospy.loginfo("%s without a robot (spawn_model adds robots), physics step %g s, "
                      "real-time factor %s", config.world, config.time_step,
                      real_time_factor or "max")
    if sim.robot is not None and sim.robot.camera is not None:
        spec = sim.camera_spec
        rospy.loginfo("camera %dx%d, %.1f deg, %g Hz, rendered by %s", spec.width, spec.height,
                      math.degrees(spec.hfov), spec.rate, sim.camera.renderer_name)
    try:
        node = SimNode(sim, real_time_factor, paused, status_period, pub_clock_frequency)
    except RequestError as err:   # the robot's topics (sync_robots)
        rospy.logfatal("gazebo: %s", err)
        sim.close()
        sys.exit(2)
    # A restarted master is told again of every topic, service and robot description.
    MasterWatch(lambda: [robot.namespace for robot in list(sim.robots.values())]).start()

    def request_stop(_signum, _frame):
        node.stop_requested = True
    signal.signal(signal.SIGINT, request_stop)
    signal.signal(signal.SIGTERM, request_stop)
    try:
        node.spin()
    finally:
        sim.close()
        rospy.signal_shutdown("simulation stopped")
