"""``libgazebo_ros_camera.so`` on a ``<sensor type="camera">``: a sensor_msgs/Image and its
CameraInfo a tick. Read into robot_plugin_types.CameraSensor with the <camera>'s SDF
defaults (320 x 240 px, 1.047 rad, clip 0.1..100 m) and gazebo_ros_camera_utils' (cameraName
empty, topics image_raw and camera_info, frame empty: a robot's is its link); the rate is the
plugin's updateRate, else the sensor's update_rate. ``read_camera`` is the reading that
gazebo_ros_openni_kinect shares. Runs on robots and on world models, where
``read_world_camera`` (shared by the depth, multi- and triggered cameras) reads into a
camera_types.WorldCamera; both read the image <format> (camera_types.IMAGE_FORMATS), the lens
<distortion> and CameraInfo's D the same way (``_image``). Units: m, rad, Hz, px.
"""
from typing import Callable, Dict, Optional

from .. import limits
from ...kinematics import ZERO_XYZ_RPY
from .camera_types import IMAGE_FORMATS, LensDistortion, WorldCamera
from .robot_plugin_types import CAMERA, CameraSensor, CameraSpec
from .sensor_reader import BASELINE, FIELD_OF_VIEW, REACH, Bounds

SENSORS = {CAMERA: "camera"}
HOSTS = ("robot", "world")
PARAMS = frozenset({
    "robotNamespace", "alwaysOn", "updateRate", "cameraName", "frameName", "imageTopicName",
    "cameraInfoTopicName", "hackBaseline", "distortionK1", "distortionK2", "distortionK3",
    "distortionT1", "distortionT2", "CxPrime", "Cx", "Cy", "focalLength", "borderCrop",
    "autoDistortion"})
# what gazebo_ros_camera_utils reads besides (a world camera's: honoured there)
WORLD_PARAMS = PARAMS | {"triggerTopicName"}
INFO_DISTORTION = ("distortionK1", "distortionK2", "distortionT1", "distortionT2",
                   "distortionK3")    # CameraInfo's D, in its order
LENS_TERM = Bounds(-limits.MAX_SCALE, limits.MAX_SCALE)


def read(reader, sensor, plugin, link: str) -> CameraSensor:
    """The camera of ``sensor`` on ``link`` with its ``plugin`` (a SensorReader's elements)."""
    if reader.host == "world":
        return read_world_camera(reader, sensor, plugin, link, WORLD_PARAMS)
    return read_camera(reader, sensor, plugin, link, PARAMS)


def _spec(reader, sensor, camera, plugin, depth: bool, baseline: Optional[float] = None):
    """(CameraSpec, <format>) of the <camera> ``camera`` of ``sensor``."""
    image = camera.find("image") if camera is not None else None
    clip = camera.find("clip") if camera is not None else None
    hfov = reader.bounded(camera, "horizontal_fov", 1.047, sensor, FIELD_OF_VIEW)
    width = reader.count(image, "width", 320, sensor, limits.MAX_IMAGE_SIDE, "px")
    height = reader.count(image, "height", 240, sensor, limits.MAX_IMAGE_SIDE, "px")
    image_format = reader.text(image, "format", "R8G8B8")
    near = reader.bounded(clip, "near", 0.1, sensor, REACH)
    far = reader.bounded(clip, "far", 100.0, sensor, REACH)
    if near >= far:
        reader.fail(reader.found(clip, "far", sensor),
                    "far %g must be greater than near %g" % (far, near), sensor)
    plugin_rate = reader.rate(plugin, "updateRate", 0.0, plugin)
    sensor_rate = reader.rate(sensor, "update_rate", 0.0, sensor)
    if baseline is None:   # the first <hackBaseline> counts, as sdformat's GetElement finds it
        baseline = reader.bounded(plugin, "hackBaseline", 0.0, plugin, BASELINE)
    spec = CameraSpec(width=width, height=height, hfov=hfov,
                      rate=plugin_rate if plugin_rate > 0 else sensor_rate,
                      near=near, far=far, depth=depth, baseline=baseline)
    return spec, image_format


def _names(reader, sensor, plugin, link: str, filename: str, suffix: str = ""):
    """The CameraSensor fields of the plugin's names."""
    camera_name = reader.topic(plugin, "cameraName", "")
    return dict(
        name=sensor.get("name"), link=link, plugin_file=filename,
        camera_name=camera_name + suffix, frame=reader.frame(plugin, link, ""),
        image_topic=reader.topic(plugin, "imageTopicName", "image_raw"),
        info_topic=reader.topic(plugin, "cameraInfoTopicName", "camera_info"),
        robot_namespace=reader.topic(plugin, "robotNamespace", ""),
        pose=reader.sensor_pose(sensor))


