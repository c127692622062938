"""A world model's <sensor>s with gazebo_ros plugins, read by world_sdf through the plugin table
(world_sensor_reading, table, the gazebo_ros_* modules): the fixture world of
test/fixtures/world_sensors, each plugin's defaults as gazebo_plugins writes them, spawned and
included models, what warns (one line per kind) and what is refused. No ROS, no pybullet.
Units: m, rad, Hz."""
from dataclasses import replace
from pathlib import Path

import pytest

from tutorial_turtlebot.errors import WorldError
from tutorial_turtlebot.sim.files.plugins import table
from tutorial_turtlebot.sim.files.plugins.camera_types import (
    DEPTH_CAMERA, MULTICAMERA, TRIGGERED_CAMERA, WorldCamera)
from tutorial_turtlebot.sim.files.plugins.robot_plugin_types import (
    CAMERA, GPU_LASER, LASER, OPENNI_KINECT, CameraSpec, LaserConfig, LaserSensor)
from tutorial_turtlebot.sim.files.plugins.sensor_types import (
    BLOCK_LASER, RANGE, BlockLaserSensor, RangeSensor, RayScan)
from tutorial_turtlebot.sim.files.sdf.sdf_elements import MAX_WARNING_CHARS
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_model_xml, load_world

from unit_helpers import world_file
import unit_paths

FIXTURE = Path(unit_paths.ROOT) / "test" / "fixtures" / "world_sensors" / "world_sensors.world"
RAY = ('<ray><scan><horizontal><samples>3</samples><min_angle>-0.1</min_angle>'
       '<max_angle>0.1</max_angle></horizontal></scan><range><min>0.1</min><max>2</max>'
       '</range></ray>')


def model(sensors, name="m", static="true"):
    return ('<model name="%s"><static>%s</static><link name="l">%s</link></model>'
            % (name, static, sensors))


def sensor(plugin_file, kind="ray", body=RAY, params="", name="s"):
    return ('<sensor name="%s" type="%s">%s<plugin name="p" filename="%s">%s</plugin></sensor>'
            % (name, kind, body, plugin_file, params))


def test_the_fixture_worlds_sensors_are_read_with_their_links_and_poses():
    world = load_world(str(FIXTURE))
    by_name = {s.name: s for s in world.sensors}
    assert list(by_name) == ["overhead_camera", "sonar", "sonar_free", "profiler", "lidar"]
    assert by_name["overhead_camera"] == WorldCamera(
        name="overhead_camera", link="overhead::link",
        spec=CameraSpec(160, 120, 1.047, 5.0, near=0.1, far=20.0),   # updateRate 5 < 10
        plugin_file=CAMERA, camera_name="overhead", frame="overhead_optical_frame",
        pose=(0.0, 0.0, 0.0, 0.0, 1.5707963, 0.0))
    assert by_name["sonar"] == RangeSensor(
        name="sonar", link="sonar_post::link",
        rays=RayScan(5, 1.0, -0.1, 0.1, 5, 1.0, -0.1, 0.1, 0.02, 2.0),
        topic="sonar", frame="sonar_link", radiation="infrared", fov=0.2, gaussian_noise=0.005,
        rate=10.0, plugin="sonar_controller")     # the smaller of 20 (sensor) and 10 (plugin)
    assert by_name["profiler"] == BlockLaserSensor(
        name="profiler", link="block_laser::link",
        rays=RayScan(20, 1.0, -0.3, 0.3, 10, 1.0, -0.4, 0.4, 0.4, 1.0),
        topic="profiler_cloud", frame="profiler_frame", rate=5.0, plugin="profiler_controller",
        robot_namespace="/")
    lidar = by_name["lidar"]
    assert (lidar.link, lidar.topic, lidar.frame, lidar.pose) == (
        "rover::chassis", "rover/scan", "rover_lidar", (0.0, 0.0, 0.15, 0.0, 0.0, 0.0))
    assert lidar.laser == LaserConfig("gazebo", 0.0, 4.712389, 4.712389 / 3, samples=4,
                                      range_min=0.1, range_max=5.0, noise_sigma=0.0, rate=5.0)
    # the contact sensor and the camera without a plugin publish nothing on ROS: silent
    assert world.warnings == ()


