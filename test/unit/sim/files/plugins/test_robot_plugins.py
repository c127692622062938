"""The <gazebo> blocks of a URDF as the simulator reads them (robot_plugins.read_plugins through
urdf_file.read_urdf): the shipped TurtleBot3 files against doc/turtlebot3.md section 2 (and 4.5),
edited robots, the one-line errors and the warnings. No ROS master needed.
Units: m, s, rad, Hz, N*m, m/s^2."""
import math
from pathlib import Path

import pybullet
import pytest

from tutorial_turtlebot.errors import UrdfError
from tutorial_turtlebot.sim.devices.lidar import LASER_MODELS, LaserConfig
from tutorial_turtlebot.sim.files.plugins.robot_plugin_types import (
    CAMERA, GPU_LASER, LASER, OPENNI_KINECT, CameraSensor, CameraSpec, DiffDrivePlugin,
    ImuPlugin, LaserSensor, RobotPlugins)
from tutorial_turtlebot.sim.files.plugins.robot_plugins import plugin_file
from tutorial_turtlebot.sim.files.urdf.urdf_file import RobotDescription, read_urdf, read_urdf_text
import unit_paths

ROOT = Path(unit_paths.ROOT)
URDF = ROOT / "urdf"
CAMERA_SNIPPET = (Path(unit_paths.DATA) / "burger_camera.xml").read_text()

# --- doc/turtlebot3.md 2.1-2.4 and 4.5, with the simulator's two choices (IMU 200 Hz, imu_link) ---


def drive(name, separation):
    """doc/turtlebot3.md 2.1: identical for all models but the name and wheelSeparation."""
    return DiffDrivePlugin(
        name=name, command_topic="cmd_vel", odometry_topic="odom", odometry_frame="odom",
        robot_base_frame="base_footprint", odometry_source="world", publish_tf=True,
        publish_wheel_tf=False, publish_wheel_joint_state=True, update_rate=30.0,
        left_joint="wheel_left_joint", right_joint="wheel_right_joint",
        wheel_separation=separation, wheel_diameter=0.066, wheel_acceleration=1.0,
        wheel_torque=10.0, robot_namespace="", publish_odom_tf=True)


# doc/turtlebot3.md 2.2: the LDS, the same on every model.
LDS = LaserSensor(
    name="lds_lfcd_sensor", link="base_scan",
    laser=LaserConfig("gazebo", 0.0, 6.28319, 6.28319 / 359, samples=360, range_min=0.12,
                      range_max=3.5, noise_sigma=0.01, rate=5.0),
    topic="scan", frame="base_scan", plugin="gazebo_ros_lds_lfcd_controller",
    robot_namespace="", plugin_file=LASER, pose=(0.0,) * 6, range_resolution=0.015)

# doc/turtlebot3.md 2.3, but 200 Hz and imu_link (deliberate, see the URDF's comment).
IMU_PLUGIN = ImuPlugin(name="imu_plugin", body_name="imu_link", frame_name="imu_link",
                       topic="imu", service_name="imu_service", update_rate=200.0,
                       gaussian_noise=0.0, robot_namespace="")


def pi_camera(width, height):
    """doc/turtlebot3.md 2.4 (waffle_pi), 4.5 (AutoRace burger): a Pi camera, gazebo_ros_camera."""
    return CameraSensor(
        name="Pi Camera", link="camera_rgb_frame",
        spec=CameraSpec(width, height, 1.085595, 30.0, near=0.03, far=100.0, depth=False,
                        baseline=0.07),
        plugin_file=CAMERA, camera_name="camera", frame="camera_rgb_optical_frame",
        image_topic="rgb/image_raw", info_topic="rgb/camera_info", robot_namespace="",
        pose=(0.0,) * 6)


R200 = CameraSensor(
    name="realsense_R200", link="camera_rgb_frame",
    # the first of the xacro's two hackBaseline (0.07, then 0) is the one Gazebo reads
    spec=CameraSpec(1920, 1080, 1.3439, 30.0, near=0.03, far=100.0, depth=True, baseline=0.07),
    plugin_file=OPENNI_KINECT, camera_name="camera", frame="camera_rgb_optical_frame",
    image_topic="rgb/image_raw", info_topic="rgb/camera_info",
    depth_image_topic="depth/image_raw", depth_info_topic="depth/camera_info",
    point_cloud_topic="depth/points", point_cloud_cutoff=0.4, point_cloud_cutoff_max=5.0,
    robot_namespace="", pose=(0.0,) * 6)

FACTS = {
    "turtlebot3_burger.urdf": RobotPlugins(
        drive("turtlebot3_burger_controller", 0.160), LDS, IMU_PLUGIN, None),
    "turtlebot3_burger_for_autorace.urdf": RobotPlugins(
        drive("turtlebot3_burger_controller", 0.160), LDS, IMU_PLUGIN, pi_camera(320, 240)),
    "turtlebot3_waffle.urdf": RobotPlugins(
        drive("turtlebot3_waffle_controller", 0.287), LDS, IMU_PLUGIN, R200),
    "turtlebot3_waffle_pi.urdf": RobotPlugins(
        drive("turtlebot3_waffle_pi_controller", 0.287), LDS, IMU_PLUGIN, pi_camera(640, 480)),
}


@pytest.mark.parametrize("filename", list(FACTS))
def test_turtlebot3_plugins_equal_the_facts(filename):
    """Every field of every plugin, and no warning."""
    assert read_urdf(URDF / filename).plugins == FACTS[filename]


