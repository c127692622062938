"""What every reader of Gazebo plugins shares: a URDF's ``<gazebo>`` blocks (robot_plugins) and
a world model's ``<sensor>`` elements (world_sensor_reading). ``SensorReader`` reads typed,
bounded values out of a ``<plugin>`` or a ``<sensor>`` (each number held to its limit in
``limits``, each name to ``limits.MAX_NAME`` characters, topics to ROS's characters), the rays of
a ``<ray>``, and words its warnings; the plugin modules (gazebo_ros_laser, ...) read their
plugin with it. A wrong value raises the reader's error in xml_reader's one-line form
``<path>:<line>: <element>: <problem>``. No ROS, no pybullet. Units: m, s, rad, Hz.
"""
import math
import os
from typing import List, NamedTuple, Tuple

from ....ros_names import is_legal_name
from .. import limits
from ...kinematics import ZERO_XYZ_RPY, XyzRpy
from .robot_plugin_types import GPU_LASER, LASER
from .sensor_types import RayScan
from ..xml_reader import XmlReader

NOISE_TYPES = ("gaussian", "gaussian_quantized", "none")
MAX_RAYS = 65536          # rays of one <ray> sensor, horizontal x vertical (a 2048 x 32 lidar)


def plugin_file(filename: str) -> str:
    """The library a ``<plugin filename=...>`` names, as Gazebo completes it: the base name with
    a ``lib`` prefix and a ``.so`` suffix (``gazebo_ros_laser`` -> ``libgazebo_ros_laser.so``)."""
    name = os.path.basename(filename.strip())
    if not name.startswith("lib"):
        name = "lib" + name
    if not name.endswith(".so"):
        name += ".so"
    return name


def strip_slash(name: str) -> str:
    """gazebo_ros takes "/base_scan" and "base_scan" for the same frame (tf's resolve)."""
    return name[1:] if name.startswith("/") else name


class Bounds(NamedTuple):
    """limits.outside's arguments for one kind of number."""

    low: float
    high: float
    unit: str = ""
    low_open: bool = False
    high_open: bool = False


DISTANCE = Bounds(0.0, limits.MAX_RANGE, "m")             # a range, a resolution, a cut-off
REACH = Bounds(0.0, limits.MAX_RANGE, "m", low_open=True)  # a clip plane
ANGLE = Bounds(-limits.MAX_ANGLE, limits.MAX_ANGLE, "rad")
FIELD_OF_VIEW = Bounds(0.0, math.pi, "rad", low_open=True, high_open=True)
FACTOR = Bounds(0.0, limits.MAX_SCALE, low_open=True)
NOISE = Bounds(0.0, limits.MAX_NOISE)                      # a standard deviation
NOISE_MEAN = Bounds(-limits.MAX_NOISE, limits.MAX_NOISE)
BASELINE = Bounds(-limits.MAX_SIZE, limits.MAX_SIZE, "m")


