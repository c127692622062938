"""The ROS topics of the world models' sensors (sim/world/world_sensors), as gazebo_ros' sensor
plugins advertise them on a world file's (or a spawned SDF model's) link, or a URDF robot's
(those SimRobot does not make: robot_topics publishes its lasers and cameras):

  gazebo_ros_laser, gpu_laser  <topicName> (/world)             sensor_msgs/LaserScan
  gazebo_ros_range             <topicName> (/range)             sensor_msgs/Range
  gazebo_ros_block_laser       <topicName> (/world)             sensor_msgs/PointCloud
  gazebo_ros_camera            <cameraName>/<imageTopicName> (image_raw)      sensor_msgs/Image
                               <cameraName>/<cameraInfoTopicName> (camera_info)  CameraInfo
                               (the encoding of its <format>: rgb8, mono8, rgb16 ...)
  gazebo_ros_triggered_camera  the same, one image per std_msgs/Empty on
                               <cameraName>/<triggerTopicName> (image_trigger), subscribed
  gazebo_ros_depth_camera      the same (ir/image_raw, ir/camera_info by default), and
                               <cameraName>/depth/image_raw (32FC1 m or 16UC1 mm),
                               <cameraName>/depth/camera_info, <cameraName>/points
                               (PointCloud2, organized, x y z rgb), all of one stamp
  gazebo_ros_openni_kinect     the same topics, depths beyond pointCloudCutoffMax left out too
  gazebo_ros_multicamera       <cameraName>/left/image_raw, .../left/camera_info, and right's,
                               of one stamp
  gazebo_ros_bumper            <bumperTopicName> (bumper_states)  gazebo_msgs/ContactsState:
                               one ContactState per pair of collisions touching
  gazebo_ros_imu_sensor        <topicName> (imu_data) in <robotNamespace> (else /<model>)
                               sensor_msgs/Imu, frame_id <frameName> as written

Names resolve in the plugin's <robotNamespace>, else in the /gazebo node's namespace (the root,
as gzserver's); a robot's in its plugin's <robotNamespace>, else in the spawn's namespace
(robot_sensors). frame_id is the plugin's <frameName> as written, without a leading "/"
(default "world"; a camera's: empty); a robot's is a link of it (its sensor's by default),
prefixed as robot_topics prefixes its frames ("tb3_0/front_link"). The stamp is the sim time
of the tick. A topic nobody
subscribes to costs nothing: no ray is cast, no image rendered. A sensor's reading that fails
is skipped, with one line at most every OUTPUT_ERROR_PERIOD wall seconds per sensor.
"""
import math

import numpy as np
import rospy
from gazebo_msgs.msg import ContactState, ContactsState
from geometry_msgs.msg import Point32, Vector3, Wrench
from rosgraph.names import ns_join
from sensor_msgs.msg import (CameraInfo, ChannelFloat32, Image, Imu, LaserScan, PointCloud,
                             PointCloud2, PointField, Range)
from std_msgs.msg import Empty

from ..sim.devices.camera import pointcloud_bytes, pointcloud_xyz
from .camera_publisher import camera_info
from .part_times import TIMES
from .robot_topics import frame_prefix
from .running_topics import RunningTopics


def resolved(namespace: str, name: str) -> str:
    """``name`` in the plugin's ``namespace`` ("" = the node's: left relative)."""
    return ns_join(namespace, name) if namespace else name


def frame_id(sensor, frame: str) -> str:
    """The header's frame_id of ``frame`` (a spec's) of a RunningSensor: a robot's sensor's
    prefixed with its robot's namespace (robot_topics.frame_prefix), a world model's as it is."""
    return frame_prefix(sensor.namespace) + frame.lstrip("/") if sensor.namespace else frame


