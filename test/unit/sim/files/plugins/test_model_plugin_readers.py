"""The model plugins (their modules of the plugin table: gazebo_ros_p3d,
gazebo_ros_joint_state_publisher, hector_gazebo_ros_imu, hector_gazebo_ros_gps) read from a
world model's <plugin>s (world_sdf, world_model_plugins), an included and a spawned one, and
from a URDF's <gazebo> block (robot_plugins): each one's defaults as its source writes them,
its parameters, and what warns. No ROS, no pybullet. Units: m, rad, deg, Hz."""
from pathlib import Path

import pytest

from tutorial_turtlebot.errors import WorldError
from tutorial_turtlebot.sim.files.plugins.gazebo_ros_joint_state_publisher import (
    JointStatePublisherPlugin)
from tutorial_turtlebot.sim.files.plugins.gazebo_ros_p3d import P3dPlugin
from tutorial_turtlebot.sim.files.plugins.hector_gazebo_ros_gps import HectorGpsPlugin
from tutorial_turtlebot.sim.files.plugins.hector_gazebo_ros_imu import (
    DRIFT_FREQUENCY, ErrorModel, HectorImuPlugin)
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_model_xml, load_world
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, read_urdf_text

from unit_helpers import world_file
import unit_paths

FIXTURES = Path(unit_paths.ROOT) / "test" / "fixtures" / "model_plugins"


def jointed(plugins, name="arm"):
    """A movable model of two links joined by a revolute joint "elbow", with ``plugins``."""
    return '''<model name="%s"><pose>0 0 1 0 0 0</pose>
<link name="base"><collision name="c"><geometry><box><size>.1 .1 .1</size></box></geometry>
</collision></link><link name="tip"><pose>0 0 0.3 0 0 0</pose><collision name="c"><geometry>
<box><size>.1 .1 .1</size></box></geometry></collision></link>
<joint name="elbow" type="revolute"><parent>base</parent><child>tip</child>
<axis><xyz>0 1 0</xyz></axis></joint>%s</model>''' % (name, plugins)


def plugins_of(tmp_path, plugins, name="arm"):
    world = load_world(world_file(tmp_path, jointed(plugins, name)))
    return world.model_plugins, world.warnings


def test_the_fixture_worlds_plugins_are_read_in_file_order():
    world = load_world(str(FIXTURES / "model_plugins.world"))
    assert world.warnings == ()
    p3d, joints, imu, box_p3d, gps = world.model_plugins
    assert p3d == P3dPlugin("bob_p3d", "pendulum", "bob", "/pendulum/bob_odom", update_rate=50)
    assert joints == JointStatePublisherPlugin("hinge_states", "pendulum", ("hinge",), 50.0)
    assert joints.namespace == "pendulum"          # the model's name: Gazebo's default
    assert (imu.model, imu.body_name, imu.robot_namespace, imu.update_rate) == (
        "box", "body", "box", 50.0)
    assert (gps.model, gps.update_rate) == ("box", 10.0)
    assert (box_p3d.topic, box_p3d.update_rate) == ("box_odom", 0.0)   # every physics step


def test_p3d_defaults_and_parameters(tmp_path):
    [plain], warnings = plugins_of(tmp_path, '<plugin name="p" filename="libgazebo_ros_p3d.so">'
                                   '<bodyName>tip</bodyName><topicName>odom</topicName>'
                                   '</plugin>')
    assert warnings == ()
    assert plain == P3dPlugin("p", "arm", "tip", "odom", frame_name="world", reference_link="",
                              xyz_offset=(0, 0, 0), rpy_offset=(0, 0, 0), gaussian_noise=0.0,
                              update_rate=0.0, robot_namespace="")
    [full], _ = plugins_of(tmp_path, '''<plugin name="q" filename="gazebo_ros_p3d">
<bodyName>/tip</bodyName><topicName>tip_pose</topicName><frameName>base</frameName>
<xyzOffset>1 2 3</xyzOffset><rpyOffset>0 0 0.5</rpyOffset><gaussianNoise>0.01</gaussianNoise>
<updateRate>25</updateRate><robotNamespace>ns</robotNamespace></plugin>''')
    assert full == P3dPlugin("q", "arm", "tip", "tip_pose", "base", "base", (1, 2, 3),
                             (0, 0, 0.5), 0.01, 25.0, "ns")


