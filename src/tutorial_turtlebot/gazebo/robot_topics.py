"""One simulated robot's ROS topics, as its URDF's gazebo_ros plugins would advertise them.

For a SimRobot in namespace N ("" = the /gazebo node's own namespace, as sim.launch's robot;
"/tb3_0/" for one spawned with robot_namespace tb3_0), topic names come from the plugins and
resolve in N; frames are the URDF's links prefixed with N's name ("tb3_0/odom",
"tb3_0/base_footprint", "tb3_0/base_scan"), as robot_state_publisher's tf_prefix does.
For a TurtleBot3:
  odom (nav_msgs/Odometry)              30 Hz, odom -> base_footprint (and on /tf)
  joint_states (sensor_msgs/JointState) 30 Hz, wheel_left_joint, wheel_right_joint
  scan (sensor_msgs/LaserScan)          5 Hz, base_scan
  imu (sensor_msgs/Imu)                 200 Hz, imu_link, linear acceleration includes gravity
  imu_service (std_srvs/Empty)          does nothing, as gazebo_ros_imu's
  camera/... (waffle, waffle_pi, a burger given a camera): see camera_publisher
A robot with several lasers or cameras publishes each on its own topics, in its own frame,
at its own rate (the first's output is "scan" / "camera", the others' "scan:1", ...).
  cmd_vel (geometry_msgs/Twist) in: linear.x (m/s), angular.z (rad/s), kept until the next
As the plugins: the diff drive's publishTf false publishes no odometry at all, publishOdomTF
false only no TF; a plugin's own <robotNamespace> replaces the robot's for its topics.
Another drive (skid steer, planar move, tricycle, force-based move) subscribes its
commandTopic and publishes its odometryTopic in odometryFrame -> robotBaseFrame with its pose
covariance, the TF as it says (the skid steer's broadcastTF, the force-based move's
publishOdometryTf; the others' always), a tricycle's publishWheelJointState its four joints on
joint_states; a planar or force-based move also reads linear.y.
A message type nobody subscribes to is not even computed.
"""
import functools
import math

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph.names import ns_join
from sensor_msgs.msg import Imu, JointState, LaserScan
from std_srvs.srv import Empty, EmptyResponse

from .camera_publisher import CameraPublisher
from .camera_rate_watch import CameraRateWatch
from .impl.packed_messages import (PackedImu, PackedJointState, PackedLaserScan, PackedOdometry,
                                   PackedTransform)
from .part_times import TIMES

# Gazebo diff-drive plugin's pose covariance diagonal (x, y, z, roll, pitch, yaw).
POSE_COVARIANCE_DIAGONAL = (1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3)


def frame_prefix(namespace: str) -> str:
    """"/tb3_0/" -> "tb3_0/"; "" -> "" (robot_state_publisher's tf_prefix convention)."""
    name = namespace.strip("/")
    return name + "/" if name else ""