class _SensorTopic:
    """One sensor's publishers; ``publish(stamp)`` at each of its ticks."""

    def __init__(self, sensor, make_publisher):
        self.sensor = sensor
        self.pubs = []
        self.make_publisher = make_publisher

    def advertise(self, topic: str, msg_type):
        pub = self.make_publisher(topic, msg_type, queue_size=1)
        self.pubs.append(pub)
        return pub

    def subscribe(self, make_subscriber) -> None:
        """The topics the plugin subscribes to (``make_subscriber``: rospy.Subscriber's)."""

    def close(self) -> None:
        for pub in self.pubs:
            pub.unregister()


class _LaserTopic(_SensorTopic):
    def __init__(self, sensor, make_publisher):
        super().__init__(sensor, make_publisher)
        spec, laser = sensor.spec, sensor.laser
        self.pub = self.advertise(resolved(spec.robot_namespace, spec.topic), LaserScan)
        self.msg = LaserScan(angle_min=laser.angle_min, angle_max=laser.angle_max,
                             angle_increment=laser.angle_increment, time_increment=0.0,
                             scan_time=0.0, range_min=laser.range_min,
                             range_max=laser.range_max, intensities=[0.0] * laser.samples)
        self.msg.header.frame_id = frame_id(sensor, spec.frame)

    def publish(self, stamp) -> None:
        if self.pub.get_num_connections() == 0:
            return
        TIMES.switch("sensors")
        ranges = self.sensor.scan()
        TIMES.switch("building")
        self.msg.header.stamp = stamp
        self.msg.ranges = ranges.tolist()
        self.pub.publish(self.msg)


class _RangeTopic(_SensorTopic):
    def __init__(self, sensor, make_publisher):
        super().__init__(sensor, make_publisher)
        spec = sensor.spec
        self.pub = self.advertise(resolved(spec.robot_namespace, spec.topic), Range)
        self.msg = Range(radiation_type=sensor.radiation_type, field_of_view=spec.fov,
                         min_range=spec.rays.range_min, max_range=spec.rays.range_max)
        self.msg.header.frame_id = frame_id(sensor, spec.frame)

    def publish(self, stamp) -> None:
        if self.pub.get_num_connections() == 0:
            return
        TIMES.switch("sensors")
        self.msg.range = self.sensor.reading()
        self.msg.header.stamp = stamp
        self.pub.publish(self.msg)


class _BlockLaserTopic(_SensorTopic):
    def __init__(self, sensor, make_publisher):
        super().__init__(sensor, make_publisher)
        spec = sensor.spec
        self.pub = self.advertise(resolved(spec.robot_namespace, spec.topic), PointCloud)
        self.msg = PointCloud()
        self.msg.header.frame_id = frame_id(sensor, spec.frame)

    def publish(self, stamp) -> None:
        if self.pub.get_num_connections() == 0:
            return
        TIMES.switch("sensors")
        points, channel = self.sensor.cloud()
        TIMES.switch("building")
        self.msg.header.stamp = stamp
        self.msg.points = [Point32(x, y, z) for x, y, z in points.tolist()]
        self.msg.channels = [ChannelFloat32(name="", values=channel.tolist())]
        self.pub.publish(self.msg)


class _CameraTopic(_SensorTopic):
    """gazebo_ros_camera (and the triggered camera): an image and its CameraInfo."""

    def __init__(self, sensor, make_publisher):
        super().__init__(sensor, make_publisher)
        spec = sensor.spec
        base = camera_base(spec)
        self.image_pub = self.advertise(resolved(base, spec.image_topic), Image)
        self.info_pub = self.advertise(resolved(base, spec.info_topic), CameraInfo)
        self.info, self.image = camera_messages(sensor, frame_id(sensor, spec.frame))

    def publish(self, stamp) -> None:
        if self.info_pub.get_num_connections() > 0:
            self.info.header.stamp = stamp
            self.info_pub.publish(self.info)
        if self.image_pub.get_num_connections() == 0:
            return
        TIMES.switch("sensors")
        pixels = self.sensor.image()
        TIMES.switch("building")
        self.image.header.stamp = stamp
        self.image.data = pixels.tobytes()
        self.image_pub.publish(self.image)