@pytest.mark.parametrize("body, words", [
    ("<topicName>t</topicName>", "has no <bodyName>"),
    ("<bodyName>tip</bodyName>", "has no <topicName>"),
    ("<bodyName>nose</bodyName><topicName>t</topicName>", "'nose' is not a link"),
    ("<bodyName>tip</bodyName><topicName>t</topicName><frameName>moon</frameName>",
     "'moon' is neither world, map nor a link"),
])
def test_a_p3d_gazebo_would_not_run_is_one_warning_and_left_out(tmp_path, body, words):
    found, warnings = plugins_of(tmp_path, '<plugin name="p" filename="libgazebo_ros_p3d.so">'
                                 '%s</plugin>' % body)
    assert found == ()
    [line] = warnings
    assert words in line and "test.world:" in line


def test_joint_state_publisher_defaults_and_an_unknown_joint(tmp_path):
    [plugin], _ = plugins_of(tmp_path, '<plugin name="j" filename="libgazebo_ros_joint_state_'
                             'publisher.so"><jointName> elbow , elbow</jointName></plugin>')
    assert plugin == JointStatePublisherPlugin("j", "arm", ("elbow", "elbow"), 100.0, "")
    found, [line] = plugins_of(tmp_path, '<plugin name="j" filename="libgazebo_ros_joint_state_'
                               'publisher.so"><jointName>elbow,knee</jointName></plugin>')
    assert found == () and "'knee'" in line and "elbow" in line


def test_hector_imu_defaults_and_its_error_models(tmp_path):
    [plain], warnings = plugins_of(tmp_path, '<plugin name="i" filename="libhector_gazebo_ros_'
                                   'imu.so"/>')
    assert warnings == ()
    assert plain == HectorImuPlugin("i", "arm", "base", "base", "imu", 0.0)   # the first link
    assert plain.accel == ErrorModel((0, 0, 0), (0, 0, 0), (DRIFT_FREQUENCY,) * 3, (0, 0, 0))
    [imu], _ = plugins_of(tmp_path, '''<plugin name="i" filename="libhector_gazebo_ros_imu.so">
<bodyName>tip</bodyName><frameId>imu_frame</frameId><topicName>raw_imu</topicName>
<accelDrift>0.1 0.2 0.3</accelDrift><rateGaussianNoise>0.05</rateGaussianNoise>
<yawOffset>0.2</yawOffset><rpyOffset>0.01 0.02 0</rpyOffset><randomEngineSeed>7</randomEngineSeed>
<updateRate>100</updateRate></plugin>''')
    assert (imu.body_name, imu.frame_id, imu.topic, imu.update_rate, imu.seed) == (
        "tip", "imu_frame", "raw_imu", 100.0, 7)
    assert imu.accel.drift == (0.1, 0.2, 0.3)
    assert imu.accel.offset == pytest.approx((0.02 * 9.8065, -0.01 * 9.8065, 0.0))
    assert imu.rate.gaussian_noise == (0.05, 0.05, 0.05)
    assert imu.heading.offset[0] == 0.2


def test_hector_gps_defaults_and_its_reference(tmp_path):
    [plain], warnings = plugins_of(tmp_path, '<plugin name="g" filename="libhector_gazebo_ros_'
                                   'gps.so"><bodyName>tip</bodyName></plugin>')
    assert warnings == ()
    assert plain == HectorGpsPlugin("g", "arm", "tip", "tip", "fix", "fix_velocity", 4.0, 49.9,
                                    8.9, 0.0, 0.0, 0, 1)
    [gps], _ = plugins_of(tmp_path, '''<plugin name="g" filename="libhector_gazebo_ros_gps.so">
<referenceLatitude>-33.5</referenceLatitude><referenceLongitude>151.2</referenceLongitude>
<referenceHeading>90</referenceHeading><referenceAltitude>12</referenceAltitude>
<gaussianNoise>0.5</gaussianNoise><velocityDrift>0.1</velocityDrift><status>2</status>
</plugin>''')
    assert (gps.reference_latitude, gps.reference_longitude, gps.reference_heading,
            gps.reference_altitude, gps.status) == (-33.5, 151.2, 90.0, 12.0, 2)
    assert gps.position.gaussian_noise == (0.5,) * 3 and gps.velocity.drift == (0.1,) * 3


