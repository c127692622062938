"""A URDF robot's sensors that SimRobot does not make itself, run as a world model's are
(sim/world/robot_sensors, world_sensors): the robot of test/fixtures/robot_sensors/probe.urdf,
spawned as spawn_model spawns it into namespace probe in robot_sensors.world, whose wall's face
is 0.5 m ahead of the robot's origin. Its range sensor sits on sonar_link, fixed 0.20 m behind
the chassis' centre (Gazebo lumps it into the chassis), looking ahead through the chassis: it
reads the wall at 0.70 m, its rays passing the robot itself, as its lasers' do; its bumper on
the chassis feels the floor its rear edge rests on, and the wall once driven into it. No ROS
master. Units: m, s, N."""
from pathlib import Path

import numpy as np
import pytest

from tutorial_turtlebot.sim.files.plugins.gazebo_ros_bumper import BumperSensor
from tutorial_turtlebot.sim.files.plugins.gazebo_ros_imu_sensor import ImuSensorPlugin
from tutorial_turtlebot.sim.files.plugins.sensor_types import RangeSensor
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, read_urdf_text
from tutorial_turtlebot.sim.world.robot_sensors import robot_sensor_specs
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl
from tutorial_turtlebot.sim.world.world_sensors import DepthCameraRunner, runner_for

from unit_helpers import at, run, world_file
import unit_paths

FIXTURE = Path(unit_paths.FIXTURES) / "robot_sensors"
URDF = FIXTURE / "probe.urdf"
WALL_AHEAD = 0.5        # m, the wall's face ahead of the robot's origin
SENSOR_AHEAD = -0.2     # m, the range sensor ahead of the robot's origin (behind it)
WEIGHT = 2.4 * 9.8      # N, the robot's


@pytest.fixture(scope="module")
def probe():
    sim = Simulation(SimConfig(world=str(FIXTURE / "robot_sensors.world"), spawn_robot=False))
    warnings = WorldControl(sim).spawn("probe", URDF.read_text(), at(0.0, 0.0, 0.035),
                                       kind="urdf", robot_namespace="probe")
    run(sim, 0.5)
    yield sim, sim.robots["probe"], warnings
    sim.close()


def sensor(sim, kind):
    return next(s for s in sim.world_sensors.sensors if s.kind == kind)


def test_the_robots_range_and_bumper_are_read_and_run_without_a_warning(probe):
    sim, robot, warnings = probe
    plugins = robot.description.plugins
    assert robot.warnings == [] and warnings == [] and sim.world_sensors.warnings == []
    assert (plugins.lasers, plugins.cameras) == ((), ())
    assert [(type(s), s.name, s.link) for s in plugins.sensors] == [
        (RangeSensor, "sonar", "sonar_link"), (BumperSensor, "bumper", "chassis")]
    assert [(s.kind, s.model.name) for s in sim.world_sensors.sensors] == [
        ("range", "probe"), ("bumper", "probe")]


def test_a_lumped_links_sensor_sits_on_the_link_gazebo_lumps_it_into(probe):
    """sonar_link is fixed to the chassis: its sensor is the chassis' at sonar_link's pose;
    topics in the spawn's namespace, frames the robot's links."""
    sim, robot, _ = probe
    sonar, bumper = (s.spec for s in sim.world_sensors.sensors)
    assert (sonar.link, sonar.pose, sonar.frame) == (
        "probe::chassis", (SENSOR_AHEAD, 0.0, 0.02, 0.0, 0.0, 0.0), "sonar_link")
    assert (sonar.topic, sonar.robot_namespace, sonar.fov) == ("front/range", "/probe/", 0.1)
    assert (bumper.link, bumper.collisions, bumper.topic, bumper.frame) == (
        "probe::chassis", ("probe::chassis::chassis_collision",), "bumper", "chassis")
    assert all(s.namespace == "/probe/" for s in sim.world_sensors.sensors)


def test_the_range_reads_the_wall_ahead_through_the_robots_own_chassis(probe):
    """Its rays skip the robot, as SimRobot's lasers' (RobotBody.ray_mask); a world model's
    mask would meet the chassis' rear face 0.05 m ahead."""
    sim, robot, _ = probe
    sonar = sensor(sim, "range")
    assert sonar.ray_mask == robot.body.ray_mask
    assert sonar.reading() == pytest.approx(WALL_AHEAD - SENSOR_AHEAD, abs=0.02)


def test_the_bumper_feels_the_floor_under_the_chassis(probe):
    sim, _, _ = probe
    [state] = sensor(sim, "bumper").contacts()
    assert (state.collision1, state.collision2) == ("probe::chassis::chassis_collision",
                                                    "ground::link::collision")
    force = np.sum([f for f, _ in state.wrenches], axis=0)
    assert 0.1 * WEIGHT < force[2] < 1.01 * WEIGHT       # up, in the chassis' frame
    np.testing.assert_allclose(state.normals[0], (0.0, 0.0, 1.0), atol=1e-3)


