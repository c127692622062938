"""What a robot URDF's ``<gazebo>`` blocks declare: the plugins and sensors Gazebo would load.

Read without ROS, Gazebo or pybullet. Each dataclass of ``robot_plugin_types`` holds one
gazebo_ros plugin's settings with Gazebo's defaults for what the block leaves out
(gazebo_plugins' ``getParameter`` defaults), so the simulation can make what that plugin would
make. Topic names are as written (relative ones resolve in the robot's namespace); frames are
link names, unprefixed. Units: m, s, rad, Hz, N*m, m/s^2.

``read_plugins`` reads them (urdf_file calls it for every URDF): libgazebo_ros_diff_drive and
libgazebo_ros_imu in a ``<gazebo>`` block; in a ``<gazebo reference="LINK">`` block a ray (or
gpu_ray) sensor with libgazebo_ros_laser (gpu_laser), a camera sensor with
libgazebo_ros_camera, a depth sensor with libgazebo_ros_openni_kinect. Everything else is
accepted as it is (surface and material settings, an imu sensor without plugin, a sensor
without ROS plugin, which publishes nothing on ROS in Gazebo either) or named in one warning
(an unknown plugin or sensor, a second laser or camera, a plugin on the wrong kind of sensor, a
parameter the plugin does not have). Wrong values raise a one-line UrdfError: every number is
held to its limit in ``limits`` (rates, ranges, samples, image sizes, noise, wheels, torque,
poses), every name and topic to ``limits.MAX_NAME`` characters, topics to ROS's characters.
"""
import math
import os
from typing import Collection, Dict, List, Mapping, NamedTuple, Optional, Tuple

from ...errors import UrdfError
from ...ros_names import is_legal_name
from . import limits
from ..kinematics import ZERO_XYZ_RPY, XyzRpy
from .robot_plugin_types import (
    CAMERA, DIFF_DRIVE, GPU_LASER, IMU, LASER, OPENNI_KINECT, CameraSensor, CameraSpec,
    DiffDrivePlugin, ImuPlugin, LaserConfig, LaserSensor, RobotPlugins)
from .xml_reader import Element, XmlReader

# --- reading the <gazebo> blocks --------------------------------------------------------------

# A sensor type -> the gazebo_ros plugin that publishes it on ROS (the only pairs Gazebo loads).
SENSOR_PLUGIN = {"ray": LASER, "gpu_ray": GPU_LASER, "camera": CAMERA, "depth": OPENNI_KINECT}
WHEEL_JOINT_TYPES = ("continuous", "revolute")
NOISE_TYPES = ("gaussian", "gaussian_quantized", "none")
_CAMERA_PARAMS = {
    "robotNamespace", "alwaysOn", "updateRate", "cameraName", "frameName", "imageTopicName",
    "cameraInfoTopicName", "hackBaseline", "distortionK1", "distortionK2", "distortionK3",
    "distortionT1", "distortionT2", "CxPrime", "Cx", "Cy", "focalLength", "borderCrop"}
# What each plugin reads (or Gazebo reads and the sim has no use for); anything else in the
# block is ignored by Gazebo, and here it gets a warning (a misspelt parameter, most often).
PLUGIN_PARAMS = {
    DIFF_DRIVE: {
        "robotNamespace", "commandTopic", "odometryTopic", "odometryFrame", "robotBaseFrame",
        "odometrySource", "publishTf", "publishOdomTF", "publishWheelTF",
        "publishWheelJointState", "updateRate", "leftJoint", "rightJoint", "wheelSeparation",
        "wheelDiameter", "wheelAcceleration", "wheelTorque", "legacyMode", "rosDebugLevel",
        "alwaysOn"},
    IMU: {"robotNamespace", "bodyName", "frameName", "topicName", "serviceName", "updateRate",
          "gaussianNoise", "xyzOffset", "rpyOffset", "alwaysOn", "imu"},
    LASER: {"robotNamespace", "topicName", "frameName", "alwaysOn"},
    GPU_LASER: {"robotNamespace", "topicName", "frameName", "alwaysOn"},
    CAMERA: _CAMERA_PARAMS,
    OPENNI_KINECT: _CAMERA_PARAMS | {
        "depthImageTopicName", "depthImageCameraInfoTopicName", "pointCloudTopicName",
        "pointCloudCutoff", "pointCloudCutoffMax", "baseline"},
}
NOT_SIMULATED = "the robot runs without it"