class _TriggeredCameraTopic(_CameraTopic):
    """gazebo_ros_triggered_camera: a camera that subscribes to its trigger topic."""

    trigger_sub = None

    def subscribe(self, make_subscriber) -> None:
        topic = resolved(camera_base(self.sensor.spec), self.sensor.spec.trigger_topic)
        self.trigger_sub = make_subscriber(topic, Empty, self._triggered, queue_size=1)

    def _triggered(self, _msg) -> None:
        self.sensor.trigger()

    def close(self) -> None:
        if self.trigger_sub is not None:
            self.trigger_sub.unregister()
        super().close()


class _DepthCameraTopic(_CameraTopic):
    """gazebo_ros_depth_camera: the image, a depth image, a point cloud, their CameraInfo."""

    def __init__(self, sensor, make_publisher):
        super().__init__(sensor, make_publisher)
        spec, camera = sensor.spec, sensor.camera_spec
        base = camera_base(spec)
        self.depth_pub = self.advertise(resolved(base, spec.depth_image_topic), Image)
        self.depth_info_pub = self.advertise(resolved(base, spec.depth_info_topic), CameraInfo)
        self.points_pub = self.advertise(resolved(base, spec.point_cloud_topic), PointCloud2)
        self.depth = Image(height=camera.height, width=camera.width, is_bigendian=0,
                           encoding="16UC1" if spec.depth_16bit else "32FC1",
                           step=(2 if spec.depth_16bit else 4) * camera.width)
        self.depth.header.frame_id = frame_id(sensor, spec.frame)
        self.points = PointCloud2(height=camera.height, width=camera.width,
                                  is_bigendian=False, is_dense=False)
        self.points.header.frame_id = frame_id(sensor, spec.frame)

    def publish(self, stamp) -> None:
        for pub in (self.info_pub, self.depth_info_pub):
            if pub.get_num_connections() > 0:
                self.info.header.stamp = stamp
                pub.publish(self.info)
        image, depth, points = (p.get_num_connections() > 0
                                for p in (self.image_pub, self.depth_pub, self.points_pub))
        if not (image or depth or points):
            return
        TIMES.switch("sensors")
        pixels, metres = self.sensor.frame(depth=depth or points)
        TIMES.switch("building")
        spec = self.sensor.spec
        if image:
            self.image.header.stamp = stamp
            self.image.data = pixels.tobytes()
            self.image_pub.publish(self.image)
        if depth:
            self.depth.header.stamp = stamp
            self.depth.data = depth_values(metres, spec.point_cloud_cutoff, spec.depth_16bit,
                                           spec.point_cloud_cutoff_max).tobytes()
            self.depth_pub.publish(self.depth)
        if points:
            self._publish_points(stamp, pixels, metres)

    def _publish_points(self, stamp, pixels, metres) -> None:
        rgb = pixels if self.sensor.encoding == "rgb8" else None
        spec = self.sensor.spec
        cutoff = (spec.point_cloud_cutoff, spec.point_cloud_cutoff_max)
        found = pointcloud_xyz(metres, self.sensor.intrinsics, cutoff=cutoff, organized=True,
                               rgb=rgb)
        data, point_step, fields = pointcloud_bytes(*found) if rgb is not None else (
            pointcloud_bytes(found))
        msg = self.points
        msg.header.stamp = stamp
        msg.fields = [PointField(name=name, offset=offset, datatype=PointField.FLOAT32, count=1)
                      for name, offset in fields]
        msg.point_step = point_step
        msg.row_step = point_step * msg.width
        msg.data = data
        self.points_pub.publish(msg)


