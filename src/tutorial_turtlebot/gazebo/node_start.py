"""The ``gazebo`` node's start (``main``, scripts/sim's entry), ordered for its first /scan.

On the way to the first physics step only what a robot's topics need is imported and built:
rospy, the simulation (world and robot) and the robots' and world models' topics. The rest
comes after, and this is why:

- Gazebo's world API (world_api.WorldApi: gazebo_msgs' service classes, the spawn code, some
  thirty services, model and link states, performance metrics, the physics' dynamic_reconfigure)
  is imported and made in a thread of its own once the robots' topics are advertised: 60 to
  100 ms that no sensor needs, much of it waiting for the master. Its clients wait for the
  services (wait_for_service), as for Gazebo's; everything under /gazebo is there a moment
  (about 0.1 s) after the first step. Its model_states schedule starts before the first step
  (SimNode), so the states keep their stamps.
- Meanwhile the first step waits, at most CONNECT_WAIT wall s, until the subscribers the master
  already lists for the robots' laser scans are connected (the master tells a subscriber of a
  new publisher up to 0.1 s after it registered: rosmaster's workers look for work every
  0.1 s). A laser's period (0.2 s on a TurtleBot3) is the longest of a robot's outputs, so its
  first reading is the dearest to miss: a node started before the sim (a test, rostopic echo)
  gets the first step's scan, at sim time 0.0025 s, not the next one 0.2 s later. Only the
  lasers: robot_state_publisher takes 0.2 to 0.3 s to connect to joint_states, which come at
  30 Hz anyway. The physics, stamps and messages are those of any start; only the wall time
  at which sim time starts moves.

Elsewhere on that path: scripts/sim keeps the garbage collector off while the modules load
(main then freezes them: never scanned again); impl/registration_poll spares init_node's 0.1 s
poll; single_instance looks for a master with a plain connect before it imports XML-RPC;
tools/setup.sh byte-compiles the package and the workspace's messages; sim/devices/camera
imports PIL at its first JPEG. doc/benchmark.md has the measured split.
Parameters: sim_node's docstring.
"""
import gc
import math
import os
import signal
import sys
import threading
import time

import rosgraph
import rosgraph.names
import rospy

from .impl import (connection_caps, publisher_connects, registration_poll, service_guard,
                   tcpros_guard, unreachable_publishers)
from .impl.master_watch import MasterWatch
from .impl.own_clock import own_the_clock
from .sim_node import GIL_SWITCH_INTERVAL, SimNode
from .single_instance import refuse_if_running
from ..errors import RequestError, UserError, one_line
from ..node_output import line_buffered
from ..node_params import checked_number, converted
from ..sim.files.meshes import mesh_cache
from ..sim.files.sdf.world_catalogue import world_from_command_line
from ..sim.world.pacing import check_rtf
from ..sim.world.simulation import SimConfig, Simulation

# wall s the first step waits, at most, for the subscribers already listed: a rospy node takes
# tens of ms to connect, a roscpp one (RViz) up to 0.3 s
CONNECT_WAIT = 0.5
CONNECT_POLL = 0.001  # wall s between two looks at their connections


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
    return converted("~" + name, value, kind)


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


def _node_params():
    """(SimConfig, real_time_factor, paused, status_period, pub_clock_frequency) of the node's
    private params; UserError (one line) when one is bad. gui:=true without a display runs
    headless, with a warning."""
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
    pub_clock_frequency = checked_number(
        "~pub_clock_frequency", _param("pub_clock_frequency", 1000.0, float), "Hz, 0 = no limit",
        at_least=0.0)
    if config.gui and not os.environ.get("DISPLAY"):
        rospy.logwarn("gazebo: gui:=true but there is no display (DISPLAY is unset): "
                      "running headless")
        config.gui = False
    return config, real_time_factor, paused, status_period, pub_clock_frequency


def _log_warning(line: str) -> None:
    """One warning line as it is (at most 200 characters): /rosout names the node."""
    rospy.logwarn("%s", line)