def plugin_file(filename: str) -> str:
    """The library a ``<plugin filename=...>`` names, as Gazebo completes it: the base name with
    a ``lib`` prefix and a ``.so`` suffix (``gazebo_ros_laser`` -> ``libgazebo_ros_laser.so``)."""
    name = os.path.basename(filename.strip())
    if not name.startswith("lib"):
        name = "lib" + name
    if not name.endswith(".so"):
        name += ".so"
    return name


def read_plugins(robot: Element, links: Collection[str], joint_types: Mapping[str, str],
                 path: str) -> RobotPlugins:
    """The plugins and sensors of the ``<gazebo>`` children of ``robot`` (a URDF ``<robot>``
    element of xml_reader, whose ``links`` and joints, ``joint_types`` = {name: type}, are
    already read).

    What gazebo_ros would load becomes a dataclass of robot_plugin_types; what it would not, or
    what this simulator does not make, becomes one line in ``warnings``. A wrong value raises
    UrdfError in xml_reader's one-line form ``<path>:<line>: <element>: <problem>``.
    """
    return _PluginReader(path, links, joint_types).read(robot)


def _strip_slash(name: str) -> str:
    """gazebo_ros takes "/base_scan" and "base_scan" for the same frame."""
    return name[1:] if name.startswith("/") else name


