"""The ROS topics of the model plugins (sim/world/model_plugins), as the plugins advertise them
on a world file's or spawned SDF model, or on a robot's URDF:

  gazebo_ros_p3d                    <topicName>                  nav_msgs/Odometry
  gazebo_ros_joint_state_publisher  joint_states                 sensor_msgs/JointState
  hector_gazebo_ros_imu             <topicName> (imu)            sensor_msgs/Imu
  hector_gazebo_ros_gps             <topicName> (fix)            sensor_msgs/NavSatFix
                                    <velocityTopicName> (fix_velocity)
                                                                 geometry_msgs/Vector3Stamped
  a drive (SDF):                    <commandTopic> (cmd_vel) in  geometry_msgs/Twist
  gazebo_ros_diff_drive,            <odometryTopic> (odom)       nav_msgs/Odometry
  _skid_steer_drive, _planar_move,  /tf odometryFrame -> robotBaseFrame (the node's one /tf)
  _tricycle_drive, hector's         joint_states (a tricycle's publishWheelJointState)
  _force_based_move                                              sensor_msgs/JointState

Names resolve in the plugin's namespace (model_plugins.namespace_of: its <robotNamespace>,
else its robot's, else the /gazebo node's; the joint state publisher's default is the model's
name). The stamp is the sim time of the tick; frames as each plugin fills them (p3d: frame_id
its <frameName>, child_frame_id its <bodyName>; hector: its <frameId>, default the link's
name; joint states: none; a drive's frames prefixed by its namespace, as a robot's). A
drive's commands reach the loop as a robot's do (the node's queue_in_loop, the latest only;
linear.y too, which a planar or force-based move reads), its odometry and TF at each of its
odometry ticks as a robot's (robot_topics: the diff drive's publishTf false none at all, a
drive's TF as its plugin says, its pose covariance the plugin's). A topic nobody subscribes to
costs nothing: nothing is read. A reading that fails is skipped, with one line at most every
OUTPUT_ERROR_PERIOD wall seconds per plugin.
"""
import math

import rospy
from geometry_msgs.msg import Twist, Vector3Stamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Imu, JointState, NavSatFix

from .impl.packed_messages import PackedJointState, PackedOdometry, PackedTransform
from .part_times import TIMES
from .running_topics import RunningTopics
from .robot_topics import POSE_COVARIANCE_DIAGONAL, frame_prefix
from .world_sensor_topics import resolved

COVARIANCE_TYPE_DIAGONAL_KNOWN = 2


def _diagonal6(variance: float):
    """A 6x6 row-major covariance with ``variance`` on its diagonal."""
    return [variance if i % 7 == 0 else 0.0 for i in range(36)]


class _PluginTopic:
    """One plugin's publishers; ``publish(stamp)`` at each of its ticks."""

    def __init__(self, plugin, make_publisher, node=None):
        self.plugin = plugin
        self.pubs = []
        self.make_publisher = make_publisher
        self.node = node

    def advertise(self, topic: str, msg_type, queue_size: int = 1):
        pub = self.make_publisher(resolved(self.plugin.namespace, topic), msg_type,
                                  queue_size=queue_size)
        self.pubs.append(pub)
        return pub

    def close(self) -> None:
        for pub in self.pubs:
            pub.unregister()


class _P3dTopic(_PluginTopic):
    def __init__(self, plugin, make_publisher, node=None):
        super().__init__(plugin, make_publisher)
        spec = plugin.spec
        self.pub = self.advertise(spec.topic, Odometry)
        self.msg = Odometry(child_frame_id=spec.body_name)
        self.msg.header.frame_id = spec.frame_name

    def publish(self, stamp) -> None:
        if self.pub.get_num_connections() == 0:
            return
        TIMES.switch("sensors")
        odom = self.plugin.odometry()
        msg = self.msg
        msg.header.stamp = stamp
        pose, twist = msg.pose.pose, msg.twist.twist
        pose.position.x, pose.position.y, pose.position.z = odom.position
        (pose.orientation.x, pose.orientation.y, pose.orientation.z,
         pose.orientation.w) = odom.orientation
        twist.linear.x, twist.linear.y, twist.linear.z = odom.linear
        twist.angular.x, twist.angular.y, twist.angular.z = odom.angular
        msg.pose.covariance = msg.twist.covariance = _diagonal6(odom.variance)
        self.pub.publish(msg)