@pytest.mark.parametrize("plugin_file, expected", [
    (RANGE, RangeSensor(name="s", link="m::l", rays=RayScan(
        3, 1.0, -0.1, 0.1, range_min=0.1, range_max=2.0))),
    (BLOCK_LASER, BlockLaserSensor(name="s", link="m::l", rays=RayScan(
        3, 1.0, -0.1, 0.1, range_min=0.1, range_max=2.0))),
])
def test_gazebo_ros_defaults_fill_what_a_ray_plugin_leaves_out(tmp_path, plugin_file, expected):
    world = load_world(world_file(tmp_path, model(sensor(plugin_file))))
    assert world.sensors == (replace(expected, plugin="p"),)
    assert world.warnings == ()


def test_the_range_plugins_defaults_are_gazebos():
    defaults = RangeSensor("s", "m::l", RayScan())
    assert (defaults.topic, defaults.frame, defaults.radiation, defaults.fov,
            defaults.gaussian_noise, defaults.rate) == ("/range", "world", "ultrasound", 0.05,
                                                        0.0, 0.0)
    block = BlockLaserSensor("s", "m::l", RayScan())
    assert (block.topic, block.frame, block.gaussian_noise) == ("/world", "world", 0.0)


def test_a_world_lasers_and_cameras_defaults_are_gazebos_frames_not_a_robots_link(tmp_path):
    camera = '<camera><image><width>8</width><height>6</height></image></camera>'
    text = model(sensor(LASER, name="laser") + sensor(CAMERA, "camera", camera, name="cam"))
    laser, cam = load_world(world_file(tmp_path, text)).sensors
    assert isinstance(laser, LaserSensor)
    assert (laser.topic, laser.frame, laser.link) == ("/world", "world", "m::l")
    assert (cam.camera_name, cam.frame, cam.image_topic, cam.info_topic) == (
        "", "", "image_raw", "camera_info")
    assert cam.spec == CameraSpec(8, 6, 1.047, 0.0, near=0.1, far=100.0)


def test_every_ros_plugin_on_a_sensor_is_its_own_output(tmp_path):
    both = ('<sensor name="s" type="ray">%s<plugin name="a" filename="%s"/>'
            '<plugin name="b" filename="gazebo_ros_range"/></sensor>' % (RAY, BLOCK_LASER))
    found = load_world(world_file(tmp_path, model(both))).sensors
    assert [(type(s), s.plugin) for s in found] == [(BlockLaserSensor, "a"), (RangeSensor, "b")]


def test_nested_included_and_spawned_models_scope_their_links(tmp_path, monkeypatch):
    monkeypatch.setenv("GAZEBO_MODEL_PATH", str(tmp_path / "models"))
    folder = tmp_path / "models" / "sonar_box"
    folder.mkdir(parents=True)
    (folder / "model.config").write_text("<model><sdf>model.sdf</sdf></model>")
    (folder / "model.sdf").write_text('<sdf version="1.6">%s</sdf>'
                                      % model(sensor(RANGE), name="sonar_box"))
    body = ('<model name="outer"><static>true</static><model name="inner"><link name="l">%s'
            '</link></model></model><include><uri>model://sonar_box</uri><name>front</name>'
            '<pose>1 2 3 0 0 0</pose></include>' % sensor(RANGE, name="nested"))
    world = load_world(world_file(tmp_path, body))
    assert [(s.name, s.link) for s in world.sensors] == [("nested", "outer::inner::l"),
                                                         ("s", "front::l")]
    spawned = load_model_xml('<sdf version="1.6">%s</sdf>' % model(sensor(RANGE, name="x")),
                             "model_xml", "bot")
    assert [(s.name, s.link) for s in spawned.sensors] == [("x", "bot::l")]


def test_a_second_model_of_one_name_takes_its_sensors_along(tmp_path):
    text = model(sensor(RANGE, name="first")) + model(sensor(RANGE, name="second"))
    world = load_world(world_file(tmp_path, text))
    assert [s.name for s in world.sensors] == ["first"]
    assert any("a second model named m is left out" in w for w in world.warnings)


