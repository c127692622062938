"""What a robot URDF's ``<gazebo>`` blocks declare: the plugins and sensors Gazebo would load.

Read without ROS, Gazebo or pybullet. Each dataclass of ``robot_plugin_types`` holds one
gazebo_ros plugin's settings with Gazebo's defaults for what the block leaves out
(gazebo_plugins' ``getParameter`` defaults), so the simulation can make what that plugin would
make. Topic names are as written (relative ones resolve in the robot's namespace); frames are
link names, unprefixed. Units: m, s, rad, Hz, N*m, m/s^2.

``read_plugins`` reads them (urdf_file calls it for every URDF), each by its module of
``table``: in a ``<gazebo>`` block the model plugins that run on robots, a drive
(libgazebo_ros_diff_drive, skid steer, planar move, tricycle, force-based move: one drive a
robot), libgazebo_ros_imu (one a robot) and the others (p3d, joint_state_publisher, hector's
imu and gps: ``RobotPlugins.model_plugins``);
in a ``<gazebo reference="LINK">`` block the sensors
whose plugin runs on robots (every sensor plugin of ``table``), read as world models' sensors
are (``table.read_sensor``): a ray or gpu_ray sensor with libgazebo_ros_laser or gpu_laser and
a camera sensor with libgazebo_ros_camera or a depth sensor with libgazebo_ros_openni_kinect
(``RobotPlugins.lasers``, ``cameras``: SimRobot makes them), and the others
(``RobotPlugins.sensors``: range, block laser, bumper, depth, multi- and triggered camera, imu
sensor, run as a world model's by world_sensors). Everything else is accepted as it is (surface
and material settings, an imu, ray, camera or depth sensor without plugin, which publishes
nothing on ROS in Gazebo either) or named in one warning (an unknown plugin or sensor, a
sensor of another type without plugin, a second drive or IMU plugin, a plugin on the wrong
kind of sensor, a parameter the plugin does not have). Every sensor runs, each on its own
topics. Wrong values raise a one-line
UrdfError: every number is held to its limit in ``limits`` (rates, ranges, samples, image
sizes, noise, wheels, torque, poses), every name and topic to ``limits.MAX_NAME`` characters,
topics to ROS's characters.
"""
from typing import Collection, List, Mapping, Optional

from ....errors import UrdfError
from .. import limits
from .robot_plugin_types import (
    CAMERA, DIFF_DRIVE, GPU_LASER, IMU, LASER, OPENNI_KINECT, CameraSensor, Drive, ImuPlugin,
    LaserSensor, RobotPlugins)
from .sensor_reader import SensorReader, plugin_file, strip_slash
from .table import (model_plugin, plugins_of, read_model_plugin, read_sensor, runs_on,
                    sensor_type)

__all__ = ["read_plugins", "plugin_file"]

# --- reading the <gazebo> blocks --------------------------------------------------------------

WHEEL_JOINT_TYPES = ("continuous", "revolute")
NOT_SIMULATED = "the robot runs without it"
# a robot's sensor without a plugin is one warning, but of the types SimRobot makes (a laser's,
# a camera's) and an imu (the TurtleBot3's, which talks only on Gazebo's transport)
QUIET_TYPES = frozenset({sensor_type(f) for f in (LASER, GPU_LASER, CAMERA, OPENNI_KINECT)}
                        | {"imu"})


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
        self.sensors: List[object] = []          # the others (world_sensors'), in file order
        self.model_plugins: List[object] = []      # the other model plugins, in file order
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
                            lasers=tuple(self.lasers), cameras=tuple(self.cameras),
                            sensors=tuple(self.sensors))

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
        """A <plugin> of a <gazebo> block: a model plugin of ``table`` that runs on robots is
        read by its module (a drive, the IMU: the robot's first of each; the others all)."""
        _, filename = self.plugin_id(elem)
        module = model_plugin(filename, self.host)
        if module is not None:
            found = read_model_plugin(self, elem, self.robot_name, self.links,
                                      self.joint_types)
            if found is None:
                return
            if module.DRIVE:
                self._keep_first("drive", found, elem, "differential drive"
                                 if filename == DIFF_DRIVE else "drive")
            elif filename == IMU:
                self._keep_first("imu", found, elem, "IMU plugin")
            else:
                self.model_plugins.append(found)
        elif runs_on(filename, self.host):
            self.warn("%s is a sensor plugin outside any <sensor>: Gazebo loads it only inside "
                      "a <sensor> in a <gazebo reference=...> block; %s"
                      % (self.describe(elem), NOT_SIMULATED))
        else:
            self.warn("%s is not simulated here; %s" % (self.describe(elem), NOT_SIMULATED))

    def _sensor(self, elem, link) -> None:
        """The plugins of a sensor on ``link`` (table.read_sensor: one plugin of a kind a
        sensor), each added to the robot's lasers, cameras (gazebo_ros_camera's and
        openni_kinect's robot cameras) or other sensors: every one runs, as in Gazebo."""
        kind = elem.get("type", "")
        alone = elem.find("plugin") is None and kind not in QUIET_TYPES
        if alone and plugins_of(kind, self.host):
            self.warn("%s on link %r is not simulated here; %s (without a gazebo_ros plugin "
                      "it publishes nothing on ROS)" % (self.sensor_id(elem), link,
                                                        NOT_SIMULATED))
        for sensor in read_sensor(self, elem, link):
            if isinstance(sensor, LaserSensor):
                self.lasers.append(sensor)
            elif type(sensor) is CameraSensor:     # not a WorldCamera
                self.cameras.append(sensor)
            else:
                self.sensors.append(sensor)

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

    wheel_joint = _wheel_joint   # the drive modules' check of a wheel joint
    link = _link                 # gazebo_ros_imu's check of a link

    def _keep_first(self, slot: str, plugin, elem, what: str) -> None:
        """Keep ``plugin`` as the robot's ``slot`` (drive, imu) unless one is there already:
        only one of each is simulated, a second one is warned about."""
        first = getattr(self, slot)
        if first is None:
            setattr(self, slot, plugin)
        else:
            self.second(elem, what, first.name)