class _PluginReader(XmlReader):
    """One pass over the <gazebo> blocks of one robot."""

    def __init__(self, path, links, joint_types):
        super().__init__(path, UrdfError)
        self.links = links
        self.joint_types = joint_types
        self.warnings: List[str] = []
        self.drive: Optional[DiffDrivePlugin] = None
        self.imu: Optional[ImuPlugin] = None
        self.laser: Optional[LaserSensor] = None
        self.camera: Optional[CameraSensor] = None

    def read(self, robot) -> RobotPlugins:
        for block in robot.findall("gazebo"):
            self._check_attributes(block)
            reference = block.get("reference", "").strip()
            if reference:
                self._reference_block(block, reference)
            else:
                self._model_block(block)
        return RobotPlugins(self.drive, self.laser, self.imu, self.camera, tuple(self.warnings))

    # --- blocks ---------------------------------------------------------------------------

    def _check_attributes(self, block) -> None:
        """Every attribute in ``block`` (reference, names, filenames, types) is at most
        limits.MAX_NAME characters, before any message names one."""
        for elem in block.iter():
            for key, value in elem.attrib.items():
                problem = limits.name_problem(key, value)
                if problem:
                    self.fail_bare(elem, "<%s>: %s" % (elem.tag, problem))

    def _model_block(self, block) -> None:
        """<gazebo> without reference: model plugins. Model properties (static, self_collide,
        ...) are accepted as they are."""
        for child in block:
            if child.tag == "plugin":
                self._model_plugin(child)
            elif child.tag == "sensor":
                self._warn("%s is in a <gazebo> block without reference, so on no link; %s"
                           % (self._sensor_id(child), NOT_SIMULATED))

    def _reference_block(self, block, reference) -> None:
        """<gazebo reference="L">: L's sensors; its surface and material settings (mu1, kp,
        material, selfCollide, ...) are accepted as they are (pybullet has its own contacts)."""
        target = _strip_slash(reference)
        if target not in self.links and target not in self.joint_types:
            self.fail(block, "reference %r is not a link of this robot" % reference)
        for child in block:
            if child.tag == "plugin":
                self._plugin_id(child)
                self._warn("%s is inside <gazebo reference=%r>, where Gazebo loads no plugin "
                           "(model plugins go in a <gazebo> block without reference); %s"
                           % (self.describe(child), reference, NOT_SIMULATED))
            elif child.tag == "sensor":
                if target in self.links:
                    self._sensor(child, target)
                else:
                    self._warn("%s is on joint %r; %s" % (self._sensor_id(child), target,
                                                          NOT_SIMULATED))

    def _model_plugin(self, elem) -> None:
        name, filename = self._plugin_id(elem)
        if filename == DIFF_DRIVE:
            self._keep_first("drive", self._diff_drive(elem, name), elem, "differential drive")
        elif filename == IMU:
            self._keep_first("imu", self._imu(elem, name), elem, "IMU plugin")
        elif filename in SENSOR_PLUGIN.values():
            self._warn("%s is a sensor plugin outside any <sensor>: Gazebo loads it only inside "
                       "a <sensor> in a <gazebo reference=...> block; %s"
                       % (self.describe(elem), NOT_SIMULATED))
        else:
            self._warn("%s is not simulated here; %s" % (self.describe(elem), NOT_SIMULATED))

    def _sensor(self, elem, link) -> None:
        kind = self.attr(elem, "type")
        self.attr(elem, "name")
        wanted = SENSOR_PLUGIN.get(kind)
        plugins = elem.findall("plugin")
        if wanted is None:
            if kind != "imu":
                self._warn("%s on link %r is not simulated here; %s"
                           % (self._sensor_id(elem), link, NOT_SIMULATED))
            # An imu sensor alone talks only on Gazebo transport (TurtleBot3 has one on
            # imu_link): nothing to make. A ROS plugin on it is another matter.
            for plugin in plugins if kind == "imu" else ():
                self._warn("%s is not simulated here; %s"
                           % (self.describe(plugin), NOT_SIMULATED))
            return
        ros_plugin = None
        for plugin in plugins:
            _, filename = self._plugin_id(plugin)
            if filename == wanted and ros_plugin is None:
                ros_plugin = plugin
            elif filename == wanted:
                self._second(plugin, "%s on %s" % (wanted, self._sensor_id(elem)),
                             ros_plugin.get("name", ""))
            elif filename in SENSOR_PLUGIN.values():
                needs = [k for k, v in SENSOR_PLUGIN.items() if v == filename][0]
                self._warn('%s on %s is of the wrong kind (it needs a <sensor type="%s">); %s'
                           % (self.describe(plugin), self._sensor_id(elem), needs,
                              NOT_SIMULATED))
            else:
                self._warn("%s is not simulated here; %s"
                           % (self.describe(plugin), NOT_SIMULATED))
        if ros_plugin is None:
            return  # no ROS plugin: Gazebo publishes nothing of it on ROS; nor do we
        if kind in ("ray", "gpu_ray"):
            self._keep_first("laser", self._laser(elem, ros_plugin, link), elem, "laser")
        else:
            self._keep_first("camera", self._camera(elem, ros_plugin, link,
                                                    depth=(kind == "depth")), elem, "camera")

    # --- the plugins -------------------------------------------------------------------------

    def _diff_drive(self, elem, name) -> DiffDrivePlugin:
        self._check_params(elem, DIFF_DRIVE)
        source_elem = elem.find("odometrySource")
        source = "world"
        if source_elem is not None:
            source = self._string(elem, "odometrySource", "world")
            if source not in ("world", "encoder"):
                self.fail(source_elem, "must be world or encoder, got %r" % source, elem)
        number = self._number
        return DiffDrivePlugin(
            name=name,
            command_topic=self._topic(elem, "commandTopic", "cmd_vel"),
            odometry_topic=self._topic(elem, "odometryTopic", "odom"),
            odometry_frame=self._string(elem, "odometryFrame", "odom"),
            robot_base_frame=self._string(elem, "robotBaseFrame", "base_footprint"),
            odometry_source="encoders" if source == "encoder" else "world",
            publish_tf=self._bool(elem, "publishTf", True),
            publish_wheel_tf=self._bool(elem, "publishWheelTF", False),
            publish_wheel_joint_state=self._bool(elem, "publishWheelJointState", False),
            update_rate=self._rate(elem, "updateRate", 100.0, elem),
            left_joint=self._wheel_joint(elem, "leftJoint", "left_joint"),
            right_joint=self._wheel_joint(elem, "rightJoint", "right_joint"),
            wheel_separation=number(elem, "wheelSeparation", 0.34, elem, _WHEEL),
            wheel_diameter=number(elem, "wheelDiameter", 0.15, elem, _WHEEL),
            wheel_acceleration=number(elem, "wheelAcceleration", 0.0, elem, _ACCELERATION),
            wheel_torque=number(elem, "wheelTorque", 5.0, elem, _TORQUE),
            robot_namespace=self._topic(elem, "robotNamespace", ""),
            publish_odom_tf=self._bool(elem, "publishOdomTF", True))

    def _imu(self, elem, name) -> ImuPlugin:
        self._check_params(elem, IMU)
        if elem.find("bodyName") is None:
            self.fail(elem, "missing <bodyName> (the link the IMU reads)")
        body = self._link(elem, "bodyName", "", elem)
        # topicName and serviceName default to /default_imu in gazebo_ros_imu.
        return ImuPlugin(
            name=name, body_name=body,
            frame_name=self._link(elem, "frameName", "", elem),
            topic=self._topic(elem, "topicName", "/default_imu"),
            service_name=self._topic(elem, "serviceName", "/default_imu"),
            update_rate=self._rate(elem, "updateRate", 0.0, elem),
            gaussian_noise=self._number(elem, "gaussianNoise", 0.0, elem, _NOISE),
            robot_namespace=self._topic(elem, "robotNamespace", ""))

    def _laser(self, sensor, plugin, link) -> LaserSensor:
        filename = plugin_file(plugin.get("filename", ""))
        self._check_params(plugin, filename)
        ray = self.child(sensor, "ray")
        scan = ray.find("scan")
        horizontal = scan.find("horizontal") if scan is not None else None
        samples = self._integer(horizontal, "samples", 640, sensor, limits.MAX_LASER_SAMPLES)
        self._number(horizontal, "resolution", 1.0, sensor, _FACTOR)
        angle_min = self._number(horizontal, "min_angle", 0.0, sensor, _ANGLE)
        angle_max = self._number(horizontal, "max_angle", 0.0, sensor, _ANGLE)
        if angle_min >= angle_max:
            self.fail(self._find(horizontal, "max_angle", sensor),
                      "max_angle %g must be greater than min_angle %g" % (angle_max, angle_min),
                      sensor)
        vertical = scan.find("vertical") if scan is not None else None
        if vertical is not None and self.integer(vertical, "samples", 1, sensor) > 1:
            self._warn("%s: a scan of several vertical planes is not simulated; only the "
                       "horizontal plane is" % self._sensor_id(sensor))
        ranges = self.child(ray, "range", sensor)
        range_min = self._number(ranges, "min", 0.0, sensor, _DISTANCE)
        if ranges.find("max") is None:
            self.fail(ranges, "missing <max>", sensor)
        range_max = self._number(ranges, "max", 0.0, sensor, _DISTANCE)
        if range_min >= range_max:
            self.fail(ranges.find("max"), "max %g must be greater than min %g"
                      % (range_max, range_min), sensor)
        sigma = self._noise(ray.find("noise"), sensor)
        rate = self._rate(sensor, "update_rate", 0.0, sensor)
        increment = (angle_max - angle_min) / (samples - 1) if samples > 1 else 0.0
        config = LaserConfig("gazebo", angle_min, angle_max, increment, samples=samples,
                             range_min=range_min, range_max=range_max, noise_sigma=sigma,
                             rate=rate)
        return LaserSensor(
            name=sensor.get("name"), link=link, laser=config,
            topic=self._topic(plugin, "topicName", "/world"),
            # gazebo_ros_laser's default frame is "/world", which is in no robot's TF tree;
            # the sensor's own link is what a scan without <frameName> is meant to be in.
            frame=self._link(plugin, "frameName", link, plugin),
            plugin=plugin.get("name", "").strip(),
            robot_namespace=self._topic(plugin, "robotNamespace", ""),
            plugin_file=filename, pose=self._pose(sensor),
            range_resolution=self._number(ranges, "resolution", 0.0, sensor, _DISTANCE))

    def _noise(self, noise, sensor) -> float:
        """The gaussian sigma (m) of a <ray><noise>; 0 without one."""
        if noise is None:
            return 0.0
        kind = self._string(noise, "type", "gaussian")
        if kind not in NOISE_TYPES:
            self.fail(noise.find("type"), "must be one of %s, got %r"
                      % (", ".join(NOISE_TYPES), kind), sensor)
        mean = self._number(noise, "mean", 0.0, sensor, _NOISE_MEAN)
        sigma = self._number(noise, "stddev", 0.0, sensor, _NOISE)
        if kind == "none":
            return 0.0
        if mean != 0.0:
            self._warn("%s: noise <mean> %g is not simulated (the noise here has mean 0)"
                       % (self._sensor_id(sensor), mean))
        return sigma

    def _camera(self, sensor, plugin, link, depth) -> CameraSensor:
        filename = plugin_file(plugin.get("filename", ""))
        self._check_params(plugin, filename)
        # Gazebo's <camera> defaults: 320x240, 1.047 rad, clip 0.1..100 m.
        camera = sensor.find("camera")
        image = camera.find("image") if camera is not None else None
        clip = camera.find("clip") if camera is not None else None
        hfov = self._number(camera, "horizontal_fov", 1.047, sensor, _FIELD_OF_VIEW)
        width = self._integer(image, "width", 320, sensor, limits.MAX_IMAGE_SIDE, "px")
        height = self._integer(image, "height", 240, sensor, limits.MAX_IMAGE_SIDE, "px")
        image_format = self._string(image, "format", "R8G8B8")
        if image_format != "R8G8B8":
            self._warn("%s: image format %r is not simulated; the images are R8G8B8 (rgb8)"
                       % (self._sensor_id(sensor), image_format))
        near = self._number(clip, "near", 0.1, sensor, _REACH)
        far = self._number(clip, "far", 100.0, sensor, _REACH)
        if near >= far:
            self.fail(self._find(clip, "far", sensor),
                      "far %g must be greater than near %g" % (far, near), sensor)
        plugin_rate = self._rate(plugin, "updateRate", 0.0, plugin)
        sensor_rate = self._rate(sensor, "update_rate", 0.0, sensor)
        distortion = [self.number(plugin, key, 0.0, plugin) for key in (   # not simulated
            "distortionK1", "distortionK2", "distortionK3", "distortionT1", "distortionT2")]
        if any(distortion):
            self._warn("%s: lens distortion is not simulated; the images are undistorted"
                       % self.describe(plugin))
        spec = CameraSpec(width=width, height=height, hfov=hfov,
                          rate=plugin_rate if plugin_rate > 0 else sensor_rate,
                          near=near, far=far, depth=depth,
                          # the first <hackBaseline> counts, as sdformat's GetElement finds it
                          baseline=self._number(plugin, "hackBaseline", 0.0, plugin,
                                                _BASELINE))
        extra: Dict[str, object] = {}
        if depth:
            cutoff = self._number(plugin, "pointCloudCutoff", 0.4, plugin, _DISTANCE)
            cutoff_max = self._number(plugin, "pointCloudCutoffMax", 5.0, plugin, _DISTANCE)
            if cutoff_max <= cutoff:
                self.fail(self._find(plugin, "pointCloudCutoffMax", plugin),
                          "pointCloudCutoffMax %g must be greater than pointCloudCutoff %g"
                          % (cutoff_max, cutoff), plugin)
            extra = dict(
                depth_image_topic=self._topic(plugin, "depthImageTopicName", "depth/image_raw"),
                depth_info_topic=self._topic(plugin, "depthImageCameraInfoTopicName",
                                             "depth/camera_info"),
                point_cloud_topic=self._topic(plugin, "pointCloudTopicName", "points"),
                point_cloud_cutoff=cutoff, point_cloud_cutoff_max=cutoff_max)
        return CameraSensor(
            name=sensor.get("name"), link=link, spec=spec, plugin_file=filename,
            camera_name=self._topic(plugin, "cameraName", ""),
            # gazebo_ros_camera_utils' default frame is "/world", in no robot's TF tree; the
            # sensor's link is what an image without <frameName> is meant to be in.
            frame=self._link(plugin, "frameName", link, plugin),
            image_topic=self._topic(plugin, "imageTopicName", "image_raw"),
            info_topic=self._topic(plugin, "cameraInfoTopicName", "camera_info"),
            robot_namespace=self._topic(plugin, "robotNamespace", ""),
            pose=self._pose(sensor), **extra)

    # --- values ------------------------------------------------------------------------------

    def _check_params(self, plugin, filename) -> None:
        known = PLUGIN_PARAMS[filename]
        for child in plugin:
            if child.tag not in known:
                hint = ""
                if filename in (LASER, GPU_LASER) and "rate" in child.tag.lower():
                    hint = " (a scan's rate is its sensor's <update_rate>)"
                self._warn("%s: <%s> is not a parameter of %s; ignored, as in Gazebo%s"
                           % (self.describe(plugin), child.tag, filename, hint))

    def _text(self, elem) -> str:
        return elem.value

    def _find(self, parent, tag, owner):
        """``parent``'s first <tag>, else ``parent`` (else ``owner``): where an error points."""
        elem = parent.find(tag) if parent is not None else None
        return elem if elem is not None else (parent if parent is not None else owner)

    def _string(self, parent, tag, default: str) -> str:
        """The text of the optional child <tag>: at most limits.MAX_NAME characters."""
        elem = parent.find(tag) if parent is not None else None
        if elem is None:
            return default
        problem = limits.name_problem(tag, elem.value)
        if problem:
            self.fail(elem, problem, parent)
        return elem.value

    def _topic(self, parent, tag, default: str) -> str:
        """A topic, service or namespace name: a ROS name (letters, digits, _ and /)."""
        name = self._string(parent, tag, default)
        if not is_legal_name(name):
            self.fail(parent.find(tag), "%r is not a ROS name (a letter, / or ~ first, then "
                                        "letters, digits, _ and /)" % name, parent)
        return name

    def _number(self, parent, tag, default: float, owner, bounds: "_Bounds") -> float:
        """The number of the optional child <tag> within ``bounds``: limits' one-line refusal
        otherwise."""
        value = self.number(parent, tag, default, owner)
        problem = limits.outside(tag, value, *bounds)
        if problem:
            self.fail(self._find(parent, tag, owner), problem, owner)
        return value

    def _rate(self, parent, tag, default: float, owner) -> float:
        """An update rate (Hz): 0 or within limits.rate_problem's range."""
        value = self.number(parent, tag, default, owner)
        problem = limits.rate_problem(tag, value)
        if problem:
            self.fail(self._find(parent, tag, owner), problem, owner)
        return value

    def _integer(self, parent, tag, default: int, owner, high: int, unit: str = "") -> int:
        """The positive integer of the optional child <tag>, at most ``high``."""
        value = self.integer(parent, tag, default, owner)
        problem = limits.outside(tag, value, 1, high, unit)
        if problem:
            self.fail(self._find(parent, tag, owner), problem, owner)
        return value

    def _bool(self, parent, tag, default: bool) -> bool:
        return self.flag(parent, tag, default, parent)

    def _pose(self, sensor) -> XyzRpy:
        pose = tuple(self.xyz_rpy(sensor, "pose", ZERO_XYZ_RPY, sensor))
        problem = (limits.position_problem("pose", pose[:3])
                   or limits.angles_problem("pose", pose[3:]))
        if problem:
            self.fail(sensor.find("pose"), problem, sensor)
        return pose

    def _link(self, parent, tag, default: str, owner) -> str:
        elem = parent.find(tag)
        if elem is None:
            return default
        name = _strip_slash(self._string(parent, tag, default))
        if name not in self.links:
            self.fail(elem, "%r is not a link of this robot" % self._text(elem), owner)
        return name

    def _wheel_joint(self, plugin, tag, default: str) -> str:
        elem = plugin.find(tag)
        name = self._string(plugin, tag, default)
        wheels = [j for j, kind in self.joint_types.items() if kind in WHEEL_JOINT_TYPES]
        hint = "its continuous and revolute joints: %s" % (", ".join(wheels) or "none")
        if elem is None and name not in self.joint_types:
            self.fail(plugin, "no <%s>, and the default joint %r is not in this robot (%s)"
                      % (tag, name, hint))
        if name not in self.joint_types:
            self.fail(elem, "joint %r is not in this robot (%s)" % (name, hint), plugin)
        if self.joint_types[name] not in WHEEL_JOINT_TYPES:
            self.fail(self._find(plugin, tag, plugin), "joint %r is %s; a wheel joint must be "
                      "continuous or revolute" % (name, self.joint_types[name]), plugin)
        return name

    def _plugin_id(self, elem) -> Tuple[str, str]:
        """(name, library) of a <plugin>; the filename is required, the name may be empty."""
        return elem.get("name", "").strip(), plugin_file(self.attr(elem, "filename"))

    # --- messages ----------------------------------------------------------------------------

    def describe(self, elem) -> str:
        """How messages call a <plugin>, <sensor> or <gazebo> element (else "<tag>")."""
        name = elem.get("name", "").strip()
        if elem.tag == "plugin":
            filename = elem.get("filename", "").strip()
            if not filename:
                return "plugin %r" % name if name else "<plugin>"
            return ("plugin %r (%s)" % (name, plugin_file(filename)) if name
                    else "plugin %s" % plugin_file(filename))
        if elem.tag == "sensor" and name:
            return "sensor %r" % name
        if elem.tag == "gazebo" and elem.get("reference"):
            return "<gazebo reference=%r>" % elem.get("reference")
        return "<%s>" % elem.tag

    def _sensor_id(self, elem) -> str:
        return "sensor %r (type %s)" % (elem.get("name", ""), elem.get("type", "?"))

    def _keep_first(self, slot: str, plugin, elem, what: str) -> None:
        """Keep ``plugin`` as the robot's ``slot`` (drive, imu, laser, camera) unless one is
        there already: only one of each is simulated, a second one is warned about."""
        first = getattr(self, slot)
        if first is None:
            setattr(self, slot, plugin)
        else:
            self._second(elem, what, first.name)

    def _second(self, elem, what, first) -> None:
        self._warn("%s: a second %s is not simulated here (only one per robot: %r is); %s"
                   % (self.describe(elem), what, first, NOT_SIMULATED))

    def _warn(self, message: str) -> None:
        self.warnings.append(message)


