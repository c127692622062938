"""The one table of the gazebo_ros plugins this simulator makes: the library file each is
loaded from (plugin_file's form, "libgazebo_ros_laser.so") -> its module, and the readings the
table's users share: a ``<sensor>``'s plugins (``read_sensor``: robot_plugins and
world_sensor_reading) and a model's plugins (``read_model_plugin``: robot_plugins and
world_model_plugins). No ROS, no pybullet.

The modules are found, not listed: every module of this package whose name begins with
``gazebo_ros_`` or ``hector_`` and that declares a plugin (``SENSORS`` or ``MODEL_FILES``),
imported once, in name order. Adding a plugin is one new file. A plugin module declares:

* ``SENSORS`` ({library: the sensor type it sits on}, "ray", "camera", ...) for a sensor
  plugin, read with its ``<sensor>``: Gazebo loads it on no other type. Or ``MODEL_FILES``
  (the libraries it is loaded from) for a model plugin, read from a model's ``<plugin>`` (a
  world file's or spawned SDF model's, a URDF's ``<gazebo>`` block without reference).
  Never both; no library in two modules.
* ``HOSTS``: where it runs here, "robot" (a URDF robot) and/or "world" (an SDF model).
* ``PARAMS``: the parameters it reads (or Gazebo reads and the sim has no use for); any
  other child of its ``<plugin>`` is one warning.
* ``DRIVE`` (model plugins): True for a drive; a robot runs one drive (its first; a second is
  one warning), as ``RobotPlugins.drive``. A drive's dataclass has ``command_topic``,
  ``odometry_topic``, ``odometry_frame``, ``robot_base_frame``, ``robot_namespace``,
  ``publish_odom_tf`` and ``pose_covariance`` (the odometry's pose covariance diagonal).
* ``read``: a sensor plugin's ``read(reader, sensor, plugin, link)``, a model plugin's
  ``read(reader, plugin, model, links, joints)`` (its parameters checked already): its frozen
  dataclass with the plugin's defaults, or None (one warning) for a plugin Gazebo would not
  run (gazebo_ros_imu_sensor without <frameName>, a p3d without <bodyName>, ...). ``reader``
  is a sensor_reader.SensorReader (``reader.host`` the host); ``link`` the sensor's link;
  ``model`` the model's name, ``links`` and ``joints`` the names it knows (an SDF model's
  nested ones as "inner::link").
"""
import importlib
import pkgutil
from types import ModuleType
from typing import Collection, Dict, List, Optional, Tuple

PREFIXES = ("gazebo_ros_", "hector_")     # the names of plugin modules
HOST_NAMES = ("robot", "world")


def libraries(module: ModuleType) -> Tuple[str, ...]:
    """The library files the plugin module ``module`` is loaded from."""
    sensors = getattr(module, "SENSORS", None)
    return tuple(sensors) if sensors is not None else tuple(module.MODEL_FILES)


def is_sensor_module(module: ModuleType) -> bool:
    """Whether ``module`` is a sensor plugin's (else a model plugin's)."""
    return hasattr(module, "SENSORS")


def _is_plugin(module: ModuleType) -> bool:
    """Whether ``module`` declares a plugin; a TypeError of one line for a declaration that
    lacks one of the table's attributes."""
    kinds = [name for name in ("SENSORS", "MODEL_FILES") if hasattr(module, name)]
    if not kinds:
        return False
    if len(kinds) > 1:
        raise TypeError("plugin module %s declares both SENSORS and MODEL_FILES (a plugin "
                        "sits on a sensor or on a model)" % module.__name__)
    needed = ("HOSTS", "PARAMS", "read") + (("DRIVE",) if kinds == ["MODEL_FILES"] else ())
    missing = [name for name in needed if not hasattr(module, name)]
    if missing:
        raise TypeError("plugin module %s declares %s but not %s"
                        % (module.__name__, kinds[0], ", ".join(missing)))
    if not set(module.HOSTS) <= set(HOST_NAMES):
        raise TypeError("plugin module %s: HOSTS %r is not within %r"
                        % (module.__name__, tuple(module.HOSTS), HOST_NAMES))
    return True


def discover(package: str) -> Tuple[ModuleType, ...]:
    """The plugin modules of ``package`` (a dotted name): each module whose name begins with
    one of ``PREFIXES`` and that declares a plugin, imported, in name order."""
    root = importlib.import_module(package)
    names = sorted(info.name for info in pkgutil.iter_modules(root.__path__)
                   if info.name.startswith(PREFIXES))
    modules = (importlib.import_module("%s.%s" % (package, name)) for name in names)
    return tuple(module for module in modules if _is_plugin(module))