def test_the_facts_are_the_simulators_numbers():
    """The laser is lidar.py's "gazebo" model; the wheels are 0.033 m in radius."""
    plugins = read_urdf(URDF / "turtlebot3_waffle.urdf").plugins
    assert plugins.laser.laser == LASER_MODELS["gazebo"]
    assert plugins.drive.wheel_radius == pytest.approx(0.033)
    assert plugins.imu.frame == "imu_link"


# --- edited robots -------------------------------------------------------------------------------

def burger_text():
    return (URDF / "turtlebot3_burger.urdf").read_text()


def write(tmp_path, text, name="robot.urdf"):
    path = tmp_path / name
    path.write_text(text)
    return path


def edited(tmp_path, old, new, text=None):
    """The Burger's URDF (or ``text``) with ``old`` (which must be there once) made ``new``."""
    text = burger_text() if text is None else text
    assert text.count(old) == 1, old
    return write(tmp_path, text.replace(old, new))


def with_camera(text):
    """``text`` with doc/robots.md's camera snippet pasted before </robot>."""
    return text.replace("</robot>", CAMERA_SNIPPET + "</robot>")


def test_a_24_sample_scan(tmp_path):
    """The machine-learning e-Manual's edit: 24 samples over the same turn."""
    path = edited(tmp_path, "<samples>360</samples>", "<samples>24</samples>")
    plugins = read_urdf(path).plugins
    assert plugins.laser.laser.samples == 24
    assert plugins.laser.laser.angle_increment == pytest.approx(6.28319 / 23)
    assert plugins.laser.laser.angle_max == 6.28319
    assert plugins.warnings == ()
    assert plugins.drive == FACTS["turtlebot3_burger.urdf"].drive


def test_a_shorter_slower_noisier_scan(tmp_path):
    text = burger_text()
    for old, new in [("<max>3.5</max>", "<max>2.0</max>"), ("<stddev>0.01</stddev>",
                                                            "<stddev>0.05</stddev>"),
                     ("<update_rate>5</update_rate>", "<update_rate>10</update_rate>"),
                     ("<max_angle>6.28319</max_angle>", "<max_angle>3.14159</max_angle>"),
                     ("<min_angle>0.0</min_angle>", "<min_angle>-3.14159</min_angle>")]:
        text = text.replace(old, new)
    laser = read_urdf(write(tmp_path, text)).plugins.laser.laser
    assert (laser.range_max, laser.noise_sigma, laser.rate) == (2.0, 0.05, 10.0)
    assert (laser.angle_min, laser.angle_max) == (-3.14159, 3.14159)
    assert laser.angle_increment == pytest.approx(2 * 3.14159 / 359)


def test_a_camera_on_the_burger(tmp_path):
    """doc/robots.md's snippet: a link, a fixed joint and a <gazebo> block give the Burger a camera;
    without <updateRate> in the plugin the sensor's <update_rate> is the rate."""
    robot = read_urdf(write(tmp_path, with_camera(burger_text())))
    assert robot.plugins.camera == CameraSensor(
        name="front_camera", link="camera_link",
        spec=CameraSpec(640, 480, 1.085595, 30.0, near=0.03, far=100.0),
        plugin_file=CAMERA, camera_name="camera", frame="camera_optical_frame",
        image_topic="rgb/image_raw", info_topic="rgb/camera_info")
    assert robot.plugins.warnings == ()
    assert robot.joints["camera_joint"].parent == "base_link"
    client = pybullet.connect(pybullet.DIRECT)
    try:
        body = pybullet.loadURDF(str(robot.path), physicsClientId=client)
        assert pybullet.getNumJoints(body, physicsClientId=client) == len(robot.joints)
    finally:
        pybullet.disconnect(client)


def test_plugin_rate_wins_over_sensor_rate_and_first_baseline_counts(tmp_path):
    text = (URDF / "turtlebot3_waffle.urdf").read_text()
    old = "<visualize>false</visualize>\n      <camera>"
    assert text.count(old) == 1
    text = text.replace(old, "<update_rate>5</update_rate>\n      <camera>")
    path = edited(tmp_path, "<hackBaseline>0.07</hackBaseline>",
                  "<hackBaseline>0.1</hackBaseline>", text)
    spec = read_urdf(path).plugins.camera.spec
    assert (spec.rate, spec.baseline) == (30.0, 0.1)


def test_robot_namespace_topics_and_slashed_frames(tmp_path):
    path = edited(tmp_path, "<frameName>base_scan</frameName>",
                  "<frameName>/base_scan</frameName>\n<robotNamespace>tb3_0</robotNamespace>"
                  "\n<topicName>/scan_front</topicName>")
    laser = read_urdf(path).plugins.laser
    assert (laser.frame, laser.robot_namespace) == ("base_scan", "tb3_0")
    assert laser.topic == "scan"   # the first <topicName> counts, as in Gazebo


def test_encoder_odometry_is_encoders(tmp_path):
    path = edited(tmp_path, "<odometrySource>world</odometrySource>",
                  "<odometrySource>encoder</odometrySource>")
    assert read_urdf(path).plugins.drive.odometry_source == "encoders"


# --- Gazebo's defaults for what a block leaves out ---------------------------------------------