class _MultiCameraTopic(_SensorTopic):
    """gazebo_ros_multicamera: each camera's image and CameraInfo, of one tick."""

    def __init__(self, sensor, make_publisher):
        super().__init__(sensor, make_publisher)
        self.outputs = []
        for camera in sensor.cameras:
            spec = camera.spec
            base = camera_base(spec)
            pubs = (self.advertise(resolved(base, spec.image_topic), Image),
                    self.advertise(resolved(base, spec.info_topic), CameraInfo))
            self.outputs.append(pubs + camera_messages(camera, frame_id(sensor, spec.frame)))

    def publish(self, stamp) -> None:
        for _, info_pub, info, _ in self.outputs:
            if info_pub.get_num_connections() > 0:
                info.header.stamp = stamp
                info_pub.publish(info)
        wanted = [image_pub.get_num_connections() > 0 for image_pub, *_ in self.outputs]
        if not any(wanted):
            return
        TIMES.switch("sensors")
        images = self.sensor.images(wanted)
        TIMES.switch("building")
        for (image_pub, _, _, image), pixels in zip(self.outputs, images):
            if pixels is not None:
                image.header.stamp = stamp
                image.data = pixels.tobytes()
                image_pub.publish(image)


class _BumperTopic(_SensorTopic):
    """gazebo_ros_bumper: the contacts of the sensor's collisions, each pair one ContactState
    (info, names, per point wrench, position, normal, depth; their total wrench)."""

    def __init__(self, sensor, make_publisher):
        super().__init__(sensor, make_publisher)
        spec = sensor.spec
        self.pub = self.advertise(resolved(spec.robot_namespace, spec.topic), ContactsState)
        self.msg = ContactsState()
        self.msg.header.frame_id = frame_id(sensor, spec.frame)

    def publish(self, stamp) -> None:
        if self.pub.get_num_connections() == 0:
            return
        TIMES.switch("sensors")
        found = self.sensor.contacts()
        TIMES.switch("building")
        self.msg.header.stamp = stamp
        self.msg.states = [contact_state(c, i, len(found), stamp) for i, c in enumerate(found)]
        self.pub.publish(self.msg)


def contact_state(contact, index: int, count: int, stamp) -> ContactState:
    """The ContactState of one pair (world_sensors.ContactState), as gazebo_ros_bumper fills
    it: its info line, each point's wrench and their sum."""
    state = ContactState(collision1_name=contact.collision1,
                         collision2_name=contact.collision2)
    state.info = ("Debug:  i:(%d/%d)     my geom:%s   other geom:%s         time:%s\n"
                  % (index, count, contact.collision1, contact.collision2, stamp))
    total = np.zeros(6)
    for force, torque in contact.wrenches:
        state.wrenches.append(Wrench(Vector3(*force), Vector3(*torque)))
        total += np.concatenate([force, torque])
    state.total_wrench = Wrench(Vector3(*total[:3]), Vector3(*total[3:]))
    state.contact_positions = [Vector3(*p) for p in contact.positions]
    state.contact_normals = [Vector3(*n) for n in contact.normals]
    state.depths = list(contact.depths)
    return state


class _ImuSensorTopic(_SensorTopic):
    """gazebo_ros_imu_sensor: the link's Imu, gaussianNoise squared on the covariances'
    diagonals."""

    def __init__(self, sensor, make_publisher):
        super().__init__(sensor, make_publisher)
        spec = sensor.spec
        self.pub = self.advertise(resolved(spec.robot_namespace, spec.topic), Imu)
        self.msg = Imu()
        self.msg.header.frame_id = frame_id(sensor, spec.frame)
        variance = spec.gaussian_noise ** 2
        diagonal = [variance, 0.0, 0.0, 0.0, variance, 0.0, 0.0, 0.0, variance]
        self.msg.orientation_covariance = list(diagonal)
        self.msg.angular_velocity_covariance = list(diagonal)
        self.msg.linear_acceleration_covariance = list(diagonal)

    def publish(self, stamp) -> None:
        if self.pub.get_num_connections() == 0:
            return
        TIMES.switch("sensors")
        reading = self.sensor.reading(stamp.to_nsec())
        TIMES.switch("building")
        msg = self.msg
        msg.header.stamp = stamp
        (msg.orientation.x, msg.orientation.y, msg.orientation.z,
         msg.orientation.w) = reading.orientation
        msg.angular_velocity = Vector3(*reading.angular_velocity)
        msg.linear_acceleration = Vector3(*reading.linear_acceleration)
        self.pub.publish(msg)


