"""A world model's contact sensor with libgazebo_ros_bumper.so and imu sensor with
libgazebo_ros_imu_sensor.so, read by world_sdf through the plugin table (gazebo_ros_bumper,
gazebo_ros_imu_sensor): gazebo_plugins' defaults, the collisions scoped as Gazebo's
ContactSensor scopes them, the <imu> noise, an IMU plugin without <frameName> left out with one
warning, and a robot's imu sensor still not run. No ROS, no pybullet. Units: rad, Hz."""
import pytest

from tutorial_turtlebot.errors import WorldError
from tutorial_turtlebot.sim.files.plugins import table
from tutorial_turtlebot.sim.files.plugins.gazebo_ros_bumper import BUMPER, BumperSensor
from tutorial_turtlebot.sim.files.plugins.gazebo_ros_imu_sensor import (
    IMU_SENSOR, AxisNoise, ImuSensorPlugin)
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world

from unit_helpers import world_file

CONTACT = "<contact><collision>pad</collision><collision>rim</collision></contact>"
NOISE = ('<imu><angular_velocity><z><noise type="gaussian"><mean>0.01</mean><stddev>0.02'
         '</stddev><bias_mean>0.003</bias_mean></noise></z></angular_velocity>'
         '<linear_acceleration><x><noise type="gaussian"><stddev>0.1</stddev></noise></x>'
         '</linear_acceleration></imu>')


def model(sensors, name="m"):
    return ('<model name="%s"><static>true</static><link name="l"><collision name="pad">'
            '<geometry><box><size>1 1 1</size></box></geometry></collision>%s</link></model>'
            % (name, sensors))


def sensor(plugin_file, kind, body="", params=""):
    return ('<sensor name="s" type="%s">%s<plugin name="p" filename="%s">%s</plugin></sensor>'
            % (kind, body, plugin_file, params))


def test_the_bumper_is_contact_sensors_and_the_imu_sensor_imu_sensors_on_both_hosts():
    for host in ("world", "robot"):
        assert table.plugins_of("contact", host) == (BUMPER,)
        assert table.plugins_of("imu", host) == (IMU_SENSOR,)


def test_a_bumper_takes_gazebo_ros_bumpers_defaults(tmp_path):
    world = load_world(world_file(tmp_path, model(sensor(BUMPER, "contact", CONTACT))))
    assert world.sensors == (BumperSensor(name="s", link="m::l",
                                          collisions=("m::l::pad", "m::l::rim"), plugin="p"),)
    assert (world.sensors[0].topic, world.sensors[0].frame, world.sensors[0].rate) == (
        "bumper_states", "world", 0.0)
    assert world.warnings == ()


def test_a_bumpers_settings_and_its_sensors_rate(tmp_path):
    params = ("<bumperTopicName>pads</bumperTopicName><frameName>/pad_frame</frameName>"
              "<robotNamespace>rig</robotNamespace>")
    body = "<update_rate>25</update_rate>" + CONTACT
    [bumper] = load_world(world_file(tmp_path, model(sensor(BUMPER, "contact", body,
                                                            params)))).sensors
    assert (bumper.topic, bumper.frame, bumper.robot_namespace, bumper.rate) == (
        "pads", "pad_frame", "rig", 25.0)


def test_an_imu_sensor_takes_gazebo_ros_imu_sensors_defaults(tmp_path):
    text = model(sensor(IMU_SENSOR, "imu", params="<frameName>imu_link</frameName>"))
    [imu] = load_world(world_file(tmp_path, text)).sensors
    assert imu == ImuSensorPlugin(name="s", link="m::l", frame="imu_link", plugin="p",
                                  robot_namespace="/m")
    assert (imu.topic, imu.rate, imu.gaussian_noise, imu.rpy_offset) == (
        "imu_data", 1.0, 0.0, (0.0, 0.0, 0.0))


def test_an_imu_sensors_settings_and_its_imu_noise(tmp_path):
    params = ("<frameName>/imu_link</frameName><topicName>imu</topicName><robotNamespace>rig"
              "</robotNamespace><updateRateHZ>100</updateRateHZ><gaussianNoise>0.05"
              "</gaussianNoise><rpyOffset>0 0 1.5</rpyOffset>")
    body = "<update_rate>40</update_rate>" + NOISE
    [imu] = load_world(world_file(tmp_path, model(sensor(IMU_SENSOR, "imu", body,
                                                         params)))).sensors
    assert (imu.frame, imu.topic, imu.robot_namespace, imu.rate, imu.gaussian_noise,
            imu.rpy_offset) == ("/imu_link", "imu", "rig", 40.0, 0.05, (0.0, 0.0, 1.5))
    assert imu.rate_noise == (AxisNoise(), AxisNoise(), AxisNoise(0.01, 0.02, 0.003, 0.0))
    assert imu.accel_noise == (AxisNoise(0.0, 0.1), AxisNoise(), AxisNoise())


def test_an_imu_plugin_without_frame_name_does_not_load_one_warning(tmp_path):
    world = load_world(world_file(tmp_path, model(sensor(IMU_SENSOR, "imu"))))
    assert world.sensors == ()
    [warning] = world.warnings
    assert "has no <frameName>" in warning and "\n" not in warning


def test_a_wrong_imu_noise_is_refused_in_one_line(tmp_path):
    body = '<imu><angular_velocity><x><noise type="pink"/></x></angular_velocity></imu>'
    text = model(sensor(IMU_SENSOR, "imu", body, "<frameName>f</frameName>"))
    with pytest.raises(WorldError, match="type must be one of") as refused:
        load_world(world_file(tmp_path, text))
    assert "\n" not in str(refused.value)