class SensorReader(XmlReader):
    """Reads plugins and sensors for one host: ``host`` "robot" (a URDF, whose frames are its
    links) or "world" (a world model, whose frames are written as the plugin says). Warnings
    end in ``without`` (what runs without the element) and gather in ``warnings``."""

    host = "robot"
    one_per_sensor = True     # a second plugin of a kind on one sensor is warned (robots)

    def __init__(self, path: str, error, without: str):
        super().__init__(path, error)
        self.without = without
        self.warnings: List[str] = []

    # --- frames and names (a host's own) -------------------------------------------------------

    def frame(self, plugin, link: str, gazebo_default: str) -> str:
        """The plugin's <frameName>, without a leading "/"; ``gazebo_default`` without one."""
        return strip_slash(self.text(plugin, "frameName", gazebo_default))

    # --- values ----------------------------------------------------------------------------------

    def check_params(self, plugin, filename, known) -> None:
        """One warning per child of ``plugin`` that its plugin (library ``filename``) does not
        read: not one of ``known``."""
        for child in plugin:
            if child.tag not in known:
                hint = ""
                if filename in (LASER, GPU_LASER) and "rate" in child.tag.lower():
                    hint = " (a scan's rate is its sensor's <update_rate>)"
                self.warn("%s: <%s> is not a parameter of %s; ignored, as in Gazebo%s"
                          % (self.describe(plugin), child.tag, filename, hint), child)

    def found(self, parent, tag, owner):
        """``parent``'s first <tag>, else ``parent`` (else ``owner``): where an error points."""
        elem = parent.find(tag) if parent is not None else None
        return elem if elem is not None else (parent if parent is not None else owner)

    def text(self, parent, tag, default: str) -> str:
        """The text of the optional child <tag>: at most limits.MAX_NAME characters."""
        elem = parent.find(tag) if parent is not None else None
        if elem is None:
            return default
        problem = limits.name_problem(tag, elem.value)
        if problem:
            self.fail(elem, problem, parent)
        return elem.value

    def topic(self, parent, tag, default: str) -> str:
        """A topic, service or namespace name: a ROS name (letters, digits, _ and /)."""
        name = self.text(parent, tag, default)
        if not is_legal_name(name):
            self.fail(parent.find(tag), "%r is not a ROS name (a letter, / or ~ first, then "
                                        "letters, digits, _ and /)" % name, parent)
        return name

    def bounded(self, parent, tag, default: float, owner, bounds: Bounds) -> float:
        """The number of the optional child <tag> within ``bounds``: limits' one-line refusal
        otherwise."""
        value = self.number(parent, tag, default, owner)
        problem = limits.outside(tag, value, *bounds)
        if problem:
            self.fail(self.found(parent, tag, owner), problem, owner)
        return value

    def rate(self, parent, tag, default: float, owner) -> float:
        """An update rate (Hz): 0 or within limits.rate_problem's range."""
        value = self.number(parent, tag, default, owner)
        problem = limits.rate_problem(tag, value)
        if problem:
            self.fail(self.found(parent, tag, owner), problem, owner)
        return value

    def count(self, parent, tag, default: int, owner, high: int, unit: str = "") -> int:
        """The positive integer of the optional child <tag>, at most ``high``."""
        value = self.integer(parent, tag, default, owner)
        problem = limits.outside(tag, value, 1, high, unit)
        if problem:
            self.fail(self.found(parent, tag, owner), problem, owner)
        return value

    def sensor_pose(self, sensor) -> XyzRpy:
        """The sensor's <pose> in its link (x y z roll pitch yaw; m, rad)."""
        pose = tuple(self.xyz_rpy(sensor, "pose", ZERO_XYZ_RPY, sensor))
        problem = (limits.position_problem("pose", pose[:3])
                   or limits.angles_problem("pose", pose[3:]))
        if problem:
            self.fail(sensor.find("pose"), problem, sensor)
        return pose

    def ray_noise(self, noise, sensor) -> float:
        """The gaussian sigma (m) of a <ray><noise>; 0 without one."""
        if noise is None:
            return 0.0
        kind = self.text(noise, "type", "gaussian")
        if kind not in NOISE_TYPES:
            self.fail(noise.find("type"), "must be one of %s, got %r"
                      % (", ".join(NOISE_TYPES), kind), sensor)
        mean = self.bounded(noise, "mean", 0.0, sensor, NOISE_MEAN)
        sigma = self.bounded(noise, "stddev", 0.0, sensor, NOISE)
        if kind == "none":
            return 0.0
        if mean != 0.0:
            self.warn("%s: noise <mean> %g is not simulated (the noise here has mean 0)"
                      % (self.sensor_id(sensor), mean), noise)
        return sigma

    def ray_scan(self, sensor, one_plane: bool = False) -> RayScan:
        """The rays of ``sensor``'s <ray> (SDF's defaults: 640 samples, one vertical sample,
        angles 0). ``one_plane`` (a LaserScan): max_angle must exceed min_angle, and more than
        one vertical sample is one warning (only the horizontal plane is scanned)."""
        ray = self.child(sensor, "ray")
        scan = ray.find("scan")
        horizontal = scan.find("horizontal") if scan is not None else None
        samples = self.count(horizontal, "samples", 640, sensor, limits.MAX_LASER_SAMPLES)
        resolution = self.bounded(horizontal, "resolution", 1.0, sensor, FACTOR)
        angle_min = self.bounded(horizontal, "min_angle", 0.0, sensor, ANGLE)
        angle_max = self.bounded(horizontal, "max_angle", 0.0, sensor, ANGLE)
        if one_plane and angle_min >= angle_max:
            self.fail(self.found(horizontal, "max_angle", sensor),
                      "max_angle %g must be greater than min_angle %g" % (angle_max, angle_min),
                      sensor)
        vertical = scan.find("vertical") if scan is not None else None
        if one_plane:
            if vertical is not None and self.integer(vertical, "samples", 1, sensor) > 1:
                self.warn("%s: a scan of several vertical planes is not simulated; only the "
                          "horizontal plane is" % self.sensor_id(sensor), vertical)
            column: Tuple = (1, 1.0, 0.0, 0.0)
        else:
            column = (self.count(vertical, "samples", 1, sensor, limits.MAX_LASER_SAMPLES),
                      self.bounded(vertical, "resolution", 1.0, sensor, FACTOR),
                      self.bounded(vertical, "min_angle", 0.0, sensor, ANGLE),
                      self.bounded(vertical, "max_angle", 0.0, sensor, ANGLE))
            if samples * column[0] > MAX_RAYS:
                self.fail(scan, "%d x %d rays are more than %d" % (samples, column[0], MAX_RAYS),
                          sensor)
        ranges = self.child(ray, "range", sensor)
        range_min = self.bounded(ranges, "min", 0.0, sensor, DISTANCE)
        if ranges.find("max") is None:
            self.fail(ranges, "missing <max>", sensor)
        range_max = self.bounded(ranges, "max", 0.0, sensor, DISTANCE)
        if range_min >= range_max:
            self.fail(ranges.find("max"), "max %g must be greater than min %g"
                      % (range_max, range_min), sensor)
        return RayScan(samples, resolution, angle_min, angle_max, *column, range_min=range_min,
                       range_max=range_max)

    # --- messages --------------------------------------------------------------------------------

    def plugin_id(self, elem) -> Tuple[str, str]:
        """(name, library) of a <plugin>; the filename is required, the name may be empty."""
        return elem.get("name", "").strip(), plugin_file(self.attr(elem, "filename"))

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

    def sensor_id(self, elem) -> str:
        return "sensor %r (type %s)" % (elem.get("name", ""), elem.get("type", "?"))

    def second(self, elem, what, first) -> None:
        self.warn("%s: a second %s is not simulated here (only one per robot: %r is); %s"
                  % (self.describe(elem), what, first, self.without), elem)

    def warn(self, message: str, elem=None) -> None:
        """One warning line about ``elem`` (robots: the message alone)."""
        self.warnings.append(message)

    def skip_plugin(self, plugin, sensor, message: str) -> None:
        """A plugin on ``sensor`` that does not run here: one warning."""
        self.warn(message, plugin)

    def not_run(self, sensor, link: str, plugins) -> None:
        """A sensor of a type no plugin of this host makes: one warning (a robot's imu sensor
        alone talks only on Gazebo transport: nothing to make, and no warning)."""
        kind = sensor.get("type", "")
        if kind != "imu":
            self.warn("%s on link %r is not simulated here; %s"
                      % (self.sensor_id(sensor), link, self.without), sensor)
        for plugin in plugins if kind == "imu" else ():
            self.warn("%s is not simulated here; %s" % (self.describe(plugin), self.without),
                      plugin)