def camera_base(spec) -> str:
    """A camera plugin's namespace: <cameraName> in its <robotNamespace>."""
    return resolved(spec.robot_namespace, spec.camera_name) if spec.camera_name else (
        spec.robot_namespace)


def camera_messages(camera, frame: str):
    """(CameraInfo, Image) of a CameraRunner in ``frame``, their fixed fields filled."""
    size = camera.camera_spec
    info = camera_info(camera.intrinsics, size.width, size.height, frame)
    image = Image(height=size.height, width=size.width, encoding=camera.encoding,
                  is_bigendian=0, step=camera.pixel_bytes * size.width)
    image.header.frame_id = frame
    return info, image


def depth_values(metres, cutoff: float, sixteen: bool, cutoff_max: float = math.inf):
    """gazebo_ros_depth_camera's depth image: m (float32), NaN at or inside ``cutoff`` (and,
    openni_kinect's, at or beyond ``cutoff_max``); or with ``sixteen`` mm (uint16, 0 there;
    past 65.535 m it wraps, as the plugin's cast)."""
    with np.errstate(invalid="ignore"):
        seen = metres > cutoff
        if cutoff_max < math.inf:
            seen &= metres < cutoff_max
    if not sixteen:
        return np.where(seen, metres, np.float32(np.nan)).astype(np.float32)
    finite = np.where(seen & np.isfinite(metres), metres * 1000.0, 0.0)
    return (finite.astype(np.int64) % 65536).astype("<u2")


TOPICS = {"laser": _LaserTopic, "range": _RangeTopic, "block_laser": _BlockLaserTopic,
          "camera": _CameraTopic, "depth_camera": _DepthCameraTopic,
          "triggered_camera": _TriggeredCameraTopic, "multicamera": _MultiCameraTopic,
          "bumper": _BumperTopic, "imu_sensor": _ImuSensorTopic}


class WorldSensorTopics:
    """The publishers of every running world sensor, following the simulation's
    (WorldSensors.generation: a spawned model's sensors are advertised, a deleted model's taken
    back), and their messages at each tick (``publish``, the node's "world_sensors" output)."""

    def __init__(self, sim, make_publisher, make_subscriber=rospy.Subscriber):
        """``sim``: the Simulation; ``make_publisher(topic, type, queue_size=1)``: the node's
        (non-blocking) publishers; ``make_subscriber(topic, type, callback, queue_size=1)``
        the subscribers of the plugins that listen (a triggered camera's trigger)."""
        self.sim = sim
        self.make_publisher = make_publisher
        self.make_subscriber = make_subscriber
        self.running = RunningTopics("world sensor", self._topic)   # RunningSensor -> topic
        self._warned = 0             # WorldSensors.warnings logged so far
        self.sync()

    @property
    def topics(self):
        """RunningSensor -> its _SensorTopic."""
        return self.running.topics

    def _topic(self, sensor):
        topic = TOPICS[sensor.kind](sensor, self.make_publisher)
        topic.subscribe(self.make_subscriber)
        return topic

    def sync(self) -> None:
        """Advertise the sensors that are new, take back those that are gone."""
        sensors = self.sim.world_sensors
        for warning in sensors.warnings[self._warned:]:
            rospy.logwarn("gazebo: %s", warning)
        self._warned = len(sensors.warnings)
        self.running.sync(sensors.generation, sensors.sensors)

    def publish(self, stamp) -> None:
        """The messages of the sensors due at this step (WorldSensors.due_now)."""
        self.sync()
        self.running.publish(self.sim.world_sensors.due_now, stamp)
        TIMES.switch("other")

    def close(self) -> None:
        self.running.close()
