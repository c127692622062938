"""The drive plugins besides the diff drive as a URDF's <gazebo> block declares them (their
modules of the plugin table, through urdf_file.read_urdf_text): Gazebo's defaults, the
parameters read, the one-line refusals and the warnings. Units: m, s, rad, Hz, N*m."""
from pathlib import Path

import pytest

from tutorial_turtlebot.errors import UrdfError
from tutorial_turtlebot.sim.files.plugins.gazebo_ros_force_based_move import (
    ForceBasedMovePlugin)
from tutorial_turtlebot.sim.files.plugins.gazebo_ros_planar_move import PlanarMovePlugin
from tutorial_turtlebot.sim.files.plugins.gazebo_ros_skid_steer_drive import SkidSteerPlugin
from tutorial_turtlebot.sim.files.plugins.gazebo_ros_tricycle_drive import TricyclePlugin
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf_text
import unit_paths

DRIVES = Path(unit_paths.FIXTURES) / "drives"
SKID = (DRIVES / "skid_steer.urdf").read_text()
PLANAR = (DRIVES / "planar_move.urdf").read_text()


def with_plugin(text, plugin):
    """``text`` (a fixture URDF) with its one <plugin> replaced by ``plugin``."""
    start, end = text.index("<plugin"), text.index("</plugin>") + len("</plugin>")
    return text[:start] + plugin + text[end:]


def skid_plugin(body=""):
    """A skid steer on the fixture's wheels (its joints' names are Gazebo's defaults)."""
    return ('<plugin name="skid" filename="libgazebo_ros_skid_steer_drive.so">%s</plugin>'
            % body)


def test_the_skid_steer_fixture_is_read_as_written():
    robot = read_urdf_text(SKID, "skid")
    assert robot.plugins.drive == SkidSteerPlugin(
        name="skid_steer_drive_controller", wheel_separation=0.35, wheel_diameter=0.1,
        torque=10.0, update_rate=100.0, robot_base_frame="base_footprint", broadcast_tf=True)
    assert robot.plugins.warnings == ()


def test_skid_steer_defaults_are_gazebos():
    """gazebo_ros_skid_steer_drive: joints left_front_joint ..., separation 0.4 m, diameter
    0.15 m, torque 5 N*m, cmd_vel, odom, odom -> base_footprint, 100 Hz, covariances 1e-4,
    1e-4, 1e-2, no TF."""
    drive = read_urdf_text(with_plugin(SKID, skid_plugin()), "skid").plugins.drive
    assert drive == SkidSteerPlugin(name="skid")
    assert (drive.wheel_separation, drive.wheel_diameter, drive.torque) == (0.4, 0.15, 5.0)
    assert (drive.command_topic, drive.odometry_topic, drive.odometry_frame,
            drive.robot_base_frame) == ("cmd_vel", "odom", "odom", "base_footprint")
    assert drive.update_rate == 100.0 and drive.broadcast_tf is False
    assert drive.pose_covariance == (1e-4, 1e-4, 1e12, 1e12, 1e12, 1e-2)


def test_skid_steer_parameters_are_read():
    body = ("<robotNamespace>rover</robotNamespace><commandTopic>drive/cmd</commandTopic>"
            "<odometryTopic>drive/odom</odometryTopic><odometryFrame>world_odom</odometryFrame>"
            "<robotBaseFrame>base_link</robotBaseFrame><updateRate>50</updateRate>"
            "<covariance_x>0.5</covariance_x><covariance_y>0.25</covariance_y>"
            "<covariance_yaw>0.125</covariance_yaw><broadcastTF>1</broadcastTF>")
    drive = read_urdf_text(with_plugin(SKID, skid_plugin(body)), "skid").plugins.drive
    assert (drive.robot_namespace, drive.command_topic, drive.odometry_topic) == (
        "rover", "drive/cmd", "drive/odom")
    assert (drive.odometry_frame, drive.robot_base_frame, drive.update_rate) == (
        "world_odom", "base_link", 50.0)
    assert drive.pose_covariance == (0.5, 0.25, 1e12, 1e12, 1e12, 0.125)
    assert drive.publish_odom_tf is True