def by_library(modules: Collection[ModuleType]) -> Dict[str, ModuleType]:
    """{library: its module} of ``modules``; a ValueError for a library two modules claim."""
    table: Dict[str, ModuleType] = {}
    for module in modules:
        for filename in libraries(module):
            if filename in table:
                raise ValueError("%s is claimed by both %s and %s"
                                 % (filename, table[filename].__name__, module.__name__))
            table[filename] = module
    return table


MODULES = discover(__package__)
PLUGINS = by_library(MODULES)


# --- sensor plugins --------------------------------------------------------------------------

def sensor_type(filename: str) -> Optional[str]:
    """The sensor type the plugin library ``filename`` sits on; None for another library (a
    model plugin's, one not simulated)."""
    module = PLUGINS.get(filename)
    return module.SENSORS[filename] if module is not None and is_sensor_module(module) else None


def runs_on(filename: str, host: str) -> bool:
    """Whether the sensor plugin library ``filename`` runs on ``host`` ("robot", "world")."""
    return sensor_type(filename) is not None and host in PLUGINS[filename].HOSTS


def plugins_of(kind: str, host: str) -> Tuple[str, ...]:
    """The plugin libraries that run on a sensor of type ``kind`` on ``host``."""
    return tuple(f for f, m in PLUGINS.items() if sensor_type(f) == kind and host in m.HOSTS)


def read_sensor(reader, elem, link: str) -> List[object]:
    """The data of each plugin on the <sensor> ``elem`` of ``link`` that runs on the reader's
    host (a SensorReader), in file order; a warning for each plugin that does not run
    (reader.skip_plugin), and for a sensor that no plugin here makes (reader.not_run). A sensor
    without a gazebo_ros plugin gives nothing and no warning: Gazebo publishes nothing of it on
    ROS either. On a robot (``reader.one_per_sensor``) a second plugin of a kind is warned."""
    kind = reader.attr(elem, "type")
    reader.attr(elem, "name")
    plugins = elem.findall("plugin")
    wanted = plugins_of(kind, reader.host)
    if not wanted:
        reader.not_run(elem, link, plugins)
        return []
    kept = []
    first: Dict[str, object] = {}
    for plugin in plugins:
        _, filename = reader.plugin_id(plugin)
        if filename in wanted and filename in first and reader.one_per_sensor:
            reader.second(plugin, "%s on %s" % (filename, reader.sensor_id(elem)),
                          first[filename].get("name", ""))
        elif filename in wanted:
            first.setdefault(filename, plugin)
            kept.append((filename, plugin))
        elif runs_on(filename, reader.host):
            reader.skip_plugin(plugin, elem, '%s on %s is of the wrong kind (it needs a <sensor '
                               'type="%s">); %s' % (reader.describe(plugin),
                                                    reader.sensor_id(elem),
                                                    sensor_type(filename), reader.without))
        else:
            reader.skip_plugin(plugin, elem, "%s is not simulated here; %s"
                               % (reader.describe(plugin), reader.without))
    read = (PLUGINS[filename].read(reader, elem, plugin, link) for filename, plugin in kept)
    return [data for data in read if data is not None]


# --- model plugins ---------------------------------------------------------------------------

def model_plugin(filename: str, host: str) -> Optional[ModuleType]:
    """The module of the model plugin library ``filename`` if it runs on ``host``, else None."""
    module = PLUGINS.get(filename)
    if module is None or is_sensor_module(module) or host not in module.HOSTS:
        return None
    return module


def is_model_plugin(filename: str, host: str) -> bool:
    """Whether the library ``filename`` is a model plugin that runs on ``host``."""
    return model_plugin(filename, host) is not None


def read_model_plugin(reader, plugin, model: str, links: Collection[str],
                      joints: Collection[str]) -> Optional[object]:
    """The data of the model plugin ``plugin`` (a <plugin> element, of a library that
    ``is_model_plugin`` on the reader's host, of a model of name ``model``), its parameters
    checked; None (one warning) where Gazebo would not run it."""
    _, filename = reader.plugin_id(plugin)
    module = PLUGINS[filename]
    reader.check_params(plugin, filename, module.PARAMS)
    return module.read(reader, plugin, model, links, joints)
