"""What a robot URDF's ``<gazebo>`` blocks declare: the plugins and sensors Gazebo would load.

Read without ROS, Gazebo or pybullet. Each dataclass of ``robot_plugin_types`` holds one
gazebo_ros plugin's settings with Gazebo's defaults for what the block leaves out
(gazebo_plugins' ``getParameter`` defaults), so the simulation can make what that plugin would
make. Topic names are as written (relative ones resolve in the robot's namespace); frames are
link names, unprefixed. Units: m, s, rad, Hz, N*m, m/s^2.

``read_plugins`` reads them (urdf_file calls it for every URDF): libgazebo_ros_diff_drive (or
another drive of ``drives``: skid steer, planar move, tricycle, force-based move; one drive
a robot) and libgazebo_ros_imu
in a ``<gazebo>`` block, and there the model plugins of ``model_table`` too (p3d,
joint_state_publisher, hector's imu and gps: ``RobotPlugins.model_plugins``);
in a ``<gazebo reference="LINK">`` block the sensors
whose plugin runs on robots (the plugin modules of ``table``: a ray or gpu_ray sensor with
libgazebo_ros_laser or gpu_laser, a camera sensor with libgazebo_ros_camera, a depth sensor
with libgazebo_ros_openni_kinect), read as world models' sensors are (``table.read_sensor``).
Everything else is accepted as it is (surface and material settings, an imu sensor without
plugin, a sensor without ROS plugin, which publishes nothing on ROS in Gazebo either) or named
in one warning (an unknown plugin or sensor, a second drive or IMU plugin, a plugin on the
wrong kind of sensor, a parameter the plugin does not have). Every laser and camera runs, each
on its own topics (``RobotPlugins.lasers``, ``cameras``). Wrong values raise a one-line
UrdfError: every number is held to its limit in ``limits`` (rates, ranges, samples, image
sizes, noise, wheels, torque, poses), every name and topic to ``limits.MAX_NAME`` characters,
topics to ROS's characters.
"""
from typing import Collection, List, Mapping, Optional

from ....errors import UrdfError
from .. import limits
from .robot_plugin_types import (
    DIFF_DRIVE, IMU, CameraSensor, DiffDrivePlugin, Drive, ImuPlugin, LaserSensor, RobotPlugins)
from .sensor_reader import NOISE, SensorReader, plugin_file, strip_slash
from .drives import MODULES as DRIVES
from .gazebo_ros_diff_drive import PARAMS as DIFF_DRIVE_PARAMS, read_diff_drive
from .model_table import is_model_plugin, read_model_plugin
from .table import read_sensor, runs_on

__all__ = ["read_plugins", "read_diff_drive", "plugin_file"]

# --- reading the <gazebo> blocks --------------------------------------------------------------

WHEEL_JOINT_TYPES = ("continuous", "revolute")
# What each model plugin reads (or Gazebo reads and the sim has no use for); anything else in
# the block is ignored by Gazebo, and here it gets a warning (a misspelt parameter, most often).
# A sensor plugin's are its module's PARAMS (table).
MODEL_PLUGIN_PARAMS = {
    DIFF_DRIVE: DIFF_DRIVE_PARAMS,     # gazebo_ros_diff_drive's: a robot's and a model's
    IMU: {"robotNamespace", "bodyName", "frameName", "topicName", "serviceName", "updateRate",
          "gaussianNoise", "xyzOffset", "rpyOffset", "alwaysOn", "imu"},
}
NOT_SIMULATED = "the robot runs without it"


def read_plugins(robot, links: Collection[str], joint_types: Mapping[str, str],
                 path: str) -> RobotPlugins:
    """The plugins and sensors of the ``<gazebo>`` children of ``robot`` (a URDF ``<robot>``
    element of xml_reader, whose ``links`` and joints, ``joint_types`` = {name: type}, are
    already read).

    What gazebo_ros would load becomes a dataclass of robot_plugin_types; what it would not, or
    what this simulator does not make, becomes one line in ``warnings``. A wrong value raises
    UrdfError in xml_reader's one-line form ``<path>:<line>: <element>: <problem>``.
    """
    return _PluginReader(path, links, joint_types).read(robot)