ROBOT = """<robot name="r">
  <link name="base"/>
  <link name="left"/>
  <link name="right"/>
  <link name="lidar"/>
  <joint name="left_joint" type="continuous"><parent link="base"/><child link="left"/>
  </joint>
  <joint name="right_joint" type="continuous"><parent link="base"/><child link="right"/>
  </joint>
  <joint name="lidar_joint" type="fixed"><parent link="base"/><child link="lidar"/></joint>
%s
</robot>
"""


def test_gazebo_defaults(tmp_path):
    """Blocks with almost nothing in them get gazebo_plugins' defaults; a laser without
    <frameName> is in its own link (Gazebo's "/world" is in no robot's TF tree)."""
    blocks = """
  <gazebo><plugin name="drive" filename="libgazebo_ros_diff_drive.so"/></gazebo>
  <gazebo><plugin name="imu" filename="gazebo_ros_imu"><bodyName>base</bodyName></plugin></gazebo>
  <gazebo reference="lidar">
    <sensor type="gpu_ray" name="front">
      <ray><scan><horizontal><samples>3</samples><min_angle>-1</min_angle>
        <max_angle>1</max_angle></horizontal></scan><range><max>10</max></range></ray>
      <plugin name="lidar_plugin" filename="libgazebo_ros_gpu_laser.so"/>
    </sensor>
  </gazebo>"""
    plugins = read_urdf(write(tmp_path, ROBOT % blocks)).plugins
    assert plugins.drive == DiffDrivePlugin(
        name="drive", update_rate=100.0, left_joint="left_joint", right_joint="right_joint",
        wheel_separation=0.34, wheel_diameter=0.15, wheel_acceleration=0.0, wheel_torque=5.0,
        publish_tf=True, publish_wheel_joint_state=False, odometry_source="world")
    assert plugins.imu == ImuPlugin(name="imu", body_name="base", frame_name="",
                                    topic="/default_imu", service_name="/default_imu",
                                    update_rate=0.0)
    assert plugins.imu.frame == "base"
    assert plugins.laser == LaserSensor(
        name="front", link="lidar", plugin="lidar_plugin", plugin_file=GPU_LASER,
        topic="/world", frame="lidar",
        laser=LaserConfig("gazebo", -1.0, 1.0, 1.0, samples=3, range_min=0.0, range_max=10.0,
                          noise_sigma=0.0, rate=0.0))
    assert plugins.warnings == ()


def test_depth_camera_defaults(tmp_path):
    blocks = """
  <gazebo reference="lidar">
    <sensor type="depth" name="kinect">
      <plugin name="k" filename="libgazebo_ros_openni_kinect.so"/>
    </sensor>
  </gazebo>"""
    camera = read_urdf(write(tmp_path, ROBOT % blocks)).plugins.camera
    assert camera == CameraSensor(
        name="kinect", link="lidar", plugin_file=OPENNI_KINECT, camera_name="", frame="lidar",
        spec=CameraSpec(320, 240, 1.047, 0.0, near=0.1, far=100.0, depth=True, baseline=0.0),
        image_topic="ir/image_raw", info_topic="ir/camera_info",   # the kinect's own defaults
        depth_image_topic="depth/image_raw", depth_info_topic="depth/camera_info",
        point_cloud_topic="points")


def test_plugin_file_is_completed_as_gazebo_does():
    assert plugin_file("gazebo_ros_laser") == LASER
    assert plugin_file("/opt/ros/noetic/lib/libgazebo_ros_camera.so") == CAMERA
    assert plugin_file(" libgazebo_ros_imu.so ") == "libgazebo_ros_imu.so"


def test_a_description_built_by_hand_has_no_plugins():
    robot = RobotDescription("r", "r.urdf", {}, {})
    assert robot.plugins == RobotPlugins()


# --- bad blocks: (old text in the Burger, new text, the line's marker, words of the message) -----