def test_what_does_not_run_is_one_warning_per_kind_counting_the_others(tmp_path):
    text = "".join(model(sensor("libgazebo_ros_imu_sensor.so", "imu", ""), name="i%d" % i)
                   for i in range(3))
    text += model(sensor("libgazebo_ros_p3d.so"), name="p1")
    text += model(sensor("libgazebo_ros_p3d.so"), name="p2")
    text += model(sensor(RANGE, "camera", "<camera/>"), name="wrong")
    world = load_world(world_file(tmp_path, text))
    assert world.sensors == ()
    assert len(world.warnings) == 3, world.warnings
    imu, p3d, wrong = world.warnings
    # gazebo_ros_imu_sensor does not load without a <frameName>
    assert ("plugin 'p' (libgazebo_ros_imu_sensor.so) is not simulated here: it has no "
            "<frameName>" in imu)
    assert imu.endswith("(and 2 more)")
    assert "<plugin> of a sensor skipped: plugin 'p' (libgazebo_ros_p3d.so)" in p3d
    assert p3d.endswith("(and 1 more)")
    assert 'of the wrong kind (it needs a <sensor type="ray">)' in wrong
    assert all(len(w) <= MAX_WARNING_CHARS and "\n" not in w for w in world.warnings)


def test_a_parameter_the_plugin_does_not_read_is_one_located_warning(tmp_path):
    path = world_file(tmp_path, model(sensor(RANGE, params="<fov>0.3</fov><raditaion>x"
                                                           "</raditaion>")))
    world = load_world(path)
    assert world.sensors[0].fov == 0.3
    [warning] = world.warnings
    assert warning.startswith(path + ":4: plugin 'p' (%s): <raditaion> is not a parameter"
                              % RANGE)


@pytest.mark.parametrize("change, words", [
    ("<samples>3</samples>", ["<samples>", "'x'"]),
    ("<max>2</max>", ["max 0.1 must be greater than min 0.1"]),
    ("<min_angle>-0.1</min_angle>", ["min_angle", "nan"]),
])
def test_a_wrong_value_is_refused_in_one_line_naming_file_and_line(tmp_path, change, words):
    bad = {"<samples>3</samples>": "<samples>x</samples>", "<max>2</max>": "<max>0.1</max>",
           "<min_angle>-0.1</min_angle>": "<min_angle>nan</min_angle>"}[change]
    path = world_file(tmp_path, model(sensor(RANGE, body=RAY.replace(change, bad))))
    with pytest.raises(WorldError) as err:
        load_world(path)
    text = str(err.value)
    assert text.startswith(path + ":4: ") and "\n" not in text
    for word in words:
        assert word in text, text


def test_a_name_beyond_the_limit_is_refused(tmp_path):
    with pytest.raises(WorldError, match="<sensor>: name"):
        load_world(world_file(tmp_path, model(sensor(RANGE, name="n" * 300))))


def test_too_many_rays_are_refused(tmp_path):
    body = RAY.replace("<samples>3</samples>", "<samples>3000</samples>").replace(
        "</horizontal>", "</horizontal><vertical><samples>3000</samples></vertical>")
    with pytest.raises(WorldError, match="3000 x 3000 rays are more than 65536"):
        load_world(world_file(tmp_path, model(sensor(BLOCK_LASER, body=body))))


def test_the_table_maps_each_plugin_file_to_its_module_and_sensor():
    sensor_plugins = [f for f in table.PLUGINS if table.sensor_type(f) is not None]
    assert {f: table.sensor_type(f) for f in sensor_plugins} == {
        LASER: "ray", GPU_LASER: "gpu_ray", CAMERA: "camera", OPENNI_KINECT: "depth",
        RANGE: "ray", BLOCK_LASER: "ray", DEPTH_CAMERA: "depth", MULTICAMERA: "multicamera",
        TRIGGERED_CAMERA: "camera", "libgazebo_ros_bumper.so": "contact",
        "libgazebo_ros_imu_sensor.so": "imu"}
    assert table.plugins_of("ray", "world") == (BLOCK_LASER, LASER, RANGE)    # name order
    # every sensor plugin runs on both hosts (a robot's others in world_sensors)
    assert table.plugins_of("ray", "robot") == (BLOCK_LASER, LASER, RANGE)
    assert table.plugins_of("depth", "world") == (DEPTH_CAMERA, OPENNI_KINECT)
    assert all(table.runs_on(f, host) for f in sensor_plugins for host in ("robot", "world"))
    for module in table.MODULES:
        assert callable(module.read) and module.PARAMS
        assert set(module.HOSTS) <= {"robot", "world"}
