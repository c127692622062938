"""ROS glue of a simulated camera: the topics Gazebo's camera plugins and the real robot use.

Publications, named by the URDF's camera plugin (cameraName, imageTopicName, ...) in the
robot's namespace; for a TurtleBot3 (frame ``camera_rgb_optical_frame``, one render a tick):
  camera/rgb/image_raw, camera/image                    sensor_msgs/Image, rgb8
  camera/rgb/camera_info, camera/camera_info            sensor_msgs/CameraInfo, plumb_bob
  camera/rgb/image_raw/compressed, camera/image/compressed   sensor_msgs/CompressedImage, jpeg
  a depth camera (the waffle's RealSense R200, libgazebo_ros_openni_kinect) also:
  camera/depth/image_raw (32FC1, metres, NaN outside 0.4..5 m), camera/depth/camera_info,
  camera/depth/points (sensor_msgs/PointCloud2, organized, x y z rgb)
``camera/image`` and ``camera/camera_info`` are the real robot's names (its cv_camera).
A camera with a lens <distortion> or another <format> publishes as a world model's
(world_sensor_topics): the image distorted and in its format's encoding (mono8 for L8 ...),
CameraInfo's D the plugin's; its jpeg is of that image as image_transport's compressed plugin
makes it (8 bits a channel; none of a Bayer image), a point cloud's colours only from rgb8.
A robot's further cameras (SimRobot.cameras) have a CameraPublisher each, with their own names.
Nothing is rendered or encoded for topics nobody subscribes to.
"""
import rospy
from sensor_msgs.msg import CameraInfo, CompressedImage, Image, PointCloud2, PointField

from ..sim.devices.camera import (CameraIntrinsics, depth_image, jpeg_available, jpeg_bytes,
                                  pointcloud_bytes, pointcloud_xyz)
from ..sim.devices.image_formats import encoding as image_encoding
from rosgraph.names import ns_join

COMPRESSED_FORMAT = "rgb8; jpeg compressed bgr8"  # as image_transport's compressed plugin


def jpeg_source(pixels, encoding: str):
    """The 8-bit rgb (or grey) image image_transport's compressed plugin encodes of an Image of
    ``encoding`` and pixels ``pixels`` (16-bit channels: their high byte)."""
    eight = pixels if pixels.dtype.itemsize == 1 else (pixels >> 8).astype("uint8")
    return eight[:, :, ::-1] if encoding == "bgr8" else eight


def jpeg_format(encoding: str) -> str:
    """CompressedImage.format of an Image of ``encoding``, as the compressed plugin names it."""
    return "%s; jpeg compressed %s" % (encoding, "mono8" if encoding.startswith("mono")
                                       else "bgr8")


def camera_info(intrinsics: CameraIntrinsics, width: int, height: int,
                frame: str) -> CameraInfo:
    """The CameraInfo gazebo_ros_camera_utils fills for these intrinsics."""
    info = CameraInfo(width=width, height=height, distortion_model=intrinsics.distortion_model,
                      D=intrinsics.D(), K=intrinsics.K(), R=intrinsics.R(), P=intrinsics.P())
    info.header.frame_id = frame
    return info