@pytest.mark.parametrize("body, words", [
    ("<leftFrontJoint>nowhere</leftFrontJoint>", ["<leftFrontJoint>", "joint 'nowhere' is not "
                                                  "in this robot", "left_front_joint"]),
    ("<rightRearJoint>base_joint</rightRearJoint>", ["joint 'base_joint' is fixed"]),
    ("<wheelDiameter>-0.1</wheelDiameter>", ["<wheelDiameter>", "wheelDiameter -0.1"]),
    ("<torque>0</torque>", ["<torque>", "torque 0", "positive"]),
    ("<updateRate>-5</updateRate>", ["<updateRate>"]),
    ("<commandTopic>cmd vel</commandTopic>", ["'cmd vel' is not a ROS name"]),
    ("<broadcastTF>perhaps</broadcastTF>", ["<broadcastTF>"]),
])
def test_bad_skid_steer_values_are_one_line_refusals(body, words):
    text = with_plugin(SKID, skid_plugin(body))
    with pytest.raises(UrdfError) as err:
        read_urdf_text(text, "skid")
    message = str(err.value)
    assert message.startswith("skid:") and "\n" not in message
    for word in words:
        assert word in message


def test_missing_default_wheel_joints_are_refused():
    """Gazebo throws without a joint of the name: so does the reader, naming the robot's."""
    text = SKID.replace("left_front_joint", "lf_joint")
    with pytest.raises(UrdfError, match="no <leftFrontJoint>, and the default joint "
                                        "'left_front_joint' is not in this robot"):
        read_urdf_text(with_plugin(text, skid_plugin()), "skid")


def test_a_misspelt_drive_parameter_is_warned_and_a_second_drive_too():
    second = ('<plugin name="other" filename="libgazebo_ros_planar_move.so"/>')
    text = with_plugin(SKID, skid_plugin("<wheelSeperation>0.3</wheelSeperation>") + second)
    plugins = read_urdf_text(text, "skid").plugins
    assert plugins.drive.wheel_separation == 0.4 and plugins.drive.name == "skid"
    assert len(plugins.warnings) == 2
    assert "<wheelSeperation> is not a parameter of libgazebo_ros_skid_steer_drive.so" in (
        plugins.warnings[0])
    assert "other" in plugins.warnings[1] and "skid" in plugins.warnings[1]


def test_the_planar_move_fixture_and_its_defaults():
    """gazebo_ros_planar_move: cmd_vel, odom, odom -> base_footprint, odometry at 20 Hz, no
    command timeout, the TF always."""
    robot = read_urdf_text(PLANAR, "planar")
    assert robot.plugins.drive == PlanarMovePlugin(name="object_controller")
    bare = '<plugin name="p" filename="libgazebo_ros_planar_move.so"/>'
    drive = read_urdf_text(with_plugin(PLANAR, bare), "planar").plugins.drive
    assert (drive.command_topic, drive.odometry_topic, drive.odometry_frame,
            drive.robot_base_frame, drive.odometry_rate, drive.cmd_timeout) == (
        "cmd_vel", "odom", "odom", "base_footprint", 20.0, -1.0)
    assert drive.publish_odom_tf is True
    assert drive.pose_covariance == (1e-5, 1e-5, 1e12, 1e12, 1e12, 1e-3)


def test_planar_move_parameters_and_refusals():
    plugin = ('<plugin name="p" filename="gazebo_ros_planar_move"><cmdTimeout>0.5</cmdTimeout>'
              '<odometryRate>50</odometryRate><robotNamespace>mover</robotNamespace>'
              '<updateRate>10</updateRate></plugin>')
    plugins = read_urdf_text(with_plugin(PLANAR, plugin), "planar").plugins
    assert (plugins.drive.cmd_timeout, plugins.drive.odometry_rate,
            plugins.drive.robot_namespace) == (0.5, 50.0, "mover")
    assert len(plugins.warnings) == 1 and "<updateRate> is not a parameter" in (
        plugins.warnings[0])
    bad = plugin.replace("<cmdTimeout>0.5", "<cmdTimeout>nan")
    with pytest.raises(UrdfError, match="<cmdTimeout>"):
        read_urdf_text(with_plugin(PLANAR, bad), "planar")