class _JointStateTopic(_PluginTopic):
    def __init__(self, plugin, make_publisher, node=None):
        super().__init__(plugin, make_publisher)
        self.pub = self.advertise("joint_states", JointState)
        self.msg = JointState()

    def publish(self, stamp) -> None:
        if self.pub.get_num_connections() == 0:
            return
        TIMES.switch("sensors")
        names, positions, velocities = self.plugin.joint_states()
        self.msg.header.stamp = stamp
        self.msg.name, self.msg.position, self.msg.velocity = list(names), positions, velocities
        self.pub.publish(self.msg)


class _HectorImuTopic(_PluginTopic):
    def __init__(self, plugin, make_publisher, node=None):
        super().__init__(plugin, make_publisher)
        self.pub = self.advertise(plugin.spec.topic, Imu, queue_size=10)
        self.msg = Imu()
        self.msg.header.frame_id = plugin.spec.frame_id

    def publish(self, stamp) -> None:
        if self.pub.get_num_connections() == 0:
            return
        TIMES.switch("sensors")
        reading = self.plugin.imu(stamp.to_nsec())
        msg = self.msg
        msg.header.stamp = stamp
        o, w, a = msg.orientation, msg.angular_velocity, msg.linear_acceleration
        o.x, o.y, o.z, o.w = reading.orientation
        w.x, w.y, w.z = reading.angular_velocity
        a.x, a.y, a.z = reading.linear_acceleration
        msg.orientation_covariance = list(reading.orientation_covariance)
        msg.angular_velocity_covariance = list(reading.angular_velocity_covariance)
        msg.linear_acceleration_covariance = list(reading.linear_acceleration_covariance)
        self.pub.publish(msg)


class _HectorGpsTopic(_PluginTopic):
    def __init__(self, plugin, make_publisher, node=None):
        super().__init__(plugin, make_publisher)
        spec = plugin.spec
        self.fix_pub = self.advertise(spec.topic, NavSatFix, queue_size=10)
        self.velocity_pub = self.advertise(spec.velocity_topic, Vector3Stamped, queue_size=10)
        self.fix = NavSatFix(position_covariance_type=COVARIANCE_TYPE_DIAGONAL_KNOWN)
        self.fix.header.frame_id = spec.frame_id
        self.fix.status.status, self.fix.status.service = spec.status, spec.service
        self.velocity = Vector3Stamped()
        self.velocity.header.frame_id = spec.frame_id

    def publish(self, stamp) -> None:
        wants_fix = self.fix_pub.get_num_connections() > 0
        wants_velocity = self.velocity_pub.get_num_connections() > 0
        if not (wants_fix or wants_velocity):
            return
        TIMES.switch("sensors")
        reading = self.plugin.fix(stamp.to_nsec())
        if wants_fix:
            fix = self.fix
            fix.header.stamp = stamp
            fix.latitude, fix.longitude, fix.altitude = (reading.latitude, reading.longitude,
                                                         reading.altitude)
            fix.position_covariance = list(reading.position_covariance)
            self.fix_pub.publish(fix)
        if wants_velocity:
            self.velocity.header.stamp = stamp
            v = self.velocity.vector
            v.x, v.y, v.z = reading.velocity
            self.velocity_pub.publish(self.velocity)


