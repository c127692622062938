"""Gazebo's world API on the ``/gazebo`` node: the names, types and answers of
gazebo_ros_api_plugin, over sim/world_control.

Publications (only while subscribed):
  ~model_states (gazebo_msgs/ModelStates)  every model: world file, robot, spawned (in order),
                                           every ``~model_states_rate`` Hz of sim time
  ~link_states (gazebo_msgs/LinkStates)    every link, scoped "model::link", as model_states
  ~performance_metrics (gazebo_msgs/PerformanceMetrics)  about once a wall second: stamp = sim
      time, real_time_factor over the last period, and per sensor of every robot (laser, IMU,
      camera; name "world::model::link::sensor", the link being the one the sensor's link is
      lumped into, the IMU named by its gazebo_ros_imu plugin) sim_update_rate (readings per
      sim second), real_update_rate (per wall second) and fps (camera frames per wall second;
      -1 for other sensors, as gazebo_ros). A reading nobody subscribes to is not even made,
      so such a sensor reports 0.
Subscriptions (the services' topic twins; the answer is dropped):
  ~set_model_state (gazebo_msgs/ModelState), ~set_link_state (gazebo_msgs/LinkState)
Services:
  ~reset_simulation, ~reset_world, ~pause_physics, ~unpause_physics (std_srvs/Empty; reset:
  time back to 0 and every model to its spawn; world: models only, time runs on);
  ~get_model_state, ~set_model_state, ~get_link_state, ~set_link_state, ~get_world_properties,
  ~get_model_properties, ~spawn_sdf_model, ~spawn_urdf_model, ~delete_model,
  ~get_physics_properties, ~set_physics_properties, ~apply_body_wrench, ~clear_body_wrenches,
  ~apply_joint_effort, ~clear_joint_forces, ~get_link_properties, ~set_link_properties,
  ~get_joint_properties, ~set_joint_properties, ~set_model_configuration,
  ~get_light_properties, ~set_light_properties, ~delete_light; dynamic_reconfigure of the
  physics (gazebo/physics_config) on ``~``.
  get_model_properties' geom_names are Gazebo's collision names (urdf_file.RobotDescription.
  collision_names for a URDF: "<link>_collision", "<link>_fixed_joint_lump__<child>_
  collision_<i>"). The wrench, effort, link, joint and light semantics: sim/world_control.
Parameters:
  ~model_states_rate (100.0)  Hz of sim time; 0 = never publish model/link states
Every request runs in the simulation loop between two physics steps (SimNode.run_in_loop,
SimNode.queue_in_loop) and answers within one step; a bad one gets success=false and Gazebo's
one-line status. Only the node's public methods and attributes are used.
"""
import threading
import time

import rospy
from gazebo_msgs.msg import (LinkState, LinkStates, ModelState, ModelStates, ODEPhysics,
                             PerformanceMetrics, SensorPerformanceMetric)
from gazebo_msgs.srv import (ApplyBodyWrench, ApplyBodyWrenchResponse, ApplyJointEffort,
                             ApplyJointEffortResponse, BodyRequest, BodyRequestResponse,
                             DeleteLight, DeleteLightResponse, DeleteModel,
                             DeleteModelResponse, GetJointProperties,
                             GetJointPropertiesResponse, GetLightProperties,
                             GetLightPropertiesResponse, GetLinkProperties,
                             GetLinkPropertiesResponse, GetLinkState, GetLinkStateResponse,
                             GetModelProperties, GetModelPropertiesResponse, GetModelState,
                             GetModelStateResponse, GetPhysicsProperties,
                             GetPhysicsPropertiesResponse, GetWorldProperties,
                             GetWorldPropertiesResponse, JointRequest, JointRequestResponse,
                             SetJointProperties, SetJointPropertiesResponse,
                             SetLightProperties, SetLightPropertiesResponse, SetLinkProperties,
                             SetLinkPropertiesResponse, SetLinkState, SetLinkStateResponse,
                             SetModelConfiguration, SetModelConfigurationResponse,
                             SetModelState, SetModelStateResponse, SetPhysicsProperties,
                             SetPhysicsPropertiesResponse, SpawnModel, SpawnModelResponse)