TRICYCLE = (DRIVES / "tricycle.urdf").read_text()
FORCE = (DRIVES / "force_based_move.urdf").read_text()


def test_tricycle_defaults_are_gazebos():
    """gazebo_ros_tricycle_drive: its four default joints (the fixture's), diameters 0.15 m,
    encoder wheels 0.5 m apart, torque 5 N*m, base_link, 100 Hz, world odometry, no ramp,
    tolerances 0.01, the angle at once."""
    bare = '<plugin name="t" filename="libgazebo_ros_tricycle_drive.so"/>'
    drive = read_urdf_text(with_plugin(TRICYCLE, bare), "tricycle").plugins.drive
    assert drive == TricyclePlugin(name="t")
    assert (drive.steering_joint, drive.actuated_wheel_joint, drive.encoder_wheel_left_joint,
            drive.encoder_wheel_right_joint) == ("front_steering_joint", "front_wheel_joint",
                                                 "left_wheel_joint", "right_wheel_joint")
    assert (drive.actuated_wheel_diameter, drive.encoder_wheel_separation,
            drive.wheel_torque, drive.robot_base_frame, drive.update_rate) == (
        0.15, 0.5, 5.0, "base_link", 100.0)
    assert (drive.odometry_source, drive.steering_speed, drive.wheel_speed_tolerance) == (
        "world", 0.0, 0.01)


def test_tricycle_parameters_and_refusals():
    plugin = ('<plugin name="t" filename="libgazebo_ros_tricycle_drive.so">'
              '<wheelAcceleration>0.5</wheelAcceleration><odometrySource>encoder</odometrySource>'
              '<steeringSpeed>1.0</steeringSpeed></plugin>')
    drive = read_urdf_text(with_plugin(TRICYCLE, plugin), "tricycle").plugins.drive
    assert (drive.wheel_acceleration, drive.wheel_deceleration) == (0.5, 0.5)   # its default
    assert (drive.odometry_source, drive.steering_speed) == ("encoders", 1.0)
    for old, new, words in [("encoder<", "wheels<", "must be world or encoder"),
                            ("<steeringSpeed>1.0", "<steeringSpeed>-1", "<steeringSpeed>")]:
        with pytest.raises(UrdfError, match=words):
            read_urdf_text(with_plugin(TRICYCLE, plugin.replace(old, new)), "tricycle")
    no_joint = TRICYCLE.replace("front_steering_joint", "steer_joint")
    with pytest.raises(UrdfError, match="no <steeringJoint>"):
        read_urdf_text(no_joint, "tricycle")


def test_force_based_move_defaults_and_gains():
    """hector's gazebo_ros_force_based_move: gains x, y 10000 N per m/s, yaw 100 N*m per
    rad/s; odometry at 20 Hz with its TF."""
    bare = '<plugin name="f" filename="libgazebo_ros_force_based_move.so"/>'
    drive = read_urdf_text(with_plugin(FORCE, bare), "force").plugins.drive
    assert drive == ForceBasedMovePlugin(name="f")
    assert (drive.x_velocity_p_gain, drive.y_velocity_p_gain, drive.yaw_velocity_p_gain) == (
        10000.0, 10000.0, 100.0)
    assert (drive.odometry_rate, drive.publish_odom_tf, drive.robot_base_frame) == (
        20.0, True, "base_footprint")
    plugin = bare.replace("/>", "><yaw_velocity_p_gain>50</yaw_velocity_p_gain>"
                                "<publishOdometryTf>false</publishOdometryTf></plugin>")
    drive = read_urdf_text(with_plugin(FORCE, plugin), "force").plugins.drive
    assert drive.yaw_velocity_p_gain == 50.0 and drive.publish_odom_tf is False
    with pytest.raises(UrdfError, match="<x_velocity_p_gain>"):
        read_urdf_text(with_plugin(FORCE, bare.replace(
            "/>", "><x_velocity_p_gain>-1</x_velocity_p_gain></plugin>")), "force")