class RobotTopics:
    """Publishers, messages and the cmd_vel subscriber of one SimRobot."""

    def __init__(self, robot, make_publisher, tf_publisher):
        """``make_publisher(topic, type, queue_size=1)`` gives a (non-blocking) publisher;
        ``tf_publisher``: the node's one publisher of tf2_msgs/TFMessage on /tf (None for a
        robot without a drive plugin: it publishes no transform). Whatever
        fails on the way (a topic ROS refuses, a message that cannot be built) is raised
        after every topic made so far is taken back: nothing of the robot is left behind."""
        self.robot = robot
        self.namespace = robot.namespace
        self.prefix = frame_prefix(robot.namespace)
        self.tf_pub = tf_publisher
        self.command = None              # the latest (linear, angular), applied by the loop
        self.pubs = {}
        self.publishers = {}   # what the robot's schedules name (SimRobot.due), by name
        self.services = []
        self.subscriber = None
        self.camera = None               # the first camera's CameraPublisher
        self.cameras = []                # every camera's, in the robot's order
        self._frame_pubs = {}            # a camera's output -> its publishers that need a frame
        self.scans_packed = {}           # a laser's output -> its PackedLaserScan
        self._advertised = []  # every publisher made for this robot, the camera's too
        # sensor readings published, for ~performance_metrics (world_api)
        self.sensor_updates = {"scan": 0, "imu": 0, "camera": 0}
        self.sensor_updates.update((sensor.output, 0) for sensor in robot.lasers + robot.cameras)
        # camera ticks the loop skipped, being behind the wall clock (LoopPacer.frame_in_time)
        self.frames_skipped = 0
        camera = robot.schedules.get(robot.cameras[0].output) if robot.cameras else None
        self.camera_watch = CameraRateWatch(camera.rate_hz if camera else 0.0)

        def advertise(topic, msg_type, queue_size=1):
            publisher = make_publisher(topic, msg_type, queue_size=queue_size)
            self._advertised.append(publisher)
            return publisher
        try:
            self._advertise(advertise)
        except Exception:
            self.close()
            raise

    def _advertise(self, make_publisher) -> None:
        robot = self.robot
        drive, imu = robot.drive_plugin, robot.imu_plugin
        if "odom" in robot.schedules:
            self.pubs["odom"] = make_publisher(self.topic(drive.odometry_topic, drive), Odometry)
            self.publishers["odom"] = self._publish_odom
        if "joint_states" in robot.schedules:
            self.pubs["joint_states"] = make_publisher(self.topic("joint_states", drive),
                                                       JointState)
            self.publishers["joint_states"] = self._publish_joints
        for index, laser in enumerate(robot.lasers):
            self.pubs[laser.output] = make_publisher(self.topic(laser.sensor.topic,
                                                                laser.sensor), LaserScan)
            self.publishers[laser.output] = (self._publish_scan if index == 0 else
                                             functools.partial(self._publish_scan, index=index))
        if imu:
            self.pubs["imu"] = make_publisher(self.topic(imu.topic, imu), Imu)
            self.publishers["imu"] = self._publish_imu
            self.services.append(rospy.Service(self.topic(imu.service_name, imu), Empty,
                                               lambda _request: EmptyResponse()))
        for index, camera in enumerate(robot.cameras):
            publisher = CameraPublisher(robot, make_publisher, self.namespace, self.prefix,
                                        index=index)
            self.cameras.append(publisher)
            self.publishers[camera.output] = (
                self._publish_camera if index == 0
                else functools.partial(self._publish_camera, index=index))
            self._frame_pubs[camera.output] = (publisher.image_pubs + publisher.jpeg_pubs
                                               + publisher.depth_pubs + publisher.points_pubs)
        self.camera = self.cameras[0] if self.cameras else None
        self._build_messages()
        if drive:
            self.subscriber = rospy.Subscriber(self.topic(drive.command_topic, drive), Twist,
                                               self._on_cmd_vel, queue_size=1)

    def topic(self, name: str, plugin) -> str:
        """A plugin's topic name resolved in its <robotNamespace>, else in the robot's
        namespace ("" = the node's)."""
        namespace = plugin.robot_namespace or self.namespace
        return ns_join(namespace, name) if namespace else name

    def frame(self, name: str) -> str:
        return self.prefix + name.lstrip("/")

    def close(self) -> None:
        """Unadvertise every topic and service of the robot (delete_model)."""
        if self.subscriber is not None:
            self.subscriber.unregister()
        for service in self.services:
            service.shutdown()
        for pub in self._advertised:
            pub.unregister()

    # --- messages --------------------------------------------------------------------------------

    def _build_messages(self) -> None:
        """Each message is kept serialized (packed_messages): a publish rewrites only its
        stamp, sequence number and readings."""
        robot = self.robot
        drive = robot.drive_plugin
        if drive:
            odom_frame = self.frame(drive.odometry_frame)
            base_frame = self.frame(drive.robot_base_frame)
            covariance = getattr(drive, "pose_covariance", POSE_COVARIANCE_DIAGONAL)
            self.odom_packed = PackedOdometry(odom_frame, base_frame, covariance)
            self.tf_packed = PackedTransform(odom_frame, base_frame)
        if robot.diff_plugin:
            self.joints_packed = PackedJointState("", [drive.left_joint, drive.right_joint])
        elif "joint_states" in robot.schedules:   # a tricycle's publishWheelJointState
            self.joints_packed = PackedJointState("", robot.motion.joint_names)
        for index, sensor in enumerate(robot.lasers):
            laser = robot.laser if index == 0 else sensor.config
            scan = LaserScan(angle_min=laser.angle_min, angle_max=laser.angle_max,
                             angle_increment=laser.angle_increment, time_increment=0.0,
                             scan_time=0.0, range_min=laser.range_min,
                             range_max=laser.range_max, intensities=[0.0] * laser.samples)
            scan.header.frame_id = self.frame(sensor.sensor.frame)
            self.scans_packed[sensor.output] = PackedLaserScan(scan)
        self.scan_packed = self.scans_packed.get("scan")   # the first laser's
        if robot.imu_plugin:   # gazebo_ros_imu's covariances: the noise's variance
            self.imu_packed = PackedImu(self.frame(robot.imu_plugin.frame),
                                        robot.imu_plugin.gaussian_noise ** 2)

    def _publish_odom(self, stamp) -> None:
        wants_odom = self.pubs["odom"].get_num_connections() > 0
        wants_tf = (self.robot.drive_plugin.publish_odom_tf
                    and self.tf_pub.get_num_connections() > 0)
        if not (wants_odom or wants_tf):
            return
        TIMES.switch("sensors")
        state = self.robot.odom()
        TIMES.switch("serializing")
        if wants_odom:
            packed = self.odom_packed
            packed.set_stamp(stamp.secs, stamp.nsecs)
            packed.write(state.position, state.orientation, state.linear, state.angular)
            self.pubs["odom"].publish_packed(packed)
        if wants_tf:
            packed = self.tf_packed
            packed.write(stamp.secs, stamp.nsecs, state.position, state.orientation)
            self.tf_pub.publish_packed(packed)

    def _publish_joints(self, stamp) -> None:
        if self.pubs["joint_states"].get_num_connections() == 0:
            return
        TIMES.switch("sensors")
        positions, velocities = self.robot.joint_states()
        TIMES.switch("serializing")
        packed = self.joints_packed
        packed.set_stamp(stamp.secs, stamp.nsecs)
        packed.write(positions, velocities)
        self.pubs["joint_states"].publish_packed(packed)

    def _publish_scan(self, stamp, index: int = 0) -> None:
        """Laser ``index``'s scan (of SimRobot.lasers), cast only for a subscriber."""
        output = self.robot.lasers[index].output
        if self.pubs[output].get_num_connections() == 0:
            return
        TIMES.switch("sensors")
        ranges = self.robot.scan(index) if index else self.robot.scan()
        TIMES.switch("serializing")
        packed = self.scans_packed[output]
        packed.set_stamp(stamp.secs, stamp.nsecs)
        packed.write(ranges)
        self.pubs[output].publish_packed(packed)
        self.sensor_updates[output] += 1

    def _publish_imu(self, stamp) -> None:
        if self.pubs["imu"].get_num_connections() == 0:
            return
        TIMES.switch("sensors")
        state = self.robot.imu()
        TIMES.switch("serializing")
        packed = self.imu_packed
        packed.set_stamp(stamp.secs, stamp.nsecs)
        packed.write(state.orientation, state.angular_velocity, state.linear_acceleration)
        self.pubs["imu"].publish_packed(packed)
        self.sensor_updates["imu"] += 1

    def frame_wanted(self, output: str) -> bool:
        """Whether anybody subscribes to a topic of camera ``output`` that needs its frame."""
        return any(pub.get_num_connections() > 0 for pub in self._frame_pubs.get(output, ()))

    def _publish_camera(self, stamp, index: int = 0) -> None:
        """Camera ``index``'s tick; a frame is rendered (and counted) only for a subscriber."""
        output = self.robot.cameras[index].output
        if self.frame_wanted(output):
            self.sensor_updates[output] += 1
        TIMES.switch("sensors")   # rendering; its messages are built from the frame
        self.cameras[index].publish(stamp)

    # --- input -----------------------------------------------------------------------------------

    def _on_cmd_vel(self, msg: Twist) -> None:
        linear, angular = msg.linear.x, msg.angular.z
        if not (math.isfinite(linear) and math.isfinite(angular)):
            rospy.logwarn_throttle(5.0, "%s ignored: NaN or infinite field (linear.x=%r, "
                                   "angular.z=%r)" % (self.subscriber.name, linear, angular))
            return
        if self.robot.motion is not None:   # another drive: linear.y too (a planar move's)
            lateral = msg.linear.y
            if not math.isfinite(lateral):
                rospy.logwarn_throttle(5.0, "%s ignored: NaN or infinite linear.y (%r)"
                                       % (self.subscriber.name, lateral))
                return
            self.command = (linear, angular, lateral)
            return
        self.command = (linear, angular)

    def apply_command(self) -> None:
        """Hand the latest cmd_vel (if a new one came) to the robot; called by the loop."""
        command, self.command = self.command, None
        if command is None:
            return
        problems = self.robot.command(*command)
        if problems:
            rospy.logwarn_throttle(5.0, "cmd_vel beyond %s's limits: %s"
                                   % (self.robot.name, "; ".join(problems)))