from geometry_msgs.msg import Pose, Twist
from std_srvs.srv import Empty, EmptyResponse

from .callback_pace import CallbackPace
from .loop_requests import ANSWER_TIMEOUT, MAX_QUEUED, Busy, NotAnswered
from ..errors import RequestError, one_line
from .part_times import TIMES
from ..sim.world.physics_properties import OdeConfig, PhysicsProperties
from ..sim.world.spawn_request import prepare_spawn
from ..sim.world.world_control import WorldControl
from ..sim.world.world_models import spawn_failure
from ..sim.world.world_properties import JOINT_CONFIG_FIELDS

METRICS_PERIOD = 1.0     # wall s between two ~performance_metrics
MAX_LOG_LINE = 200       # characters of one warning line in the log
BUSY = ("the simulation is busy (%d requests wait for it); nothing was done: try again"
        % MAX_QUEUED)
JOINT_TYPES = {"revolute": GetJointPropertiesResponse.REVOLUTE,
               "continuous": GetJointPropertiesResponse.CONTINUOUS,
               "prismatic": GetJointPropertiesResponse.PRISMATIC,
               "fixed": GetJointPropertiesResponse.FIXED,
               "ball": GetJointPropertiesResponse.BALL,
               "universal": GetJointPropertiesResponse.UNIVERSAL}


def failure(srv_type, text: str):
    """The response of ``srv_type`` that says ``text`` failed: success False and the text as its
    status_message, as every gazebo_msgs response with those fields does; a service error
    where the response has no such fields."""
    response = srv_type._response_class()
    if not hasattr(response, "success"):
        raise rospy.ServiceException(text)
    response.success = False
    if hasattr(response, "status_message"):
        response.status_message = text
    return response


def spawn_warning(name: str, warning: str) -> str:
    """The log line of a spawned model's ``warning``: "spawn NAME: ...", at most
    MAX_LOG_LINE characters (the model's name cut to 40)."""
    line = "spawn %s: %s" % (name if len(name) <= 40 else name[:37] + "...", warning)
    return line if len(line) <= MAX_LOG_LINE else line[:MAX_LOG_LINE - 3] + "..."


def refusals_answered(srv_type, handler):
    """``handler`` with a RequestError (Gazebo's refusal) as its answer: ``failure`` of the
    error's text (success False, status_message the text)."""
    def handle(request):
        try:
            return handler(request)
        except RequestError as err:
            return failure(srv_type, str(err))
    return handle


def pose_in(msg):
    p, q = msg.position, msg.orientation
    return (p.x, p.y, p.z), (q.x, q.y, q.z, q.w)


def twist_in(msg):
    return (msg.linear.x, msg.linear.y, msg.linear.z), (msg.angular.x, msg.angular.y, msg.angular.z)


def fill_pose(msg, pose):
    (msg.position.x, msg.position.y, msg.position.z), \
        (msg.orientation.x, msg.orientation.y, msg.orientation.z, msg.orientation.w) = pose
    return msg


def fill_twist(msg, twist):
    (msg.linear.x, msg.linear.y, msg.linear.z), \
        (msg.angular.x, msg.angular.y, msg.angular.z) = twist
    return msg


def _states(msg_type, states):
    msg = msg_type()
    msg.name = [name for name, _, _ in states]
    msg.pose = [fill_pose(Pose(), pose) for _, pose, _ in states]
    msg.twist = [fill_twist(Twist(), twist) for _, _, twist in states]
    return msg


def ode_msg(ode: OdeConfig) -> ODEPhysics:
    return ODEPhysics(auto_disable_bodies=ode.auto_disable_bodies,
                      sor_pgs_precon_iters=ode.sor_pgs_precon_iters,
                      sor_pgs_iters=ode.sor_pgs_iters, sor_pgs_w=ode.sor_pgs_w,
                      sor_pgs_rms_error_tol=ode.sor_pgs_rms_error_tol,
                      contact_surface_layer=ode.contact_surface_layer,
                      contact_max_correcting_vel=ode.contact_max_correcting_vel,
                      cfm=ode.cfm, erp=ode.erp, max_contacts=ode.max_contacts)