class _PluginReader(SensorReader):
    """One pass over the <gazebo> blocks of one robot."""

    def __init__(self, path, links, joint_types):
        super().__init__(path, UrdfError, NOT_SIMULATED)
        self.links = links
        self.joint_types = joint_types
        self.drive: Optional[Drive] = None
        self.imu: Optional[ImuPlugin] = None
        self.lasers: List[LaserSensor] = []      # every laser, in file order
        self.cameras: List[CameraSensor] = []    # every camera, in file order
        self.model_plugins: List[object] = []      # model_table's plugins, in file order
        self.robot_name = ""

    def read(self, robot) -> RobotPlugins:
        self.robot_name = robot.get("name", "")
        for block in robot.findall("gazebo"):
            self._check_attributes(block)
            reference = block.get("reference", "").strip()
            if reference:
                self._reference_block(block, reference)
            else:
                self._model_block(block)
        return RobotPlugins(self.drive, imu=self.imu, warnings=tuple(self.warnings),
                            model_plugins=tuple(self.model_plugins),
                            lasers=tuple(self.lasers), cameras=tuple(self.cameras))

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
                self.warn("%s is in a <gazebo> block without reference, so on no link; %s"
                          % (self.sensor_id(child), NOT_SIMULATED))

    def _reference_block(self, block, reference) -> None:
        """<gazebo reference="L">: L's sensors; its surface and material settings (mu1, kp,
        material, selfCollide, ...) are accepted as they are (pybullet has its own contacts)."""
        target = strip_slash(reference)
        if target not in self.links and target not in self.joint_types:
            self.fail(block, "reference %r is not a link of this robot" % reference)
        for child in block:
            if child.tag == "plugin":
                self.plugin_id(child)
                self.warn("%s is inside <gazebo reference=%r>, where Gazebo loads no plugin "
                          "(model plugins go in a <gazebo> block without reference); %s"
                          % (self.describe(child), reference, NOT_SIMULATED))
            elif child.tag == "sensor":
                if target in self.links:
                    self._sensor(child, target)
                else:
                    self.warn("%s is on joint %r; %s" % (self.sensor_id(child), target,
                                                         NOT_SIMULATED))

    def _model_plugin(self, elem) -> None:
        name, filename = self.plugin_id(elem)
        if filename == DIFF_DRIVE:
            self._keep_first("drive", self._diff_drive(elem, name), elem, "differential drive")
        elif filename in DRIVES:
            self._keep_first("drive", DRIVES[filename].read(self, elem, name), elem, "drive")
        elif filename == IMU:
            self._keep_first("imu", self._imu(elem, name), elem, "IMU plugin")
        elif is_model_plugin(filename):     # p3d, joint states, hector's (model_table)
            found = read_model_plugin(self, elem, self.robot_name, self.links,
                                      self.joint_types)
            if found is not None:
                self.model_plugins.append(found)
        elif runs_on(filename, self.host):
            self.warn("%s is a sensor plugin outside any <sensor>: Gazebo loads it only inside "
                      "a <sensor> in a <gazebo reference=...> block; %s"
                      % (self.describe(elem), NOT_SIMULATED))
        else:
            self.warn("%s is not simulated here; %s" % (self.describe(elem), NOT_SIMULATED))

    def _sensor(self, elem, link) -> None:
        """The laser or camera of a sensor on ``link`` (table.read_sensor: one plugin of a
        kind a sensor), added to the robot's: every one runs, as in Gazebo."""
        for sensor in read_sensor(self, elem, link):
            (self.lasers if isinstance(sensor, LaserSensor) else self.cameras).append(sensor)

    # --- the model plugins -------------------------------------------------------------------

    def _diff_drive(self, elem, name) -> DiffDrivePlugin:
        self.check_params(elem, DIFF_DRIVE, MODEL_PLUGIN_PARAMS[DIFF_DRIVE])
        return read_diff_drive(self, elem, name, self._wheel_joint)

    def _imu(self, elem, name) -> ImuPlugin:
        self.check_params(elem, IMU, MODEL_PLUGIN_PARAMS[IMU])
        if elem.find("bodyName") is None:
            self.fail(elem, "missing <bodyName> (the link the IMU reads)")
        body = self._link(elem, "bodyName", "", elem)
        # topicName and serviceName default to /default_imu in gazebo_ros_imu.
        return ImuPlugin(
            name=name, body_name=body,
            frame_name=self._link(elem, "frameName", "", elem),
            topic=self.topic(elem, "topicName", "/default_imu"),
            service_name=self.topic(elem, "serviceName", "/default_imu"),
            update_rate=self.rate(elem, "updateRate", 0.0, elem),
            gaussian_noise=self.bounded(elem, "gaussianNoise", 0.0, elem, NOISE),
            robot_namespace=self.topic(elem, "robotNamespace", ""))

    # --- values ------------------------------------------------------------------------------

    def frame(self, plugin, link: str, gazebo_default: str) -> str:
        """A robot's sensor frame: its <frameName>, a link of the robot; without one the
        sensor's own link (gazebo_ros' default "/world" is in no robot's TF tree)."""
        return self._link(plugin, "frameName", link, plugin)

    def _link(self, parent, tag, default: str, owner) -> str:
        elem = parent.find(tag)
        if elem is None:
            return default
        name = strip_slash(self.text(parent, tag, default))
        if name not in self.links:
            self.fail(elem, "%r is not a link of this robot" % elem.value, owner)
        return name

    def _wheel_joint(self, plugin, tag, default: str) -> str:
        elem = plugin.find(tag)
        name = self.text(plugin, tag, default)
        wheels = [j for j, kind in self.joint_types.items() if kind in WHEEL_JOINT_TYPES]
        hint = "its continuous and revolute joints: %s" % (", ".join(wheels) or "none")
        if elem is None and name not in self.joint_types:
            self.fail(plugin, "no <%s>, and the default joint %r is not in this robot (%s)"
                      % (tag, name, hint))
        if name not in self.joint_types:
            self.fail(elem, "joint %r is not in this robot (%s)" % (name, hint), plugin)
        if self.joint_types[name] not in WHEEL_JOINT_TYPES:
            self.fail(self.found(plugin, tag, plugin), "joint %r is %s; a wheel joint must be "
                      "continuous or revolute" % (name, self.joint_types[name]), plugin)
        return name

    wheel_joint = _wheel_joint   # the drive modules' (drives.MODULES) check of a wheel joint

    def _keep_first(self, slot: str, plugin, elem, what: str) -> None:
        """Keep ``plugin`` as the robot's ``slot`` (drive, imu) unless one is there already:
        only one of each is simulated, a second one is warned about."""
        first = getattr(self, slot)
        if first is None:
            setattr(self, slot, plugin)
        else:
            self.second(elem, what, first.name)