BAD = {
    "joint_not_there": ("<leftJoint>wheel_left_joint</leftJoint>",
                        "<leftJoint>wheel_lef_joint</leftJoint>", "<leftJoint>",
                        ["plugin 'turtlebot3_burger_controller' (libgazebo_ros_diff_drive.so) "
                         "<leftJoint>", "joint 'wheel_lef_joint' is not in this robot",
                         "wheel_left_joint, wheel_right_joint"]),
    "joint_fixed": ("<rightJoint>wheel_right_joint</rightJoint>",
                    "<rightJoint>scan_joint</rightJoint>", "<rightJoint>",
                    ["<rightJoint>", "joint 'scan_joint' is fixed", "continuous or revolute"]),
    "joint_left_out": ("<rightJoint>wheel_right_joint</rightJoint>", "",
                       'filename="libgazebo_ros_diff_drive.so"',
                       ["plugin 'turtlebot3_burger_controller'", "no <rightJoint>",
                        "default joint 'right_joint'"]),
    "reference_not_a_link": ('<gazebo reference="base_scan">', '<gazebo reference="base_sacn">',
                             'reference="base_sacn"',
                             ["<gazebo reference='base_sacn'>", "not a link"]),
    "body_not_a_link": ("<bodyName>imu_link</bodyName>", "<bodyName>imu</bodyName>",
                        "<bodyName>", ["plugin 'imu_plugin' (libgazebo_ros_imu.so) <bodyName>",
                                       "'imu' is not a link"]),
    "imu_frame_not_a_link": ("<frameName>imu_link</frameName>", "<frameName>imu</frameName>",
                             "<frameName>imu<", ["plugin 'imu_plugin'", "<frameName>",
                                                 "'imu' is not a link"]),
    "imu_without_body": ("<bodyName>imu_link</bodyName>", "", 'filename="libgazebo_ros_imu.so"',
                         ["plugin 'imu_plugin'", "missing <bodyName>"]),
    "laser_frame_not_a_link": ("<frameName>base_scan</frameName>", "<frameName>laser</frameName>",
                               "<frameName>laser", ["plugin 'gazebo_ros_lds_lfcd_controller' "
                                                    "(libgazebo_ros_laser.so) <frameName>",
                                                    "'laser' is not a link"]),
    "samples_negative": ("<samples>360</samples>", "<samples>-5</samples>", "<samples>",
                         ["sensor 'lds_lfcd_sensor' <samples>",
                          "must be a positive integer, got '-5'"]),
    "samples_zero": ("<samples>360</samples>", "<samples>0</samples>", "<samples>",
                     ["<samples>", "positive integer"]),
    "samples_fraction": ("<samples>360</samples>", "<samples>24.5</samples>", "<samples>",
                         ["<samples>", "positive integer, got '24.5'"]),
    "min_angle_not_below_max": ("<max_angle>6.28319</max_angle>", "<max_angle>0</max_angle>",
                                "<max_angle>", ["sensor 'lds_lfcd_sensor' <max_angle>",
                                                "greater than min_angle 0"]),
    "range_min_negative": ("<min>0.120</min>", "<min>-0.1</min>", "<min>",
                           ["sensor 'lds_lfcd_sensor' <min>", "min -0.1 is outside [0, 1e+06] m"]),
    "range_min_over_max": ("<min>0.120</min>", "<min>4</min>", "<max>3.5",
                           ["<max>", "max 3.5 must be greater than min 4"]),
    "noise_negative": ("<stddev>0.01</stddev>", "<stddev>-0.01</stddev>", "<stddev>-",
                       ["sensor 'lds_lfcd_sensor' <stddev>", "stddev -0.01 is outside [0, 1000]"]),
    "noise_type": ("<type>gaussian</type>\n          <mean>", "<type>pink</type>\n          <mean>",
                   "<type>pink", ["<type>", "gaussian, gaussian_quantized, none", "'pink'"]),
    "sensor_rate_negative": ("<update_rate>5</update_rate>", "<update_rate>-5</update_rate>",
                             "<update_rate>", ["sensor 'lds_lfcd_sensor' <update_rate>",
                                               "update_rate -5 is outside [1e-06, 1e+06] Hz "
                                               "(or 0: every physics step)"]),
    "imu_rate_negative": ("<updateRate>200</updateRate>", "<updateRate>-1</updateRate>",
                          "<updateRate>-1", ["plugin 'imu_plugin'", "<updateRate>",
                                             "updateRate -1 is outside"]),
    "drive_rate_negative": ("<updateRate>30</updateRate>", "<updateRate>-30</updateRate>",
                            "<updateRate>-30", ["plugin 'turtlebot3_burger_controller'",
                                                "<updateRate>", "updateRate -30 is outside"]),
    "separation_zero": ("<wheelSeparation>0.160</wheelSeparation>",
                        "<wheelSeparation>0</wheelSeparation>", "<wheelSeparation>",
                        ["<wheelSeparation>", "wheelSeparation 0 is outside [0.01, 10000] m"]),
    "separation_not_a_number": ("<wheelSeparation>0.160</wheelSeparation>",
                                "<wheelSeparation>wide</wheelSeparation>", "<wheelSeparation>",
                                ["<wheelSeparation>", "must be a number, got 'wide'"]),
    "diameter_negative": ("<wheelDiameter>0.066</wheelDiameter>",
                          "<wheelDiameter>-0.066</wheelDiameter>", "<wheelDiameter>",
                          ["<wheelDiameter>", "wheelDiameter -0.066 is outside [0.01, 10000] m"]),
    "torque_zero": ("<wheelTorque>10</wheelTorque>", "<wheelTorque>0</wheelTorque>",
                    "<wheelTorque>", ["<wheelTorque>",
                                      "wheelTorque 0 must be positive, at most 1e+06 N m"]),
    "acceleration_negative": ("<wheelAcceleration>1</wheelAcceleration>",
                              "<wheelAcceleration>-1</wheelAcceleration>", "<wheelAcceleration>",
                              ["<wheelAcceleration>",
                               "wheelAcceleration -1 is outside [0, 1e+06] m/s^2"]),
    "acceleration_nan": ("<wheelAcceleration>1</wheelAcceleration>",
                         "<wheelAcceleration>nan</wheelAcceleration>", "<wheelAcceleration>",
                         ["<wheelAcceleration>", "must be a number, got 'nan'"]),
    "odometry_source": ("<odometrySource>world</odometrySource>",
                        "<odometrySource>gps</odometrySource>", "<odometrySource>",
                        ["<odometrySource>", "must be world or encoder, got 'gps'"]),
    "not_a_boolean": ("<publishTf>true</publishTf>", "<publishTf>yes</publishTf>", "<publishTf>",
                      ["plugin 'turtlebot3_burger_controller'", "<publishTf>",
                       "must be true or false, got 'yes'"]),
    "plugin_without_filename": ('filename="libgazebo_ros_imu.so"', "", 'name="imu_plugin"',
                                ["plugin 'imu_plugin'", "missing attribute 'filename'"]),
    "pose_five_numbers": ("<pose>0 0 0 0 0 0</pose>", "<pose>0 0 0 0 0</pose>", "<pose>",
                          ["sensor 'lds_lfcd_sensor' <pose>", "six numbers"]),
}
# the same, in the Burger with doc/robots.md's camera
BAD_CAMERA = {
    "width_zero": ("<width>640</width>", "<width>0</width>", "<width>",
                   ["sensor 'front_camera' <width>", "must be a positive integer, got '0'"]),
    "width_not_a_number": ("<width>640</width>", "<width>wide</width>", "<width>",
                           ["<width>", "positive integer, got 'wide'"]),
    "height_negative": ("<height>480</height>", "<height>-480</height>", "<height>",
                        ["<height>", "positive integer"]),
    "fov_too_wide": ("<horizontal_fov>1.085595</horizontal_fov>",
                     "<horizontal_fov>3.5</horizontal_fov>", "<horizontal_fov>",
                     ["sensor 'front_camera' <horizontal_fov>",
                      "horizontal_fov 3.5 is outside (0, 3.14159) rad"]),
    "fov_zero": ("<horizontal_fov>1.085595</horizontal_fov>",
                 "<horizontal_fov>0</horizontal_fov>", "<horizontal_fov>",
                 ["<horizontal_fov>", "horizontal_fov 0 is outside (0, 3.14159)"]),
    "near_beyond_far": ("<near>0.03</near>", "<near>200</near>", "<far>",
                        ["sensor 'front_camera' <far>", "far 100 must be greater than near 200"]),
    "camera_frame_not_a_link": ("<frameName>camera_optical_frame</frameName>",
                                "<frameName>camera_rgb_optical_frame</frameName>",
                                "<frameName>camera_rgb",
                                ["plugin 'camera_controller' (libgazebo_ros_camera.so) "
                                 "<frameName>", "'camera_rgb_optical_frame' is not a link"]),
    "camera_on_no_link": ('<gazebo reference="camera_link">', '<gazebo reference="camera">',
                          'reference="camera"', ["<gazebo reference='camera'>", "not a link"]),
    "camera_rate_negative": ("<update_rate>30</update_rate>", "<update_rate>-30</update_rate>",
                             "<update_rate>-30", ["sensor 'front_camera' <update_rate>",
                                                  "update_rate -30 is outside"]),
}

