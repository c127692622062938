"""The ``gazebo`` node: a pybullet stand-in for gzserver + gazebo_ros with a TurtleBot3.

It owns the clock: physics runs at ``~max_step_size`` of sim time per step, paced to
``~real_time_factor`` x wall time, and ``/clock`` is published for every node under
``/use_sim_time``. Every message of one step carries that step's sim time as its stamp.

Publications (relative names resolve in the node's namespace, as Gazebo's plugins do):
  /clock (rosgraph_msgs/Clock)          ~clock_rate Hz of sim time (100), at most
                                        ~pub_clock_frequency a wall second (1000)
  /tf (tf2_msgs/TFMessage)              every robot's odom -> base_footprint, 30 Hz; advertised
                                        while a robot with a drive plugin (or an SDF
                                        model with a diff drive) is in the world
  each robot's topics, made from its URDF's <gazebo> plugins: see robot_topics
  (sim.launch's robot in the node's namespace: odom, joint_states, scan, imu, camera/...,
  subscribing cmd_vel; one spawned with robot_namespace tb3_0: /tb3_0/odom, ...)
  each world model's sensors with a gazebo_ros plugin (a camera, a laser, a range sensor, a
  block laser): see world_sensor_topics; each model plugin (p3d, joint_state_publisher,
  hector's imu and gps) of a world model or robot: see model_plugin_topics
  A message type nobody subscribes to is not even computed.
Services: ~reset_simulation, ~reset_world, ~pause_physics, ~unpause_physics and the rest of
  Gazebo's world API: see world_api (which reaches the node through its public methods)
  (none of it with ~enable_ros_network false: then only /clock and the robots' topics),
  advertised just after the robots' topics, while the first steps run (node_start)
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
  ~enable_ros_network (true)  Gazebo's: false offers no world API (topics, services, physics
                              reconfigure); /clock and the robots' plugin topics stay
"""
import math
import time

import rospy
from rosgraph_msgs.msg import Clock
from tf2_msgs.msg import TFMessage

from .impl.own_clock import set_time
from .loop_pacer import WAKE_CHECK, LoopPacer
from .loop_requests import ANSWER_TIMEOUT, Busy, LoopRequests
from ..errors import RequestError, one_line
from ..sim.kinematics import yaw_from_quat
from .impl.nonblocking_publisher import make_nonblocking
from .impl.packed_messages import PackedClock
from . import part_times
from .part_times import TIMES
from .robot_topics import RobotTopics
from .running_topics import OUTPUT_ERROR_PERIOD
from .model_plugin_topics import ModelPluginTopics
from .world_sensor_topics import WorldSensorTopics
from .send_queue import SendQueue
from ..sim.world.simulation import Simulation
from ..sim.world.model_plugins import MODEL_PLUGINS
from ..sim.world.world_sensors import WORLD_SENSORS

SHUTDOWN_CHECK_STEPS = 200
# The longest (wall s) the loop keeps the GIL while another thread of the node waits for it:
# rospy's threads (a subscriber's handshake, a service call, the master's calls) take their
# turn this soon, as fast as possible too, when the loop no longer lets go of the GIL at every
# socket write (Python's default: 5 ms).
GIL_SWITCH_INTERVAL = 0.0005
# As fast as possible, pybullet casts a laser's rays on this many threads (WorldPhysics.
# ray_threads): the same hits, a 360-ray scan in about 60 % of the wall time.
FAST_RAY_THREADS = 2
# A robot output that fails (an exception making a scan, an image ...) is skipped and named in
# one line, at most once this many wall seconds per robot and output.