class CameraPublisher:
    """Renders one of a robot's cameras when one of its topics has a subscriber, and
    publishes."""

    def __init__(self, robot, make_publisher=rospy.Publisher, namespace: str = "",
                 frame_prefix: str = "", index: int = 0):
        """``robot``: a SimRobot with a camera (``camera_sensor``, ``camera_image``);
        ``make_publisher(topic, type, queue_size=...)``: rospy.Publisher, or a stand-in;
        topics in ``namespace`` ("" = the node's), frames prefixed with ``frame_prefix``;
        ``index``: which of the robot's ``cameras`` (0: the first, ``camera_sensor``)."""
        self.robot, self.index = robot, index
        if index == 0:
            spec, sensor = robot.camera_spec, robot.camera_sensor
            self.intrinsics = robot.camera_intrinsics
        else:
            camera = robot.cameras[index]
            spec, sensor, self.intrinsics = camera.spec, camera.sensor, camera.intrinsics
        base = ns_join(namespace, sensor.camera_name) if namespace else sensor.camera_name

        advertised = set()

        def pubs(msg_type, *topics):
            """One publisher per topic (the plugin's names may equal the real robot's)."""
            out = []
            for name in (ns_join(base, t) for t in topics):
                if name not in advertised:
                    advertised.add(name)
                    out.append(make_publisher(name, msg_type, queue_size=1))
            return out
        self.image_pubs = pubs(Image, sensor.image_topic, "image")
        self.info_pubs = pubs(CameraInfo, sensor.info_topic, "camera_info")
        self.encoding, pixel_bytes = image_encoding(sensor.image_format)
        self.jpeg_pubs = (pubs(CompressedImage, sensor.image_topic + "/compressed",
                               "image/compressed")
                          if jpeg_available() and not self.encoding.startswith("bayer") else [])
        self.depth_pubs, self.points_pubs = [], []
        if spec.depth:
            self.depth_pubs = pubs(Image, sensor.depth_image_topic)
            self.info_pubs += pubs(CameraInfo, sensor.depth_info_topic)
            self.points_pubs = pubs(PointCloud2, sensor.point_cloud_topic)
        frame = frame_prefix + sensor.frame.lstrip("/")
        self.info = camera_info(self.intrinsics, spec.width, spec.height, frame)
        self.image = Image(height=spec.height, width=spec.width, encoding=self.encoding,
                           is_bigendian=0, step=pixel_bytes * spec.width)
        self.image.header.frame_id = frame
        self.depth = Image(height=spec.height, width=spec.width, encoding="32FC1",
                           is_bigendian=0, step=4 * spec.width)
        self.depth.header.frame_id = frame
        self.jpeg = CompressedImage(format=COMPRESSED_FORMAT if self.encoding == "rgb8"
                                    else jpeg_format(self.encoding))
        self.jpeg.header.frame_id = frame
        self.points = PointCloud2(height=spec.height, width=spec.width, is_bigendian=False,
                                  is_dense=False)
        self.points.header.frame_id = frame

    @staticmethod
    def _wanted(pubs):
        return [p for p in pubs if p.get_num_connections() > 0]

    def publish(self, stamp: rospy.Time) -> None:
        """One camera tick at sim time ``stamp``."""
        images, jpegs = self._wanted(self.image_pubs), self._wanted(self.jpeg_pubs)
        depths, points = self._wanted(self.depth_pubs), self._wanted(self.points_pubs)
        for pub in self._wanted(self.info_pubs):
            self.info.header.stamp = stamp
            pub.publish(self.info)
        if not (images or jpegs or depths or points):
            return
        wants_depth = bool(depths or points)
        rgb, depth = (self.robot.camera_image(depth=wants_depth, index=self.index) if self.index
                      else self.robot.camera_image(depth=wants_depth))
        if images:
            self.image.header.stamp = stamp
            self.image.data = rgb.tobytes()
            for pub in images:
                pub.publish(self.image)
        if jpegs:
            self.jpeg.header.stamp = stamp
            self.jpeg.data = jpeg_bytes(rgb if self.encoding == "rgb8"
                                        else jpeg_source(rgb, self.encoding))
            for pub in jpegs:
                pub.publish(self.jpeg)
        if depths:
            self.depth.header.stamp = stamp
            self.depth.data = depth_image(depth).tobytes()
            for pub in depths:
                pub.publish(self.depth)
        if points:
            self._publish_points(stamp, rgb, depth, points)

    def _publish_points(self, stamp, rgb, depth, pubs) -> None:
        if self.encoding == "rgb8":
            data, point_step, fields = pointcloud_bytes(*pointcloud_xyz(
                depth, self.intrinsics, organized=True, rgb=rgb))
        else:     # no colours but rgb8's, as a world model's depth camera
            data, point_step, fields = pointcloud_bytes(pointcloud_xyz(
                depth, self.intrinsics, organized=True))
        msg = self.points
        msg.header.stamp = stamp
        msg.fields = [PointField(name=name, offset=offset, datatype=PointField.FLOAT32, count=1)
                      for name, offset in fields]
        msg.point_step = point_step
        msg.row_step = point_step * msg.width
        msg.data = data
        for pub in pubs:
            pub.publish(msg)