# Under abuse: every number of the plugin blocks is held to limits, refused at parse
# time in limits' wording, before anything is built (1e39 once half-added a robot and ended the
# sim; 16385 samples ended it at the first scan subscriber; wheelDiameter 1e-300 flipped it).
HUGE = {
    "range_max_1e39": ("<max>3.5</max>", "<max>1e39</max>", "<max>1e39",
                       ["sensor 'lds_lfcd_sensor' <max>", "max 1e+39 is outside [0, 1e+06] m"]),
    "range_min_1e300": ("<min>0.120</min>", "<min>1e300</min>", "<min>",
                        ["<min>", "min 1e+300 is outside [0, 1e+06] m"]),
    "range_resolution": ("<resolution>0.015</resolution>", "<resolution>1e300</resolution>",
                         "<resolution>1e300", ["<resolution>", "1e+300 is outside"]),
    "samples_16385": ("<samples>360</samples>", "<samples>16385</samples>", "<samples>",
                      ["sensor 'lds_lfcd_sensor' <samples>", "samples 16385 is outside [1, 3600]"]),
    "samples_3e8": ("<samples>360</samples>", "<samples>300000000</samples>", "<samples>",
                    ["<samples>", "samples 300000000 is outside [1, 3600]"]),
    "scan_resolution": ("<resolution>1</resolution>", "<resolution>1e300</resolution>",
                        "<resolution>1e300",
                        ["<resolution>", "resolution 1e+300 must be positive, at most 10000"]),
    "angle_1e300": ("<min_angle>0.0</min_angle>", "<min_angle>-1e300</min_angle>",
                    "<min_angle>", ["<min_angle>", "min_angle -1e+300 is outside [-1e+06, 1e+06] "
                                                   "rad"]),
    "laser_noise_1e200": ("<stddev>0.01</stddev>", "<stddev>1e200</stddev>", "<stddev>1e200",
                          ["<stddev>", "stddev 1e+200 is outside [0, 1000]"]),
    "laser_noise_mean": ("<mean>0.0</mean>\n          <stddev>0.01",
                         "<mean>1e300</mean>\n          <stddev>0.01", "<mean>1e300",
                         ["<mean>", "mean 1e+300 is outside [-1000, 1000]"]),
    "sensor_rate_tiny": ("<update_rate>5</update_rate>", "<update_rate>1e-300</update_rate>",
                         "<update_rate>", ["<update_rate>", "update_rate 1e-300 is outside "
                                                            "[1e-06, 1e+06] Hz"]),
    "sensor_rate_huge": ("<update_rate>5</update_rate>", "<update_rate>1e300</update_rate>",
                         "<update_rate>", ["<update_rate>", "1e+300 is outside"]),
    "sensor_pose": ("<pose>0 0 0 0 0 0</pose>", "<pose>1e300 0 0 0 0 0</pose>", "<pose>",
                    ["sensor 'lds_lfcd_sensor' <pose>", "pose.x 1e+300 is outside [-1e+06, "
                                                        "1e+06] m"]),
    "imu_noise_1e200": ("<gaussianNoise>0.0</gaussianNoise>",
                        "<gaussianNoise>1e200</gaussianNoise>", "<gaussianNoise>",
                        ["plugin 'imu_plugin' (libgazebo_ros_imu.so) <gaussianNoise>",
                         "gaussianNoise 1e+200 is outside [0, 1000]"]),
    "imu_rate_tiny": ("<updateRate>200</updateRate>", "<updateRate>1e-300</updateRate>",
                      "<updateRate>1e-300",
                      ["plugin 'imu_plugin'", "updateRate 1e-300 is outside"]),
    "diameter_1e-300": ("<wheelDiameter>0.066</wheelDiameter>",
                        "<wheelDiameter>1e-300</wheelDiameter>", "<wheelDiameter>",
                        ["<wheelDiameter>", "wheelDiameter 1e-300 is outside [0.01, 10000] m"]),
    "diameter_1e300": ("<wheelDiameter>0.066</wheelDiameter>",
                       "<wheelDiameter>1e300</wheelDiameter>", "<wheelDiameter>",
                       ["<wheelDiameter>", "1e+300 is outside [0.01, 10000] m"]),
    "separation_1e300": ("<wheelSeparation>0.160</wheelSeparation>",
                         "<wheelSeparation>1e300</wheelSeparation>", "<wheelSeparation>",
                         ["wheelSeparation 1e+300 is outside [0.01, 10000] m"]),
    "separation_1e-300": ("<wheelSeparation>0.160</wheelSeparation>",
                          "<wheelSeparation>1e-300</wheelSeparation>", "<wheelSeparation>",
                          ["wheelSeparation 1e-300 is outside [0.01, 10000] m"]),
    "torque_1e300": ("<wheelTorque>10</wheelTorque>", "<wheelTorque>1e300</wheelTorque>",
                     "<wheelTorque>", ["wheelTorque 1e+300 must be positive, at most 1e+06 N m"]),
    "acceleration_1e300": ("<wheelAcceleration>1</wheelAcceleration>",
                           "<wheelAcceleration>1e300</wheelAcceleration>", "<wheelAcceleration>",
                           ["wheelAcceleration 1e+300 is outside [0, 1e+06] m/s^2"]),
    "drive_rate_tiny": ("<updateRate>30</updateRate>", "<updateRate>1e-300</updateRate>",
                        "<updateRate>1e-300", ["plugin 'turtlebot3_burger_controller'",
                                               "updateRate 1e-300 is outside"]),
    "topic_not_a_ros_name": ("<topicName>scan</topicName>", "<topicName>my scan</topicName>",
                             "<topicName>my", ["<topicName>", "'my scan' is not a ROS name"]),
    "topic_too_long": ("<topicName>scan</topicName>", "<topicName>%s</topicName>" % ("s" * 300),
                       "<topicName>sss", ["<topicName>", "topicName is 300 characters, more "
                                                         "than the 256 allowed"]),
    "frame_too_long": ("<odometryFrame>odom</odometryFrame>",
                       "<odometryFrame>%s</odometryFrame>" % ("o" * 300), "<odometryFrame>",
                       ["odometryFrame is 300 characters, more than the 256 allowed"]),
    "plugin_name_too_long": ('name="imu_plugin"', 'name="%s"' % ("i" * 300), 'name="iii',
                             ["<plugin>: name is 300 characters, more than the 256 allowed"]),
}
HUGE_CAMERA = {
    "width_5000": ("<width>640</width>", "<width>5000</width>", "<width>",
                   ["sensor 'front_camera' <width>", "width 5000 is outside [1, 4096] px"]),
    "far_1e300": ("<far>100</far>", "<far>1e300</far>", "<far>",
                  ["<far>", "far 1e+300 must be positive, at most 1e+06 m"]),
    "camera_rate_tiny": ("<update_rate>30</update_rate>", "<update_rate>1e-300</update_rate>",
                         "<update_rate>1e-300", ["<update_rate>", "1e-300 is outside"]),
    "baseline_1e300": ("<cameraName>camera</cameraName>",
                       "<cameraName>camera</cameraName><hackBaseline>1e300</hackBaseline>",
                       "<cameraName>", ["<hackBaseline>", "hackBaseline 1e+300 is outside "
                                                          "[-10000, 10000] m"]),
}