def ode_in(msg: ODEPhysics) -> OdeConfig:
    return OdeConfig(bool(msg.auto_disable_bodies), int(msg.sor_pgs_precon_iters),
                     int(msg.sor_pgs_iters), float(msg.sor_pgs_w),
                     float(msg.sor_pgs_rms_error_tol), float(msg.contact_surface_layer),
                     float(msg.contact_max_correcting_vel), float(msg.cfm), float(msg.erp),
                     int(msg.max_contacts))


class WorldApi:
    """Adds the world API to a SimNode (topics, services, due publishing, dynamic_reconfigure)."""

    def __init__(self, node, model_states_rate: float = 100.0):
        self.node = node
        self.sim = node.sim
        for name, action in (("reset_simulation", self.sim.reset_simulation),
                             ("reset_world", self.sim.reset_world),
                             ("pause_physics", node.pause), ("unpause_physics", node.unpause)):
            rospy.Service("~" + name, Empty, self._empty_service(name, action))
        self.control = WorldControl(node.sim)
        self.pubs = {"model_states": node.advertise("~model_states", ModelStates, 10),
                     "link_states": node.advertise("~link_states", LinkStates, 10)}
        if model_states_rate > 0:   # its schedule is the node's, set before the first step
            node.add_output("model_states", self._publish_states)
        self.topic_pace = CallbackPace()   # a flooding publisher of the two topics is slowed
        rospy.Subscriber("~set_model_state", ModelState, self._on_set_model_state, queue_size=10)
        rospy.Subscriber("~set_link_state", LinkState, self._on_set_link_state, queue_size=10)
        for name, srv_type, handler in (   # every handler's RequestError is its answer
                ("get_model_state", GetModelState, self._get_model_state),
                ("set_model_state", SetModelState, self._set_model_state),
                ("get_link_state", GetLinkState, self._get_link_state),
                ("set_link_state", SetLinkState, self._set_link_state),
                ("get_world_properties", GetWorldProperties, self._get_world_properties),
                ("get_model_properties", GetModelProperties, self._get_model_properties),
                ("spawn_sdf_model", SpawnModel, self._spawner("sdf")),
                ("spawn_urdf_model", SpawnModel, self._spawner("urdf")),
                ("delete_model", DeleteModel, self._delete_model),
                ("get_physics_properties", GetPhysicsProperties, self._get_physics),
                ("set_physics_properties", SetPhysicsProperties, self._set_physics),
                ("apply_body_wrench", ApplyBodyWrench, self._apply_body_wrench),
                ("clear_body_wrenches", BodyRequest, self._clear_body_wrenches),
                ("apply_joint_effort", ApplyJointEffort, self._apply_joint_effort),
                ("clear_joint_forces", JointRequest, self._clear_joint_forces),
                ("get_link_properties", GetLinkProperties, self._get_link_properties),
                ("set_link_properties", SetLinkProperties, self._set_link_properties),
                ("get_joint_properties", GetJointProperties, self._get_joint_properties),
                ("set_joint_properties", SetJointProperties, self._set_joint_properties),
                ("set_model_configuration", SetModelConfiguration,
                 self._set_model_configuration),
                ("get_light_properties", GetLightProperties, self._get_light_properties),
                ("set_light_properties", SetLightProperties, self._set_light_properties),
                ("delete_light", DeleteLight, self._delete_light)):
            wrap = self._answered if name.startswith("spawn_") else self._in_loop
            rospy.Service("~" + name, srv_type,
                          wrap(name, srv_type, refusals_answered(srv_type, handler)))
        self.metrics = PerformanceMeter(self)
        self.reconfigure = None
        try:
            from .physics_reconfigure import PhysicsReconfigure
        except ImportError as err:
            rospy.logwarn("dynamic_reconfigure of the physics is off: %s", err)
        else:
            self.reconfigure = PhysicsReconfigure(self)

    # --- running in the simulation loop ----------------------------------------------------------

    def run_in_loop(self, action):
        """Run ``action()`` in the simulation loop between two steps; what it returns, or what
        it raised, raised here; loop_requests.NotAnswered if the loop did not start it within
        ANSWER_TIMEOUT (then it never runs)."""
        return self.node.run_in_loop(action, ANSWER_TIMEOUT)

    def _in_loop(self, name, srv_type, handler):
        """A service callback that runs ``handler(request)`` in the loop (_answered)."""
        return self._answered(name, srv_type,
                              lambda request: self.run_in_loop(lambda: handler(request)))

    def _answered(self, name, srv_type, run):
        """A service callback that returns ``run(request)``. Its failures are answered, never
        hidden: success False (or, for a response without it, a service error) with one line,
        either that the loop did not start it in time (nothing was done) or the internal error
        raised."""
        def call(request):
            try:
                return run(request)
            except Busy:
                problem = BUSY
            except NotAnswered:
                problem = ("the simulation did not answer within %g s; nothing was done"
                           % ANSWER_TIMEOUT)
            except Exception as err:  # noqa: BLE001 - a request must never stop the node
                problem = "internal error: " + one_line(err)
                rospy.logerr("%s: %s", name, problem)
            return failure(srv_type, "%s: %s" % (name, problem))
        return call

    def _empty_service(self, name, action):
        """An Empty service (reset, pause) whose action runs in the loop. A failure is a
        service error that says what happened: the loop did not start it in time (then it never
        runs), or the action raised (named in one line)."""
        def handle(_request):
            try:
                self.run_in_loop(action)
            except Busy:
                raise rospy.ServiceException("%s: %s" % (name, BUSY)) from None
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

    def queue_in_loop(self, action, key=None):
        """Run ``action()`` in the loop without waiting (topic twins of the services, the
        metrics); a RequestError is a throttled warning, anything else an error line. With a
        ``key``, an action of that key the loop has not run yet is replaced (the latest wins).
        Dropped, with a throttled warning, when the loop's queue is full."""
        def run():
            try:
                action()
            except RequestError as err:
                rospy.logwarn_throttle(5.0, str(err))
            except Exception as err:  # noqa: BLE001
                rospy.logerr(one_line(err))
        if not self.node.queue_in_loop(run, key):
            rospy.logwarn_throttle(5.0, "a topic message was dropped: " + BUSY)

    # --- publishing --------------------------------------------------------------------------

    def _publish_states(self, stamp) -> None:
        model_pub, link_pub = self.pubs["model_states"], self.pubs["link_states"]
        for pub, msg_type, states in ((model_pub, ModelStates, self.control.model_states),
                                      (link_pub, LinkStates, self.control.link_states)):
            if pub.get_num_connections() > 0:
                TIMES.switch("building")
                msg = _states(msg_type, states())
                TIMES.switch("serializing")
                pub.publish(msg)

    # --- handlers (run in the loop) ----------------------------------------------------------

    def _get_model_state(self, req):
        pose, twist, seq = self.control.get_model_state(req.model_name, req.relative_entity_name)
        resp = GetModelStateResponse()
        resp.header.seq = seq
        resp.header.stamp = rospy.Time(*divmod(self.sim.time_ns, 1_000_000_000))
        resp.header.frame_id = req.relative_entity_name
        fill_pose(resp.pose, pose)
        fill_twist(resp.twist, twist)
        resp.success, resp.status_message = True, "GetModelState: got properties"
        return resp

    def _set_model_state(self, req):
        state = req.model_state
        self.control.set_model_state(state.model_name, pose_in(state.pose),
                                     twist_in(state.twist), state.reference_frame)
        return SetModelStateResponse(True, "SetModelState: set model state done")

    def _on_set_model_state(self, state: ModelState) -> None:
        self.topic_pace.wait()
        self.queue_in_loop(lambda: self.control.set_model_state(
            state.model_name, pose_in(state.pose), twist_in(state.twist), state.reference_frame),
            key=("set_model_state", state.model_name))

    def _get_link_state(self, req):
        pose, twist = self.control.get_link_state(req.link_name, req.reference_frame)
        resp = GetLinkStateResponse()
        resp.link_state.link_name = req.link_name
        resp.link_state.reference_frame = req.reference_frame
        fill_pose(resp.link_state.pose, pose)
        fill_twist(resp.link_state.twist, twist)
        resp.success, resp.status_message = True, "GetLinkState: got state"
        return resp

    def _set_link_state(self, req):
        state = req.link_state
        self.control.set_link_state(state.link_name, pose_in(state.pose),
                                    twist_in(state.twist), state.reference_frame)
        return SetLinkStateResponse(True, "SetLinkState: set link state done")

    def _on_set_link_state(self, state: LinkState) -> None:
        self.topic_pace.wait()
        self.queue_in_loop(lambda: self.control.set_link_state(
            state.link_name, pose_in(state.pose), twist_in(state.twist), state.reference_frame),
            key=("set_link_state", state.link_name))

    def _get_world_properties(self, _req):
        return GetWorldPropertiesResponse(sim_time=self.sim.time,
                                          model_names=self.sim.models.names(),
                                          rendering_enabled=True, success=True,
                                          status_message="GetWorldProperties: got properties")

    def _get_model_properties(self, req):
        props = self.control.model_properties(req.model_name)
        resp = GetModelPropertiesResponse()
        resp.body_names, resp.geom_names = props.body_names, props.geom_names
        resp.joint_names, resp.is_static = props.joint_names, props.is_static
        resp.success, resp.status_message = True, "GetModelProperties: got properties"
        return resp

    def _spawner(self, kind):
        """spawn_sdf_model / spawn_urdf_model, in the service's own thread: the names and the
        pose are checked in the loop, the text and its files are read and checked here (while
        physics and the other requests go on), then the loop builds it."""
        def spawn(req):
            name, namespace = req.model_name, req.robot_namespace
            pose = self.run_in_loop(lambda: self.control.spawn_pose(
                name, pose_in(req.initial_pose), req.reference_frame, namespace))
            prepared = prepare_spawn(name, req.model_xml, pose, kind, robot_namespace=namespace)
            built = self.run_in_loop(lambda: self._build(prepared, pose, namespace))
            # what Gazebo would skip too, then what the building could not draw as its files say
            for warning in (prepared.world.warnings if prepared.world is not None else ()) + built:
                rospy.logwarn("%s", spawn_warning(name, warning))
            return SpawnModelResponse(True, "SpawnModel: Successfully spawned entity")
        return spawn

    def _build(self, prepared, pose, namespace) -> tuple:
        """In the loop: build a prepared spawn, and a robot's topics (if they cannot be made,
        it is out of the world again); the building's warning lines."""
        built = tuple(self.control.spawn_prepared(prepared, pose, namespace))
        try:
            self.node.sync_robots()  # a robot URDF: its plugins' topics
        except RequestError as err:
            rospy.logerr("spawn: %s", err)
            raise spawn_failure(str(err)) from None
        return built

    def _delete_model(self, req):
        self.control.delete(req.model_name)
        self.node.sync_robots()  # a robot's topics go with it
        return DeleteModelResponse(True, "DeleteModel: successfully deleted model")

    def _get_physics(self, _req):
        props = self.control.physics_properties()
        resp = GetPhysicsPropertiesResponse(time_step=props.time_step, pause=self.node.paused,
                                            max_update_rate=props.max_update_rate,
                                            ode_config=ode_msg(props.ode), success=True,
                                            status_message="GetPhysicsProperties: got properties")
        resp.gravity.x, resp.gravity.y, resp.gravity.z = props.gravity
        return resp

    def _set_physics(self, req):
        g = req.gravity
        props = PhysicsProperties(req.time_step, req.max_update_rate, (g.x, g.y, g.z),
                                  ode_in(req.ode_config))
        self.apply_physics(props)
        return SetPhysicsPropertiesResponse(True, "physics engine updated")

    def apply_physics(self, props: PhysicsProperties) -> None:
        """Apply ``props`` (in the loop): the sim's step and engine, then the pacing."""
        self.control.set_physics_properties(props)
        self.node.set_real_time_factor(props.real_time_factor)

    # --- forces, links, joints, lights (run in the loop) ---------------------------------------

    def _apply_body_wrench(self, req):
        p, w = req.reference_point, req.wrench
        self.control.apply_body_wrench(
            req.body_name, req.reference_frame, (p.x, p.y, p.z),
            (w.force.x, w.force.y, w.force.z), (w.torque.x, w.torque.y, w.torque.z),
            req.start_time.to_nsec(), req.duration.to_nsec())
        return ApplyBodyWrenchResponse(True, "")    # Gazebo says nothing more

    def _clear_body_wrenches(self, req):
        self.control.clear_body_wrenches(req.body_name)
        return BodyRequestResponse()

    def _apply_joint_effort(self, req):
        self.control.apply_joint_effort(req.joint_name, req.effort, req.start_time.to_nsec(),
                                        req.duration.to_nsec())
        return ApplyJointEffortResponse(True, "ApplyJointEffort: effort set")

    def _clear_joint_forces(self, req):
        self.control.clear_joint_forces(req.joint_name)
        return JointRequestResponse()

    def _get_link_properties(self, req):
        props = self.control.get_link_properties(req.link_name)
        resp = GetLinkPropertiesResponse()
        resp.com.position.x, resp.com.position.y, resp.com.position.z = props.com
        resp.com.orientation.w = 1.0       # the inertia is given in the link's axes
        resp.gravity_mode, resp.mass = props.gravity_mode, props.mass
        resp.ixx, resp.ixy, resp.ixz, resp.iyy, resp.iyz, resp.izz = props.inertia
        resp.success, resp.status_message = True, "GetLinkProperties: got properties"
        return resp

    def _set_link_properties(self, req):
        c, q = req.com.position, req.com.orientation
        self.control.set_link_properties(
            req.link_name, (c.x, c.y, c.z), req.gravity_mode, req.mass,
            (req.ixx, req.ixy, req.ixz, req.iyy, req.iyz, req.izz),
            com_orientation=(q.x, q.y, q.z, q.w))
        return SetLinkPropertiesResponse(True, "SetLinkProperties: properties set")

    def _get_joint_properties(self, req):
        props = self.control.get_joint_properties(req.joint_name)
        resp = GetJointPropertiesResponse()
        resp.type = JOINT_TYPES.get(props.kind, resp.REVOLUTE)
        resp.damping, resp.position, resp.rate = props.damping, props.position, props.rate
        resp.success, resp.status_message = True, "GetJointProperties: got properties"
        return resp

    def _set_joint_properties(self, req):
        config = req.ode_joint_config
        self.control.set_joint_properties(
            req.joint_name, {field: getattr(config, field) for field in JOINT_CONFIG_FIELDS})
        return SetJointPropertiesResponse(True, "SetJointProperties: properties set")

    def _set_model_configuration(self, req):
        status = self.control.set_model_configuration(   # urdf_param_name: ignored, as Gazebo
            req.model_name, list(req.joint_names), list(req.joint_positions))
        return SetModelConfigurationResponse(True, status)

    def _get_light_properties(self, req):
        light = self.control.get_light(req.light_name)
        resp = GetLightPropertiesResponse()
        d = resp.diffuse
        d.r, d.g, d.b, d.a = light.diffuse
        resp.attenuation_constant = light.attenuation_constant
        resp.attenuation_linear = light.attenuation_linear
        resp.attenuation_quadratic = light.attenuation_quadratic
        resp.success = True                 # Gazebo's status_message stays empty
        return resp

    def _set_light_properties(self, req):
        d, s, v = req.diffuse, req.specular, req.direction
        self.control.set_light(
            req.light_name, req.cast_shadows, (d.r, d.g, d.b, d.a), (s.r, s.g, s.b, s.a),
            (req.attenuation_constant, req.attenuation_linear, req.attenuation_quadratic),
            (v.x, v.y, v.z), pose_in(req.pose))
        return SetLightPropertiesResponse(True, "")

    def _delete_light(self, req):
        return DeleteLightResponse(True, self.control.delete_light(req.light_name))