class _DriveTopic(_PluginTopic):
    """An SDF model's drive (model_drives: DiffDriveRunner, DriveRunner): cmd_vel in, odom
    and the odom TF out (and a tricycle's wheel joint states)."""

    def __init__(self, plugin, make_publisher, node=None):
        super().__init__(plugin, make_publisher, node)
        spec = plugin.spec
        prefix = frame_prefix(plugin.namespace)
        self.pub = (self.advertise(spec.odometry_topic, Odometry)
                    if plugin.publishes_odometry else None)
        self.joints_pub = (self.advertise("joint_states", JointState)
                           if plugin.joint_names else None)
        self.joints_packed = PackedJointState("", list(plugin.joint_names))
        odom_frame = prefix + spec.odometry_frame.lstrip("/")
        base_frame = prefix + spec.robot_base_frame.lstrip("/")
        self.odom_packed = PackedOdometry(odom_frame, base_frame,
                                          getattr(spec, "pose_covariance",
                                                  POSE_COVARIANCE_DIAGONAL))
        self.tf_packed = PackedTransform(odom_frame, base_frame)
        self.subscriber = rospy.Subscriber(resolved(plugin.namespace, spec.command_topic), Twist,
                                           self._on_cmd_vel, queue_size=1)

    def close(self) -> None:
        self.subscriber.unregister()
        super().close()

    def _on_cmd_vel(self, msg: Twist) -> None:
        """A callback's command, handed to the loop (the latest replaces one not yet run)."""
        linear, angular = msg.linear.x, msg.angular.z
        if not (math.isfinite(linear) and math.isfinite(angular)):
            rospy.logwarn_throttle(5.0, "%s ignored: NaN or infinite field (linear.x=%r, "
                                   "angular.z=%r)" % (self.subscriber.name, linear, angular))
            return
        lateral = msg.linear.y if self.plugin.kind == "drive" else 0.0
        if not math.isfinite(lateral):     # a planar or force-based move's linear.y
            rospy.logwarn_throttle(5.0, "%s ignored: NaN or infinite linear.y (%r)"
                                   % (self.subscriber.name, lateral))
            return
        self.node.queue_in_loop(lambda: self.apply_command(linear, angular, lateral),
                                key=("cmd_vel", self.plugin.name))

    def apply_command(self, linear: float, angular: float, lateral: float = 0.0) -> None:
        """In the loop: the command to the drive, held until the next."""
        problems = self.plugin.command(linear, angular, lateral)
        if problems:
            rospy.logwarn_throttle(5.0, "cmd_vel beyond %s's limits: %s"
                                   % (self.plugin.model.name, "; ".join(problems)))

    def publish(self, stamp) -> None:
        if self.joints_pub is not None and self.joints_pub.get_num_connections() > 0:
            TIMES.switch("sensors")
            names, positions, velocities = self.plugin.joint_states()
            self.joints_packed.set_stamp(stamp.secs, stamp.nsecs)
            self.joints_packed.write(positions, velocities)
            self.joints_pub.publish_packed(self.joints_packed)
        # publishTf false: no odometry at all (Gazebo); a drive's odometry at its own rate
        if self.pub is None or not self.plugin.odometry_due:
            return
        tf_pub = self.node.tf_pub if self.node is not None else None
        wants_odom = self.pub.get_num_connections() > 0
        wants_tf = (self.plugin.spec.publish_odom_tf and tf_pub is not None
                    and tf_pub.get_num_connections() > 0)
        if not (wants_odom or wants_tf):
            return
        TIMES.switch("sensors")
        odom = self.plugin.odometry()
        TIMES.switch("serializing")
        if wants_odom:
            self.odom_packed.set_stamp(stamp.secs, stamp.nsecs)
            self.odom_packed.write(odom.position, odom.orientation, odom.linear, odom.angular)
            self.pub.publish_packed(self.odom_packed)
        if wants_tf:
            self.tf_packed.write(stamp.secs, stamp.nsecs, odom.position, odom.orientation)
            tf_pub.publish_packed(self.tf_packed)


TOPICS = {"p3d": _P3dTopic, "joint_states": _JointStateTopic, "hector_imu": _HectorImuTopic,
          "hector_gps": _HectorGpsTopic, "diff_drive": _DriveTopic, "drive": _DriveTopic}


class ModelPluginTopics:
    """The publishers of every running model plugin, following the simulation's
    (ModelPlugins.generation: a spawned model's plugins are advertised, a deleted model's
    taken back), and their messages at each tick (``publish``, the node's "model_plugins"
    output)."""

    def __init__(self, sim, make_publisher, node=None):
        """``sim``: the Simulation; ``make_publisher(topic, type, queue_size=1)``: the node's
        (non-blocking) publishers; ``node``: the SimNode, whose ``tf_pub`` (/tf) and
        ``queue_in_loop`` a drive uses."""
        self.sim = sim
        self.make_publisher = make_publisher
        self.node = node
        self.running = RunningTopics("model plugin", self._topic)   # RunningPlugin -> topic
        self.sync()

    @property
    def topics(self):
        """RunningPlugin -> its _PluginTopic."""
        return self.running.topics

    def _topic(self, plugin):
        return TOPICS[plugin.kind](plugin, self.make_publisher, self.node)

    def sync(self) -> None:
        """Advertise the plugins that are new, take back those that are gone."""
        plugins = self.sim.model_plugins
        self.running.sync(plugins.generation, plugins.plugins)

    def publish(self, stamp) -> None:
        """The messages of the plugins due at this step (ModelPlugins.due_now)."""
        self.sync()
        self.running.publish(self.sim.model_plugins.due_now, stamp)
        TIMES.switch("other")

    def close(self) -> None:
        self.running.close()