def line_of(text, marker):
    """1-based line of the first ``marker`` in ``text``."""
    return text[:text.index(marker)].count("\n") + 1


def check_error(tmp_path, text, old, new, marker, words):
    path = edited(tmp_path, old, new, text)
    with pytest.raises(UrdfError) as err:
        read_urdf(path)
    message = str(err.value)
    assert "\n" not in message
    assert message.startswith("%s:%d: " % (path, line_of(path.read_text(), marker))), message
    for word in words:
        assert word in message, (word, message)


@pytest.mark.parametrize("case", list(BAD))
def test_bad_block_is_one_line_naming_file_line_and_element(tmp_path, case):
    check_error(tmp_path, burger_text(), *BAD[case])


@pytest.mark.parametrize("case", list(BAD_CAMERA))
def test_bad_camera_block_is_one_line_naming_file_line_and_element(tmp_path, case):
    check_error(tmp_path, with_camera(burger_text()), *BAD_CAMERA[case])


@pytest.mark.parametrize("case", list(HUGE))
def test_huge_tiny_and_long_values_are_refused_at_parse_time(tmp_path, case):
    check_error(tmp_path, burger_text(), *HUGE[case])


@pytest.mark.parametrize("case", list(HUGE_CAMERA))
def test_huge_camera_values_are_refused_at_parse_time(tmp_path, case):
    check_error(tmp_path, with_camera(burger_text()), *HUGE_CAMERA[case])