class SimNode:
    """Converts between the Simulation and ROS messages, and runs the stepping loop (``spin``).

    The loop's three helpers, each in its own module: the request queue (``requests``,
    loop_requests.LoopRequests: service and topic threads hand it work and wait for the answer),
    the pacer (``pacer``, loop_pacer.LoopPacer: when the next step may run on the wall clock)
    and the send queue (``sends``, send_queue.SendQueue: each step's messages, written when due
    without blocking). world_api uses the public methods below, never the attributes behind
    them."""

    def __init__(self, sim: Simulation, real_time_factor: float, paused: bool,
                 status_period: float, pub_clock_frequency: float = 1000.0,
                 enable_ros_network: bool = True, model_states_rate: float = 100.0):
        self.sim = sim
        self.requests = LoopRequests()   # what callbacks hand to the loop, and its wake-up
        self.stop_requested = False  # set by the SIGINT/SIGTERM handler of node_start.main()
        self.pacer = LoopPacer(real_time_factor, self.requests.wake, self._stopping,
                               pub_clock_frequency)
        self.paused = paused   # read by get_physics_properties; set by pause() and unpause()
        self.status_period = status_period
        self._next_status = self._next_report = 0.0   # wall s (set by spin)
        self.clock_packed = PackedClock()
        self.part_times_path = part_times.report_path()
        # Every message is written from this loop without a thread switch, and a subscriber
        # that stops reading loses old messages instead of stalling the simulation.
        self.sends = SendQueue()
        self.clock_pub = self.advertise("/clock", Clock)
        # tf2_ros.TransformBroadcaster's publisher (the transforms are packed_messages'), made
        # with the first robot that has a drive plugin (sync_robots)
        self.tf_pub = None
        self.publishers = {"clock": self._publish_clock}   # the world's outputs
        self.robot_topics = {}                               # robot name -> RobotTopics
        self._topics = []
        self._output_errors = {}   # (robot, output) -> the wall time its next error is logged
        self.sync_robots()
        # the world models' sensors, as their gazebo_ros plugins (world_sensor_topics)
        self.world_sensors = WorldSensorTopics(sim, self.advertise)
        self.add_output(WORLD_SENSORS, self.world_sensors.publish)
        # the models' and robots' model plugins: p3d, joint states, hector's (model_plugin_topics)
        self.model_plugins = ModelPluginTopics(sim, self.advertise, self)
        self.add_output(MODEL_PLUGINS, self.model_plugins.publish)
        # Gazebo's world API: reset, pause, model/link states, spawn, delete, physics
        # (gazebo/world_api.py), made by start_world_api after every sensor topic (test_camera.py
        # waits for it as the last; node_start: after the robots' topics, in a thread). Its
        # model_states schedule starts now, with the world's. With ~enable_ros_network false,
        # none of it (as gazebo_ros).
        self.world_api = None
        self.enable_ros_network = enable_ros_network
        self.model_states_rate = model_states_rate if enable_ros_network else 0.0
        if self.model_states_rate > 0:
            self.add_output("model_states", lambda _stamp: None)   # until the world API's
            sim.add_schedule("model_states", self.model_states_rate)
        if not enable_ros_network:
            rospy.loginfo("gazebo: ~enable_ros_network is false: no world API topics or services")

    def start_world_api(self) -> None:
        """Gazebo's world API on this node (world_api.WorldApi), unless ~enable_ros_network is
        false. Its publishing runs in the loop; making it touches nothing the loop uses, so it
        may run in any thread (node_start runs it in one of its own)."""
        if self.enable_ros_network:
            from .world_api import WorldApi   # gazebo_msgs' services, spawning: not on the
            self.world_api = WorldApi(self, self.model_states_rate)   # way to the first /scan

    # --- the node's public API (world_api) ------------------------------------------------------

    def advertise(self, topic: str, msg_type, queue_size: int = 1) -> rospy.Publisher:
        """A publisher whose messages go through the send queue: written from the loop without
        blocking (a subscriber that stops reading loses old messages)."""
        publisher = rospy.Publisher(topic, msg_type, queue_size=queue_size)
        make_nonblocking(publisher, self.sends.backlog)
        return publisher

    def add_output(self, name: str, publish) -> None:
        """``publish(stamp)`` is called in the loop whenever the simulation reports the world
        output ``name`` due (Simulation.add_schedule)."""
        self.publishers[name] = publish

    def run_in_loop(self, action, timeout: float = ANSWER_TIMEOUT):
        """Run ``action()`` in the loop between two steps and return what it returned (or raise
        what it raised); loop_requests.NotAnswered if the loop did not start it within
        ``timeout`` wall s (then it never runs). From any thread but the loop's."""
        return self.requests.call(action, timeout)

    def queue_in_loop(self, action, key=None) -> bool:
        """Run ``action()`` in the loop between two steps; return at once (its result and
        exceptions are dropped: ``action`` handles its own). With a ``key``, it replaces an
        action of that key not yet run (LoopRequests.put_latest). False when the loop's queue
        is full: ``action`` is dropped."""
        if key is not None:
            return self.requests.put_latest(key, action)
        try:
            self.requests.put(action)
        except Busy:
            return False
        return True

    def pause(self) -> None:
        """In the loop: stop stepping (requests are still answered)."""
        self.paused = True

    def unpause(self) -> None:
        """In the loop: step again, from now on the wall clock (paused time is not owed)."""
        self.paused = False
        self.pacer.restart(self.sim.time)

    def set_real_time_factor(self, rtf: float) -> None:
        """In the loop: pace at ``rtf`` sim s per wall s from now on (0 = as fast as possible);
        ValueError if it is below pacing.MIN_REAL_TIME_FACTOR."""
        self.pacer.set_rtf(rtf, self.sim.time)

    def sync_robots(self) -> None:
        """Give every robot of the simulation its topics, and take them from robots that are
        gone (after spawn_urdf_model and delete_model; run in the loop). A robot whose topics
        cannot be made is taken out of the world again, whatever of it was made (RobotTopics
        takes its own topics back), and RequestError says why in one line."""
        for name in [n for n in self.robot_topics if n not in self.sim.robots]:
            self.robot_topics.pop(name).close()
        self._sync_tf()
        failed = None
        for name, robot in list(self.sim.robots.items()):
            if name not in self.robot_topics:
                try:
                    self.robot_topics[name] = RobotTopics(robot, self.advertise, self.tf_pub)
                except Exception as err:  # noqa: BLE001 - one robot must not end the node
                    self.sim.remove_model(name)
                    failed = failed or RequestError("robot %r: its topics could not be made: %s"
                                                    % (name, one_line(err)))
                    continue
                for warning in robot.warnings:
                    rospy.logwarn("%s: %s", name, warning)
        self._topics = list(self.robot_topics.values())   # what the loop walks every step
        self._sync_tf()
        if failed is not None:
            raise failed

    def _sync_tf(self) -> None:
        """/tf is advertised while a robot or an SDF model with a drive plugin is in the world
        (the transform broadcaster of gazebo_ros_diff_drive, whatever its publishOdomTF), and
        not without."""
        wanted = (any(robot.drive_plugin for robot in self.sim.robots.values())
                  or bool(self.sim.model_plugins.drives(self.sim.time_ns)))
        if wanted and self.tf_pub is None:
            self.tf_pub = self.advertise("/tf", TFMessage, queue_size=100)
        elif not wanted and self.tf_pub is not None:
            self.tf_pub.unregister()
            self.tf_pub = None

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
            if name == "camera" and not self._camera_in_time(robot, topics):
                continue
            try:
                topics.publishers[name](stamp)
            except Exception as err:  # noqa: BLE001 - one robot's output must not end the node
                self._output_failed(robot.name, name, err)

    def _camera_in_time(self, robot, topics) -> bool:
        """Whether the robot's camera frame due now is drawn (LoopPacer.frame_in_time: not
        while the loop is late; then no image, no camera_info). The first time a subscribed
        camera keeps less than its rate, one warning says the rate it keeps."""
        in_time = self.pacer.frame_in_time(self.sim.time)
        topics.frames_skipped += not in_time
        if topics.frame_wanted("camera"):
            kept = topics.camera_watch.count(not in_time)
            if kept is not None:
                rospy.logwarn("gazebo: robot %s: its camera keeps %.1f of its %g images per "
                              "sim second: the loop is behind the wall clock and skips frames "
                              "(a smaller image or rate keeps them all)", robot.name, kept,
                              topics.camera_watch.rate_hz)
        return in_time

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
        set_time(stamp)
        if not self.pacer.clock_due(self.sim.time):   # Gazebo's ~pub_clock_frequency
            return
        TIMES.switch("serializing")
        self.clock_packed.write(stamp.secs, stamp.nsecs)
        self.clock_pub.publish_packed(self.clock_packed)

    def _restart_clock(self) -> None:
        """At start and after reset_simulation: pace from the sim time now, and everyone sees
        it at once (/clock goes whatever ~pub_clock_frequency's gap)."""
        self.pacer.restart(self.sim.time)
        self.pacer.clock_anew()
        self._publish_due([(None, "clock")])

    # --- input -----------------------------------------------------------------------------------

    def _run_requests(self) -> None:
        """Run the requests queued by service and topic callbacks, between two steps."""
        before = [self.sim.time_ns]

        def after_each():
            if self.sim.time_ns != before[0]:  # reset_simulation: everyone sees the new time now
                self.sends.send_due()          # after what was made before it
                self._restart_clock()
                before[0] = self.sim.time_ns
        self.requests.run_pending(after_each)
        self._use_ray_threads()   # set_physics_properties may have changed the pace

    def _use_ray_threads(self) -> None:
        """As fast as possible a scan's rays use the second core too (the wall time is what
        counts); at a pace, one thread (the CPU is what counts)."""
        self.sim.physics.ray_threads = 1 if self.pacer.rtf > 0 else FAST_RAY_THREADS

    def _apply_commands(self) -> None:
        """Hand each robot the cmd_vel that came since the last step."""
        for topics in self._topics:
            if topics.command is not None:
                topics.apply_command()

    def _stopping(self) -> bool:
        """Whether the node is to stop (Ctrl-C or ROS shut down); it stops from now on."""
        if self.stop_requested or rospy.is_shutdown():
            self.stop_requested = True
        return self.stop_requested

    # --- loop ------------------------------------------------------------------------------------

    def spin(self) -> None:
        """Step, publish and pace until ROS shuts down. Each turn: a look around (ROS shutdown,
        status, part times) once every SHUTDOWN_CHECK_STEPS turns and every turn while paused;
        the queued requests (requests); one physics step; its messages, sent when due (sends;
        as fast as possible gathered a SEND_GAP); at a pace, a sleep once the batch of steps
        ran far enough ahead (pacer)."""
        sim, pacer, sends, requests, times = self.sim, self.pacer, self.sends, self.requests, TIMES
        publish_due, apply_commands = self._publish_due, self._apply_commands
        self._restart_clock()
        self._use_ray_threads()
        self._next_status = time.monotonic() + self.status_period
        self._next_report = time.monotonic()
        steps = SHUTDOWN_CHECK_STEPS - 1   # the first turn looks around
        while not self.stop_requested:
            steps += 1
            if steps % SHUTDOWN_CHECK_STEPS == 0 and not self._look_around():
                break
            if requests:
                sends.send_due()   # a caller sees every message made before its answer
                self._run_requests()
            if sends:
                sends.flush()
            if self.paused:
                self._wait_paused()
                steps = SHUTDOWN_CHECK_STEPS - 1   # while paused every turn looks around
                continue
            # the pace: set_physics_properties may change it at any request
            if pacer.rtf <= 0:   # as fast as possible: sent together, once a SEND_GAP
                times.switch("physics")
                apply_commands()
                sends.send_gathered(publish_due, sim.step())
                continue
            sends.send_due_now()
            times.switch("physics")
            apply_commands()
            due = sim.step()
            if due:  # made now, sent when due on the wall clock
                sends.keep(publish_due, due, pacer.wall_of(sim.time))
            times.switch("other")
            batch_end = pacer.batch_end(sim.time)
            if batch_end is not None:
                self._send_on_time_until(batch_end)

    def _look_around(self) -> bool:
        """False once ROS shut down; else the status line and the part times when they are due
        (once every SHUTDOWN_CHECK_STEPS turns, and every turn while paused)."""
        if rospy.is_shutdown():
            return False
        if self.status_period > 0 and time.monotonic() >= self._next_status:
            self._next_status = time.monotonic() + self.status_period
            self._log_status()
        if self.part_times_path and time.monotonic() >= self._next_report:
            self._next_report = time.monotonic() + 1.0
            self._report_part_times()
        return True

    def _wait_paused(self) -> None:
        """Paused: send everything made, wait for a request (at most WAKE_CHECK wall s) and owe
        no wall time for the wait."""
        self.sends.send_due()
        self.requests.wait(WAKE_CHECK)
        self.pacer.restart(self.sim.time)

    def _send_on_time_until(self, wall_time: float) -> None:
        """Sleep until ``wall_time`` (the clock), sending each kept group of messages at its
        moment on the way: physics runs in batches, messages leave when their stamps are due.
        Requests that come meanwhile are run at once, and the batch's end is worked out again
        after them (they may pause, reset or change the pace); Ctrl-C ends the sleep."""
        pacer, sends = self.pacer, self.sends
        while True:
            next_due = sends.next_due()
            if next_due is not None and next_due < wall_time:
                if pacer.sleep_until(next_due):
                    sends.send_due(next_due)
                    continue
            elif pacer.sleep_until(wall_time):
                return
            if self.stop_requested:
                return
            self.requests.clear_wake()  # before the queue is read: a later request wakes again
            self._run_requests()
            if self.paused:
                return
            wall_time = pacer.batch_end(self.sim.time)
            if wall_time is None:
                return

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