def _log_start(sim: Simulation, config: SimConfig, real_time_factor: float) -> None:
    """What the world file names but Gazebo would skip, what its building could not draw as
    its files say (sim.physics.warnings: textures), the robot (or none) and the camera."""
    for warning in tuple(sim.world.warnings) + tuple(sim.physics.warnings):
        _log_warning(warning)
    if sim.robot is not None:
        rospy.loginfo("%s in %s at (%.2f, %.2f) yaw %.2f, physics step %g s, real-time factor %s",
                      config.model, config.world, sim.spawn[0], sim.spawn[1], sim.spawn[3],
                      config.time_step, real_time_factor or "max")
    else:
        rospy.loginfo("%s without a robot (spawn_model adds robots), physics step %g s, "
                      "real-time factor %s", config.world, config.time_step,
                      real_time_factor or "max")
    if sim.robot is not None and sim.robot.camera is not None:
        spec = sim.robot.camera_spec
        rospy.loginfo("camera %dx%d, %.1f deg, %g Hz, rendered by %s", spec.width, spec.height,
                      math.degrees(spec.hfov), spec.rate, sim.robot.camera.renderer_name)


def start_world_api(node: SimNode) -> threading.Thread:
    """``node.start_world_api()`` in a thread of its own (it is off the path to the first
    /scan). If it fails, one fatal line and the node stops, as when it failed in main."""
    def run():
        try:
            node.start_world_api()
        except Exception as err:  # noqa: BLE001 - said in one line; the node ends
            rospy.logfatal("gazebo: the world API could not start: %s", one_line(err))
            node.stop_requested = True
    thread = threading.Thread(target=run, name="world_api_start", daemon=True)
    thread.start()
    return thread


def wait_for_subscribers(node: SimNode, timeout: float = CONNECT_WAIT) -> float:
    """Wait until the subscribers the master lists for the robots' laser scans are connected,
    at most ``timeout`` wall s (none while paused: no step is near). The wall s waited."""
    start = time.monotonic()
    publishers = {pub.resolved_name: pub for topics in node.robot_topics.values()
                  for pub in (topics.pubs[laser.output] for laser in topics.robot.lasers)}
    if node.paused or not publishers:
        return 0.0
    me = rospy.get_name()
    try:
        _, subscribed, _ = rosgraph.Master(me).getSystemState()
    except Exception:  # noqa: BLE001 - the wait is a courtesy: without the list, none
        return 0.0
    wanted = [(publishers[topic], sum(name != me for name in names))
              for topic, names in subscribed if topic in publishers]
    while (any(pub.get_num_connections() < count for pub, count in wanted)
           and time.monotonic() - start < timeout):
        time.sleep(CONNECT_POLL)
    return time.monotonic() - start


def main() -> None:
    """Entry point of ``scripts/sim``."""
    gc.freeze()   # the modules loaded stay: left out of the collector's scans from now on,
    gc.enable()   # which were off while they loaded (scripts/sim)
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
    registration_poll.install()   # init_node returns once registered, not at the next 0.1 s
    rospy.init_node("gazebo", disable_signals=True)
    # Before the first topic and service: a client that stalls in its handshake (or is not a
    # ROS client at all) must not keep the others out.
    tcpros_guard.install()
    # Threads are a budget: capped subscribers and callers, closed and stalled subscribers
    # dropped, a bounded number of publishers connected to (before unreachable_publishers).
    connection_caps.install()
    publisher_connects.install()
    # Before the first subscription: a publisher it cannot reach is named in one line.
    unreachable_publishers.install()
    # Before the first service: a malformed request is one throttled line, not a traceback.
    service_guard.install()
    # The sim is the clock: its rospy time is set in _publish_clock, not from its own /clock.
    own_the_clock()
    mesh_cache.warning_sink = _log_warning     # the disk mesh cache's one line, if any
    try:
        config, real_time_factor, paused, status_period, pub_clock_frequency = _node_params()
        enable_ros_network = _param("enable_ros_network", True, bool)
        model_states_rate = _param("model_states_rate", 100.0, float)
        sim = Simulation(config)
    except UserError as err:
        rospy.logfatal("gazebo: %s", err)
        sys.exit(2)
    _log_start(sim, config, real_time_factor)
    try:
        node = SimNode(sim, real_time_factor, paused, status_period, pub_clock_frequency,
                       enable_ros_network, model_states_rate)
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
    start_world_api(node)   # the lazy start (this module's docstring)
    wait_for_subscribers(node)
    try:
        node.spin()
    finally:
        sim.close()
        rospy.signal_shutdown("simulation stopped")