def test_ray_sensor_without_ray_is_an_error(tmp_path):
    text = burger_text().replace("</ray>", "</rays>")
    check_error(tmp_path, text, "<ray>", "<rays>", '<sensor type="ray"',
                ["sensor 'lds_lfcd_sensor'", "missing <ray>"])


def test_bad_second_laser_is_an_error_too(tmp_path):
    """A second laser is read as the first: a wrong value in it is an error."""
    second = """
  <gazebo reference="base_link">
    <sensor type="ray" name="rear">
      <ray><scan><horizontal><samples>x</samples></horizontal></scan></ray>
      <plugin name="rear_laser" filename="libgazebo_ros_laser.so"/>
    </sensor>
  </gazebo>
</robot>"""
    check_error(tmp_path, burger_text(), "</robot>", second, "<samples>x",
                ["sensor 'rear' <samples>", "'x'"])


# --- what is not simulated: one warning each, no error, the rest of the robot intact ------------

WARNED = {
    "unknown_plugin": (
        '<gazebo><plugin name="gripper" filename="libgazebo_ros_gripper.so"/></gazebo>',
        "plugin 'gripper' (libgazebo_ros_gripper.so) is not simulated here; the robot runs "
        "without it"),
    "unknown_sensor": (
        '<gazebo reference="base_link"><sensor type="contact" name="bumper"><contact>'
        '<collision>base_link_collision</collision></contact></sensor></gazebo>',
        "sensor 'bumper' (type contact) on link 'base_link' is not simulated here; the robot "
        "runs without it"),
    "wrong_kind_of_plugin": (
        '<gazebo reference="base_link"><sensor type="ray" name="front"><ray><range><max>2</max>'
        '</range><scan><horizontal><min_angle>-1</min_angle><max_angle>1</max_angle>'
        '</horizontal></scan></ray><plugin name="cam" filename="libgazebo_ros_camera.so"/>'
        '</sensor></gazebo>',
        "plugin 'cam' (libgazebo_ros_camera.so) on sensor 'front' (type ray) is of the wrong "
        'kind (it needs a <sensor type="camera">); the robot runs without it'),
    "sensor_plugin_outside_a_sensor": (
        '<gazebo><plugin name="laser" filename="libgazebo_ros_laser.so"/></gazebo>',
        "plugin 'laser' (libgazebo_ros_laser.so) is a sensor plugin outside any <sensor>"),
    "second_drive": (
        '<gazebo><plugin name="drive2" filename="libgazebo_ros_diff_drive.so">'
        '<leftJoint>wheel_left_joint</leftJoint><rightJoint>wheel_right_joint</rightJoint>'
        '</plugin></gazebo>',
        "plugin 'drive2' (libgazebo_ros_diff_drive.so): a second differential drive is not "
        "simulated here (only one per robot: 'turtlebot3_burger_controller' is)"),
    "plugin_on_a_link": (
        '<gazebo reference="base_link"><plugin name="p3d" filename="libgazebo_ros_p3d.so"/>'
        '</gazebo>',
        "plugin 'p3d' (libgazebo_ros_p3d.so) is inside <gazebo reference='base_link'>, where "
        "Gazebo loads no plugin"),
    "imu_sensor_plugin": (
        '<gazebo reference="imu_link"><sensor type="imu" name="imu2"><plugin name="imu_sensor" '
        'filename="libgazebo_ros_imu_sensor.so"/></sensor></gazebo>',
        "plugin 'imu_sensor' (libgazebo_ros_imu_sensor.so) is not simulated here"),
}


@pytest.mark.parametrize("case", list(WARNED))
def test_what_is_not_simulated_is_one_warning(tmp_path, case):
    block, warning = WARNED[case]
    robot = read_urdf(edited(tmp_path, "</robot>", block + "\n</robot>"))
    assert len(robot.plugins.warnings) == 1, robot.plugins.warnings
    assert robot.plugins.warnings[0].startswith(warning), robot.plugins.warnings
    assert "\n" not in robot.plugins.warnings[0]
    facts = FACTS["turtlebot3_burger.urdf"]
    assert (robot.plugins.drive, robot.plugins.laser, robot.plugins.imu) == (
        facts.drive, facts.laser, facts.imu)


SECOND_LASER = (
    '<gazebo reference="base_link"><sensor type="ray" name="rear"><ray><range><max>2</max>'
    '</range><scan><horizontal><min_angle>-1</min_angle><max_angle>1</max_angle>'
    '</horizontal></scan></ray><plugin name="rear_laser" filename="libgazebo_ros_laser.so">'
    '<topicName>rear_scan</topicName></plugin></sensor></gazebo>')