def _lumped_link(description, link: str) -> str:
    """The link that ``link`` becomes part of once fixed joints are lumped (Gazebo's)."""
    try:
        joint = description.parent_joint(link)
        while joint is not None and joint.type == "fixed":
            link = joint.parent
            joint = description.parent_joint(link)
    except KeyError:
        pass
    return link


def sensor_names(world: str, robot) -> dict:
    """Gazebo-style scoped names of a SimRobot's sensors: {"scan" | "imu" | "camera": name}."""
    names = {}
    for key, sensor, link in (
            ("scan", robot.laser_sensor, getattr(robot.laser_sensor, "link", "")),
            ("imu", robot.imu_plugin, getattr(robot.imu_plugin, "body_name", "")),
            ("camera", robot.camera_sensor, getattr(robot.camera_sensor, "link", ""))):
        if sensor is not None:
            names[key] = "::".join((world, robot.name, _lumped_link(robot.description, link),
                                    sensor.name))
    return names


class PerformanceMeter:
    """~performance_metrics: a wall-clock thread asks the loop every METRICS_PERIOD for a
    snapshot (sim time, each robot's published sensor readings); the rates are the change since
    the last snapshot. Published only while subscribed; costs the loop nothing between."""

    def __init__(self, api: WorldApi):
        self.api = api
        self.sim = api.sim
        self.pub = api.node.advertise("~performance_metrics", PerformanceMetrics, 10)
        self._last = None           # (wall s, sim ns, {(robot, sensor): (topics, count)})
        self._names = {}            # id(RobotTopics) -> its sensor_names
        threading.Thread(target=self._run, name="performance_metrics", daemon=True).start()

    def _run(self) -> None:
        while not rospy.is_shutdown():
            time.sleep(METRICS_PERIOD)
            self.api.queue_in_loop(self.tick)

    def tick(self) -> None:
        """In the loop: snapshot, and publish the rates since the last one if subscribed."""
        wall, sim_ns = time.monotonic(), self.sim.time_ns
        counts = {}
        for name, topics in self.api.node.robot_topics.items():
            for key, count in topics.sensor_updates.items():
                counts[(name, key)] = (topics, count)
        last, self._last = self._last, (wall, sim_ns, counts)
        if last is None or self.pub.get_num_connections() == 0:
            return
        self.pub.publish(self.message(last, self._last))

    def message(self, last, now) -> PerformanceMetrics:
        (wall0, sim0, counts0), (wall1, sim1, counts1) = last, now
        wall_s, sim_s = wall1 - wall0, (sim1 - sim0) / 1e9
        msg = PerformanceMetrics()
        msg.header.stamp = rospy.Time(*divmod(sim1, 1_000_000_000))
        msg.real_time_factor = sim_s / wall_s if wall_s > 0 else 0.0
        world = self.sim.world.name
        live = set()
        for (robot, key), (topics, count) in counts1.items():
            live.add(id(topics))
            names = self._names.get(id(topics))
            if names is None:
                names = self._names[id(topics)] = sensor_names(world, topics.robot)
            if key not in names:
                continue
            before = counts0.get((robot, key))
            done = count - (before[1] if before and before[0] is topics else 0)
            msg.sensors.append(_sensor_metric(names[key], key, done, wall_s, sim_s))
        self._names = {k: v for k, v in self._names.items() if k in live}
        return msg


def _sensor_metric(name: str, key: str, done: int, wall_s: float,
                   sim_s: float) -> SensorPerformanceMetric:
    """``done`` readings of a sensor in ``wall_s`` wall s and ``sim_s`` sim s: its rates (fps
    for a camera, -1 for the others, as gazebo_ros)."""
    per_wall_s = done / wall_s if wall_s > 0 else 0.0
    return SensorPerformanceMetric(name=name, sim_update_rate=done / sim_s if sim_s > 0 else 0.0,
                                   real_update_rate=per_wall_s,
                                   fps=per_wall_s if key == "camera" else -1.0)