def test_driven_into_the_wall_the_bumper_feels_it_and_the_range_follows(probe):
    """Last: it moves the robot."""
    sim, robot, _ = probe
    range_sensor, bumper = sensor(sim, "range"), sensor(sim, "bumper")
    robot.command(0.2, 0.0)
    run(sim, 0.8)
    x = sim.models.get("probe").pose()[0][0]
    assert 0.05 < x < 0.3
    assert range_sensor.reading() == pytest.approx(WALL_AHEAD - SENSOR_AHEAD - x, abs=0.02)
    run(sim, 2.0)
    x = sim.models.get("probe").pose()[0][0]
    assert x > 0.3                     # the chassis' front (0.15 m ahead) at the wall
    touching = {state.collision2 for state in bumper.contacts()}
    assert "wall::link::collision" in touching, touching


def test_a_deleted_robot_takes_its_sensors_along():
    sim = Simulation(SimConfig(world=str(FIXTURE / "robot_sensors.world"), spawn_robot=False))
    try:
        world = WorldControl(sim)
        world.spawn("probe", URDF.read_text(), at(0.0, 0.0, 0.035), kind="urdf")
        run(sim, 0.1)
        assert [s.spec.robot_namespace for s in sim.world_sensors.sensors] == ["", ""]
        world.delete("probe")
        run(sim, 0.1)
        assert sim.world_sensors.sensors == []
    finally:
        sim.close()


def test_a_turtlebot3_has_no_such_sensor_and_the_world_none_of_its():
    """The TurtleBot3's laser, IMU and camera are SimRobot's own: nothing runs for it here."""
    sim = Simulation(SimConfig(world="empty", model="waffle"))
    try:
        run(sim, 0.1)
        assert sim.robot.description.plugins.sensors == ()
        assert sim.world_sensors.sensors == []
    finally:
        sim.close()


IMU_SENSOR = """  <gazebo reference="sonar_link">
    <sensor type="imu" name="tilt">
      <plugin name="tilt_controller" filename="libgazebo_ros_imu_sensor.so">
        <frameName>sonar_link</frameName>%s
      </plugin>
    </sensor>
  </gazebo>
</robot>"""


@pytest.mark.parametrize("own, namespace, expected", [
    ("", "/tb3_0/", "/tb3_0/"),                       # the spawn's, written into the plugin
    ("", "", "/probe"),                               # gazebo_ros_imu_sensor's "/<model>"
    ("<robotNamespace>rig</robotNamespace>", "/tb3_0/", "rig"),   # its own stays
])
def test_an_imu_sensors_namespace_is_as_gazebo_ros_spawns_it(own, namespace, expected):
    text = URDF.read_text().replace("</robot>", IMU_SENSOR % own)
    description = read_urdf_text(text, "probe.urdf")
    assert description.plugins.warnings == ()
    *_, imu = robot_sensor_specs("probe", namespace, description)
    assert isinstance(imu, ImuSensorPlugin)
    assert (imu.link, imu.frame, imu.robot_namespace) == ("probe::chassis", "sonar_link",
                                                          expected)


DEPTH_CAMERA = """  <gazebo reference="sonar_link">
    <sensor type="depth" name="eye">
      <camera><image><width>8</width><height>6</height></image></camera>
      <plugin name="eye_controller" filename="libgazebo_ros_depth_camera.so">
        <cameraName>eye</cameraName>
      </plugin>
    </sensor>
  </gazebo>
</robot>"""


def test_a_robots_depth_camera_runs_here_unless_the_launch_leaves_cameras_out():
    description = read_urdf_text(URDF.read_text().replace("</robot>", DEPTH_CAMERA),
                                 "probe.urdf")
    assert description.plugins.warnings == () and description.plugins.cameras == ()
    *_, eye = robot_sensor_specs("probe", "/probe/", description)
    assert (eye.name, eye.link, eye.frame, eye.spec.depth, eye.robot_namespace) == (
        "eye", "probe::chassis", "sonar_link", True, "/probe/")
    kinds = [type(s) for s in robot_sensor_specs("probe", "", description, cameras=False)]
    assert kinds == [RangeSensor, BumperSensor]


def test_a_robots_contact_sensor_without_plugin_is_still_one_warning():
    """As before: a robot's contact sensor alone talks only on Gazebo's transport."""
    text = URDF.read_text().replace(
        '<plugin name="bumper_controller" filename="libgazebo_ros_bumper.so">\n'
        '        <bumperTopicName>bumper</bumperTopicName>\n      </plugin>', "")
    plugins = read_urdf_text(text, "probe.urdf").plugins
    assert [type(s) for s in plugins.sensors] == [RangeSensor]
    [warning] = plugins.warnings
    assert warning.startswith("sensor 'bumper' (type contact) on link 'chassis' is not "
                              "simulated here; the robot runs without it")


def test_an_openni_kinect_on_a_world_model_runs_as_a_depth_camera(tmp_path):
    """Its WorldCamera (gazebo_ros_openni_kinect's topics) is served by DepthCameraRunner."""
    text = ('<model name="m"><static>true</static><link name="l"><sensor name="k" '
            'type="depth"><camera/><plugin name="p" filename="libgazebo_ros_openni_kinect.so"/>'
            '</sensor></link></model>')
    [kinect] = load_world(world_file(tmp_path, text)).sensors
    assert runner_for(kinect) is DepthCameraRunner


def test_the_fixture_is_read_as_a_robot():
    assert read_urdf(str(URDF)).plugins.drive is not None