def test_a_second_laser_is_simulated_too(tmp_path):
    """Every laser runs, in file order; the first stays ``laser``."""
    plugins = read_urdf(edited(tmp_path, "</robot>", SECOND_LASER + "\n</robot>")).plugins
    assert plugins.warnings == ()
    assert plugins.laser == FACTS["turtlebot3_burger.urdf"].laser
    assert [laser.name for laser in plugins.lasers] == ["lds_lfcd_sensor", "rear"]
    rear = plugins.lasers[1]
    assert (rear.link, rear.topic, rear.plugin, rear.laser.range_max) == (
        "base_link", "rear_scan", "rear_laser", 2.0)


def test_a_second_camera_is_simulated_too(tmp_path):
    snippet = CAMERA_SNIPPET.replace("camera_", "front_")  # the Waffle Pi has camera_link
    text = (URDF / "turtlebot3_waffle_pi.urdf").read_text().replace("</robot>",
                                                                    snippet + "</robot>")
    plugins = read_urdf(write(tmp_path, text)).plugins
    assert plugins.camera == FACTS["turtlebot3_waffle_pi.urdf"].camera
    assert plugins.warnings == ()
    assert [c.name for c in plugins.cameras] == ["Pi Camera", "front_camera"]
    assert plugins.cameras[1].link == "front_link"


def test_the_first_and_the_list_agree():
    """RobotPlugins made with only the first laser or camera lists it; with only the lists,
    the first is theirs."""
    facts = FACTS["turtlebot3_waffle.urdf"]
    assert facts.lasers == (facts.laser,) and facts.cameras == (facts.camera,)
    listed = RobotPlugins(lasers=(LDS, LDS), cameras=(R200,))
    assert (listed.laser, listed.camera) == (LDS, R200)
    assert RobotPlugins().lasers == () and RobotPlugins().laser is None


def test_misspelt_parameter_is_warned_and_gazebos_default_used(tmp_path):
    path = edited(tmp_path, "<wheelSeparation>0.160</wheelSeparation>",
                  "<wheelSeperation>0.160</wheelSeperation>")
    plugins = read_urdf(path).plugins
    assert plugins.drive.wheel_separation == 0.34
    assert plugins.warnings == (
        "plugin 'turtlebot3_burger_controller' (libgazebo_ros_diff_drive.so): "
        "<wheelSeperation> is not a parameter of libgazebo_ros_diff_drive.so; ignored, as in "
        "Gazebo",)


def test_ray_sensor_without_ros_plugin_makes_no_laser_and_no_warning(tmp_path):
    """In Gazebo such a sensor talks only on Gazebo transport: no /scan."""
    text = burger_text()
    start = text.index('      <plugin name="gazebo_ros_lds_lfcd_controller"')
    end = text.index("</plugin>", start) + len("</plugin>\n")
    plugins = read_urdf(write(tmp_path, text[:start] + text[end:])).plugins
    assert plugins.laser is None
    assert plugins.warnings == ()


def test_noise_mean_and_several_planes_are_warned(tmp_path):
    text = burger_text().replace("<mean>0.0</mean>\n          <stddev>0.01",
                                 "<mean>0.1</mean>\n          <stddev>0.01")
    path = edited(tmp_path, "</horizontal>", "</horizontal>\n<vertical><samples>16</samples>"
                  "</vertical>", text)
    plugins = read_urdf(path).plugins
    assert plugins.laser.laser.noise_sigma == 0.01
    assert len(plugins.warnings) == 2
    assert "several vertical planes" in plugins.warnings[0]
    assert "noise <mean> 0.1 is not simulated" in plugins.warnings[1]


# --- a URDF as text (spawn_urdf_model) ------------------------------------------------------------

def test_read_urdf_text_reads_what_read_urdf_reads():
    text = (URDF / "turtlebot3_waffle.urdf").read_text()
    robot = read_urdf_text(text, "spawn_urdf_model tb3_3")
    assert robot.path == "spawn_urdf_model tb3_3"
    assert robot.plugins == FACTS["turtlebot3_waffle.urdf"]
    assert robot.links == read_urdf(URDF / "turtlebot3_waffle.urdf").links


def test_read_urdf_text_names_its_source_in_errors():
    text = burger_text().replace("<samples>360</samples>", "<samples>0</samples>")
    with pytest.raises(UrdfError) as err:
        read_urdf_text(text, "spawn_urdf_model tb3_3")
    assert str(err.value).startswith("spawn_urdf_model tb3_3:%d: sensor 'lds_lfcd_sensor' "
                                     "<samples>: " % line_of(text, "<samples>"))


@pytest.mark.parametrize("text, words", [
    ("", ["spawn_urdf_model tb3_3:1: malformed XML"]),
    ("<robot name='r'><link name='a'></robot>", ["spawn_urdf_model tb3_3:1: malformed XML",
                                                 "mismatched tag"]),
    ("<sdf version='1.6'/>", ["spawn_urdf_model tb3_3:1: <sdf>", "<robot>"]),
    (None, ["spawn_urdf_model tb3_3: the URDF must be text, not NoneType"]),
])
def test_read_urdf_text_bad_text(text, words):
    with pytest.raises(UrdfError) as err:
        read_urdf_text(text, "spawn_urdf_model tb3_3")
    for word in words:
        assert word in str(err.value)
    assert "\n" not in str(err.value)


def test_the_r200_reads_the_first_of_two_baselines():
    text = (URDF / "turtlebot3_waffle.urdf").read_text()
    assert text.index("<hackBaseline>0.07") < text.index("<hackBaseline>0<")
    assert math.isclose(read_urdf_text(text, "w").plugins.camera.spec.baseline, 0.07)