# --- the bounds of the numbers (limits.outside's arguments) ------------------------------------

class _Bounds(NamedTuple):
    low: float
    high: float
    unit: str = ""
    low_open: bool = False
    high_open: bool = False


_DISTANCE = _Bounds(0.0, limits.MAX_RANGE, "m")             # a range, a resolution, a cut-off
_REACH = _Bounds(0.0, limits.MAX_RANGE, "m", low_open=True)  # a clip plane
_ANGLE = _Bounds(-limits.MAX_ANGLE, limits.MAX_ANGLE, "rad")
_FIELD_OF_VIEW = _Bounds(0.0, math.pi, "rad", low_open=True, high_open=True)
_FACTOR = _Bounds(0.0, limits.MAX_SCALE, low_open=True)
_NOISE = _Bounds(0.0, limits.MAX_NOISE)                      # a standard deviation
_NOISE_MEAN = _Bounds(-limits.MAX_NOISE, limits.MAX_NOISE)
_WHEEL = _Bounds(limits.MIN_WHEEL_SIZE, limits.MAX_SIZE, "m")   # a diameter, a separation
_ACCELERATION = _Bounds(0.0, limits.MAX_ACCELERATION, "m/s^2")
_TORQUE = _Bounds(0.0, limits.MAX_FORCE, "N m", low_open=True)
_BASELINE = _Bounds(-limits.MAX_SIZE, limits.MAX_SIZE, "m")
