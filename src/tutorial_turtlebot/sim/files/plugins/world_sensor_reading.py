"""The ``<sensor>`` elements of a world file's model links (and of a spawned SDF model's), read
as a robot's are (``table.read_sensor``, the plugin modules) into sensor_types.WorldSensor data:
the link's scoped name ("model::link", nested models adding parts), the sensor's <pose> in that
link, the plugin's settings with its defaults. No ROS, no pybullet.

What runs on a world model: a ray or gpu_ray sensor with gazebo_ros_laser (gpu_laser),
gazebo_ros_range or gazebo_ros_block_laser, a camera sensor with gazebo_ros_camera, a contact
sensor with gazebo_ros_bumper, an imu sensor with gazebo_ros_imu_sensor (each plugin on a sensor
is its own output, as Gazebo loads every one; table.PLUGINS has them all). A sensor of those
types without a gazebo_ros plugin publishes nothing on ROS in Gazebo either: nothing, no
warning. Every other sensor (altimeter, sonar, ...) and every other plugin on a sensor is one
warning line per kind and world, naming the first one's file and line and counting the others
("(and N more)"). Wrong values are refused as a robot's are: a WorldError of one line.
"""
from typing import Dict, List, Sequence, Tuple

from ....errors import WorldError
from .. import limits
from ..sdf.sdf_elements import MAX_WARNING_CHARS, one_line
from .sensor_reader import SensorReader
from .sensor_types import WorldSensor
from .table import read_sensor

SENSOR_SKIPPED = "<sensor> of a link skipped: "
PLUGIN_SKIPPED = "<plugin> of a sensor skipped: "
WITHOUT = "the world runs without it"


class WorldSensorReading:
    """The sensors read so far in one world document and the documents it includes (one object
    shared by their loaders), and the warning lines of the kinds left out."""

    def __init__(self):
        self._found: List[Tuple[List[object], int, WorldSensor]] = []
        self._kinds: Dict[tuple, List[int]] = {}     # kind -> [warning index, count]

    def read(self, loader, elem, link: str, links: List[object]) -> None:
        """Read the <sensor> ``elem`` of the link whose scoped name is ``link`` and which will
        be ``links``' next entry (a world_sdf loader's Link list of the model being read), with
        ``loader``'s file and warnings."""
        reader = _WorldSensorReader(loader.path, self, loader.warnings)
        for node in elem.iter():      # names, filenames, types: before a message names one
            for key, value in node.attrib.items():
                problem = limits.name_problem(key, value)
                if problem:
                    reader.fail_bare(node, "<%s>: %s" % (node.tag, problem))
        for sensor in read_sensor(reader, elem, link):
            self._found.append((links, len(links), sensor))

    def of(self, models: Sequence[object]) -> Tuple[WorldSensor, ...]:
        """The sensors, in file order, of the links of ``models`` (the world's Models): a model
        left out (a second of one name) takes its sensors along."""
        kept = {id(link) for model in models for link in model.links}
        return tuple(sensor for links, index, sensor in self._found
                     if index < len(links) and id(links[index]) in kept)

    def note(self, kind: tuple, warnings: List[str], path: str, line: int, message: str) -> None:
        """One warning line per ``kind`` and world; the later ones are counted in it."""
        seen = self._kinds.get(kind)
        if seen is None or seen[0] >= len(warnings):
            self._kinds[kind] = [len(warnings), 0]
            warnings.append(one_line(path, line, message))
            return
        seen[1] += 1
        first = warnings[seen[0]]
        first = first[:first.rindex(" (and ")] if first.endswith(" more)") else first
        tail = " (and %d more)" % seen[1]
        if len(first) + len(tail) > MAX_WARNING_CHARS:
            first = first[:MAX_WARNING_CHARS - len(tail) - 3] + "..."
        warnings[seen[0]] = first + tail


class _WorldSensorReader(SensorReader):
    """A SensorReader for a world model: frames as written, every plugin on a sensor kept,
    warnings located ("file:line: ...") and those of what does not run one per kind."""

    host = "world"
    one_per_sensor = False

    def __init__(self, path: str, reading: WorldSensorReading, warnings: List[str]):
        super().__init__(path, WorldError, WITHOUT)
        self.reading = reading
        self.warnings = warnings

    def warn(self, message: str, elem=None) -> None:
        line = one_line(self.source, elem.line if elem is not None else 0, message)
        if line not in self.warnings:
            self.warnings.append(line)

    def not_run(self, sensor, link: str, plugins) -> None:
        kind = sensor.get("type", "")
        self.reading.note(("type", kind), self.warnings, self.source, sensor.line,
                          SENSOR_SKIPPED + "%s: a world model's %s sensor does not run here"
                          % (self.sensor_id(sensor), kind))

    def skip_plugin(self, plugin, sensor, message: str) -> None:
        self.reading.note(("plugin", self.plugin_id(plugin)[1], sensor.get("type", "")),
                          self.warnings, self.source, plugin.line, PLUGIN_SKIPPED + message)