def read_camera(reader, sensor, plugin, link: str, params, depth: bool = False,
                extra: Optional[Callable[..., Dict[str, object]]] = None) -> CameraSensor:
    """A robot's camera whose plugin reads ``params`` (``depth``: with depth images),
    ``extra(reader, plugin)`` giving the depth plugin's own CameraSensor fields."""
    filename = reader.plugin_id(plugin)[1]
    reader.check_params(plugin, filename, params)
    camera = sensor.find("camera")
    spec, image_format = _spec(reader, sensor, camera, plugin, depth)
    image = _image(reader, sensor, camera, plugin, image_format)
    fields = extra(reader, plugin) if extra is not None else {}   # over the camera's own
    return CameraSensor(spec=spec, **{**_names(reader, sensor, plugin, link, filename), **image,
                                      **fields})


def read_world_camera(reader, sensor, plugin, link: str, params, depth: bool = False,
                      extra: Optional[Callable[..., Dict[str, object]]] = None,
                      camera=None, suffix: str = "",
                      baseline: Optional[float] = None) -> WorldCamera:
    """A world model's camera: the <camera> ``camera`` (else the sensor's first) of ``sensor``
    with its ``plugin`` reading ``params``; ``suffix`` added to its cameraName, ``baseline``
    instead of the plugin's hackBaseline (gazebo_ros_multicamera's left and right)."""
    filename = reader.plugin_id(plugin)[1]
    if camera is None:
        reader.check_params(plugin, filename, params)
        camera = sensor.find("camera")
    spec, image_format = _spec(reader, sensor, camera, plugin, depth, baseline)
    image = _image(reader, sensor, camera, plugin, image_format)
    fields = dict(_names(reader, sensor, plugin, link, filename, suffix), **image)
    fields.update(extra(reader, plugin) if extra is not None else {})    # the plugin's own
    return WorldCamera(spec=spec, lens_pose=_lens_pose(reader, sensor, camera), **fields)


def _image(reader, sensor, camera, plugin, image_format: str) -> Dict[str, object]:
    """The CameraSensor fields of the <camera>'s <format> and <distortion> and of CameraInfo's
    D (the plugin's distortionK1.., or the lens' with autoDistortion), a robot's as a world
    model's."""
    if image_format not in IMAGE_FORMATS:
        reader.warn("%s: image format %r is not one Gazebo renders for gazebo_ros: the images "
                    "are R8G8B8 data labelled bgr8, as gazebo_ros_camera_utils publishes them"
                    % (reader.sensor_id(sensor), image_format), camera)
    lens = _lens(reader, sensor, camera, plugin)
    info = tuple(reader.bounded(plugin, key, 0.0, plugin, LENS_TERM) for key in INFO_DISTORTION)
    if lens is not None and reader.flag(plugin, "autoDistortion", False, plugin):
        info = (lens.k1, lens.k2, lens.p1, lens.p2, lens.k3)
    return dict(image_format=image_format, lens=lens, info_distortion=info)


def _lens(reader, sensor, camera, plugin) -> Optional[LensDistortion]:
    """The <camera>'s <distortion> (SDF's defaults: 0, center 0.5 0.5); None without one."""
    elem = camera.find("distortion") if camera is not None else None
    if elem is None:
        return None
    terms = {key: reader.bounded(elem, key, 0.0, sensor, LENS_TERM)
             for key in ("k1", "k2", "k3", "p1", "p2")}
    found = elem.find("center")
    center = reader.floats(found, 2, sensor) if found is not None else (0.5, 0.5)
    return LensDistortion(center=tuple(center),
                          crop=reader.flag(plugin, "borderCrop", True, plugin), **terms)


def _lens_pose(reader, sensor, camera):
    """The <camera>'s own <pose> in its sensor (a multicamera's)."""
    if camera is None or camera.find("pose") is None:
        return ZERO_XYZ_RPY
    pose = tuple(reader.xyz_rpy(camera, "pose", None, sensor))
    problem = (limits.position_problem("pose", pose[:3])
               or limits.angles_problem("pose", pose[3:]))
    if problem:
        reader.fail(camera.find("pose"), problem, sensor)
    return pose