def test_a_wrong_value_is_refused_in_one_line(tmp_path):
    with pytest.raises(WorldError, match=r"test.world:\d+: .*referenceLatitude"):
        plugins_of(tmp_path, '<plugin name="g" filename="libhector_gazebo_ros_gps.so">'
                   '<referenceLatitude>95</referenceLatitude></plugin>')
    with pytest.raises(WorldError, match="one or three numbers"):
        plugins_of(tmp_path, '<plugin name="p" filename="libgazebo_ros_p3d.so"><bodyName>tip'
                   '</bodyName><topicName>t</topicName><xyzOffset>1 2</xyzOffset></plugin>')


def test_other_model_plugins_are_still_one_warning_per_world(tmp_path):
    body = (jointed('<plugin name="a" filename="libdoor.so"/>'
                    '<plugin name="p" filename="libgazebo_ros_p3d.so"><bodyName>tip</bodyName>'
                    '<topicName>t</topicName><misspelt>1</misspelt></plugin>')
            + jointed('<plugin name="b" filename="libgazebo_ros_force.so"/>', "arm2"))
    world = load_world(world_file(tmp_path, body))
    [p3d] = world.model_plugins
    assert p3d.body_name == "tip"
    [skipped] = [w for w in world.warnings if "<plugin> of a model skipped" in w]
    assert skipped.endswith("(and 1 more)")
    assert any("<misspelt> is not a parameter" in w for w in world.warnings)


def test_a_spawned_and_an_included_models_plugins(tmp_path):
    spawned = load_model_xml('<sdf version="1.6">%s</sdf>' % jointed(
        '<plugin name="j" filename="libgazebo_ros_joint_state_publisher.so">'
        '<jointName>elbow</jointName></plugin>'), "spawn", "copy")
    [plugin] = spawned.model_plugins
    assert (plugin.model, plugin.joint_names) == ("copy", ("elbow",))
    folder = tmp_path / "arm_model"
    folder.mkdir()
    (folder / "model.sdf").write_text('<sdf version="1.6">%s</sdf>' % jointed(""))
    (folder / "model.config").write_text("<model><sdf>model.sdf</sdf></model>")
    world = load_world(world_file(tmp_path, '''<include><uri>%s</uri><name>arm_b</name>
<plugin name="p" filename="libgazebo_ros_p3d.so"><bodyName>tip</bodyName><topicName>t
</topicName></plugin></include>''' % folder))
    [p3d] = world.model_plugins
    assert (p3d.model, p3d.body_name) == ("arm_b", "tip")


def test_a_urdf_robots_model_plugins_are_kept_without_a_warning():
    robot = read_urdf(str(FIXTURES / "p3d_robot.urdf"))
    assert robot.plugins.drive is not None
    p3d, joints = robot.plugins.model_plugins
    assert (p3d.body_name, p3d.topic, p3d.update_rate) == ("base_link", "ground_truth", 30.0)
    assert joints.joint_names == ("left_joint", "right_joint")
    assert not [w for w in robot.plugins.warnings if "not simulated" in w]


def test_a_urdf_plugin_naming_no_link_is_one_warning():
    text = (FIXTURES / "p3d_robot.urdf").read_text().replace(
        "<bodyName>base_link</bodyName>", "<bodyName>chassis</bodyName>")
    robot = read_urdf_text(text, "p3d_robot")
    assert len(robot.plugins.model_plugins) == 1
    assert any("'chassis' is not a link" in w for w in robot.plugins.warnings)
