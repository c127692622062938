#!/usr/bin/env python3
"""rostest node: turtlebot3_description's xacro files (the fixture package) expanded by xacro
and spawned by spawn_model into namespaces of the empty world, as a user of the real packages
does it; and a plain URDF whose visual and collision are a mesh.

ROS_PACKAGE_PATH holds test/fixtures (xacro_robots.test's <env>), so xacro here and the sim
find turtlebot3_description. Every wait is on wall time with a limit."""
import math
import os
import subprocess
import sys
import tempfile
import time

import rospy
import rostest
from gazebo_msgs.srv import SpawnModelRequest
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3
from nav_msgs.msg import Odometry
from sensor_msgs.msg import CameraInfo, Image, Imu, JointState, LaserScan

from sim_test_support import (WAIT, NodeProcess, Recorder, SimTestCase, one_message, publishers,
                              wait_for)

FIXTURES = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                         os.pardir, "fixtures"))
sys.path.insert(0, os.path.join(FIXTURES, "turtlebot3_description", "meshes"))
import make_meshes  # noqa: E402  (the fixture's STL writer)

# model -> (namespace, spawn x, y); facing +x, 2 m apart
ROBOTS = {"burger": ("burger", 0.0, 0.0), "waffle": ("waffle", 0.0, 2.0),
          "waffle_pi": ("waffle_pi", 0.0, -2.0)}
CAMERAS = {"waffle": ("camera/rgb/image_raw", "camera/rgb/camera_info",
                      "camera/depth/image_raw"),
           "waffle_pi": ("camera/rgb/image_raw", "camera/rgb/camera_info")}
CRATE = """<?xml version="1.0"?>
<robot name="crate">
  <link name="box">
    <inertial><mass value="2.0"/>
      <inertia ixx="0.0133" ixy="0" ixz="0" iyy="0.0133" iyz="0" izz="0.0133"/></inertial>
    <visual>
      <geometry><mesh filename="%(uri)s" scale="0.001 0.001 0.001"/></geometry>
      <material name="crate_red"><color rgba="0.7 0.2 0.1 1"/></material>
    </visual>
    <collision>
      <geometry><mesh filename="%(uri)s" scale="0.001 0.001 0.001"/></geometry>
    </collision>
  </link>
</robot>"""


def xacro(command, model):
    """robot_description of ``model`` by xacro (``command``: the program, as a user calls it)
    from the fixture's turtlebot3_description: (URDF text, wall seconds)."""
    package = subprocess.run(["rospack", "find", "turtlebot3_description"], check=True,
                             capture_output=True, text=True).stdout.strip()
    source = os.path.join(package, "urdf", "turtlebot3_%s.urdf.xacro" % model)
    start = time.monotonic()
    done = subprocess.run(command + ["--inorder", source], capture_output=True, text=True,
                          timeout=WAIT)
    assert done.returncode == 0, done.stderr
    return done.stdout, time.monotonic() - start


class XacroRobots(SimTestCase):

    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        xacro_dir = subprocess.run(["rospack", "find", "xacro"], check=True,
                                   capture_output=True, text=True).stdout.strip()
        commands = {"burger": ["rosrun", "xacro", "xacro"],
                    "waffle": [os.path.join(xacro_dir, "xacro")],     # $(find xacro)/xacro
                    "waffle_pi": ["rosrun", "xacro", "xacro"]}
        cls.timing = {}
        for model, (ns, x, y) in ROBOTS.items():
            urdf, xacro_s = xacro(commands[model], model)
            rospy.set_param("/%s/robot_description" % ns, urdf)
            start = time.monotonic()
            spawn = NodeProcess("spawn_model", "-urdf", "-param", "/%s/robot_description" % ns,
                                "-model", "tb3_" + model, "-robot_namespace", ns,
                                "-x", str(x), "-y", str(y))
            status = spawn.wait(WAIT)
            assert status == 0, spawn.stdout + spawn.stderr
            cls.timing[model] = (xacro_s, time.monotonic() - start)
        for model, (xacro_s, spawn_s) in cls.timing.items():
            print("%s: xacro %.2f s, spawn_model %.2f s (wall)" % (model, xacro_s, spawn_s))
        cls.odom = {m: Recorder("/%s/odom" % ns, Odometry) for m, (ns, _, _) in ROBOTS.items()}

    def test_1_each_robot_publishes_in_its_namespace_with_its_plugins_frames(self):
        names = self.gz.names()
        for model, (ns, x, y) in ROBOTS.items():
            self.assertIn("tb3_" + model, names)
            odom = self.odom[model].latest(WAIT)
            self.assertIsNotNone(odom, "no /%s/odom" % ns)
            self.assertEqual((odom.header.frame_id, odom.child_frame_id),
                             ("%s/odom" % ns, "%s/base_footprint" % ns))
            self.assertAlmostEqual(odom.pose.pose.position.x, x, delta=0.05)
            self.assertAlmostEqual(odom.pose.pose.position.y, y, delta=0.05)
            z = self.gz.position("tb3_" + model)[2]
            self.assertAlmostEqual(z, 0.0, delta=0.005)          # on its wheels
            scan = one_message("/%s/scan" % ns, LaserScan)
            self.assertEqual((scan.header.frame_id, len(scan.ranges)), ("%s/base_scan" % ns, 360))
            imu = one_message("/%s/imu" % ns, Imu)
            self.assertEqual(imu.header.frame_id, "%s/imu_link" % ns)
            joints = one_message("/%s/joint_states" % ns, JointState)
            self.assertEqual(list(joints.name), ["wheel_left_joint", "wheel_right_joint"])
            for topic in ("scan", "imu", "odom", "joint_states"):
                self.assertEqual(publishers("/%s/%s" % (ns, topic)), ["/gazebo"], topic)
            for topic in CAMERAS.get(model, ()):
                msg_type = CameraInfo if topic.endswith("camera_info") else Image
                msg = one_message("/%s/%s" % (ns, topic), msg_type)
                self.assertIsNotNone(msg, topic)
                self.assertEqual(msg.header.frame_id, "%s/camera_rgb_optical_frame" % ns)
            if model == "burger":
                self.assertEqual(publishers("/%s/camera/rgb/image_raw" % ns), [])
        self.assertEqual(publishers("/scan"), [])     # nothing in the root namespace

    def test_2_a_mesh_crate_falls_rests_on_its_mesh_and_is_seen(self):
        """spawn_urdf_model: a 0.2 m cube whose visual and collision are one STL (file://),
        dropped from 0.5 m 1 m ahead of the burger: it rests with its centre 0.1 m up, and the
        burger's laser, 0.032 m behind base_footprint, sees its face 0.93 m ahead."""
        folder = tempfile.mkdtemp(prefix="xacro_robots_test_")
        stl = os.path.join(folder, "crate.stl")
        make_meshes.write_stl(stl, make_meshes.box((-100, -100, -100), (100, 100, 100)), "crate")
        request = SpawnModelRequest(model_name="crate", model_xml=CRATE % {"uri": "file://" + stl},
                                    initial_pose=Pose(position=Point(1.0, 0.0, 0.5),
                                                      orientation=Quaternion(0, 0, 0, 1)))
        resp = self.gz.spawn_urdf_model(request)
        self.assertTrue(resp.success, resp.status_message)
        try:
            self.assertTrue(wait_for(lambda: abs(self.gz.position("crate")[2] - 0.1) < 0.003
                                     and self._still("crate"), WAIT),
                            self.gz.position("crate"))
            x, y, _ = self.gz.position("crate")
            self.assertAlmostEqual(x, 1.0, delta=0.01)
            self.assertAlmostEqual(y, 0.0, delta=0.01)
            scan = one_message("/burger/scan", LaserScan)
            ahead = [scan.ranges[i] for i in (-1, 0, 1)]
            self.assertLess(min(abs(r - 0.932) for r in ahead), 0.04, ahead)
        finally:
            self.gz.delete_model(model_name="crate")
            os.unlink(stl)
            os.rmdir(folder)

    def _still(self, name):
        resp = self.gz.get_model_state(model_name=name)
        v = resp.twist.linear
        return math.sqrt(v.x ** 2 + v.y ** 2 + v.z ** 2) < 0.01

    def test_3_the_waffle_pi_drives_by_its_cmd_vel(self):
        """0.2 m/s on /waffle_pi/cmd_vel for 3 s of wall time: its odom moves along +x."""
        ns = ROBOTS["waffle_pi"][0]
        cmd = rospy.Publisher("/%s/cmd_vel" % ns, Twist, queue_size=1)
        self.assertTrue(wait_for(lambda: cmd.get_num_connections() > 0, WAIT))
        start = self.odom["waffle_pi"].latest(WAIT).pose.pose.position
        deadline = time.monotonic() + 3.0
        while time.monotonic() < deadline:
            cmd.publish(Twist(linear=Vector3(0.2, 0.0, 0.0)))
            time.sleep(0.1)
        cmd.publish(Twist())
        time.sleep(0.5)
        end = self.odom["waffle_pi"].latest(WAIT).pose.pose.position
        self.assertGreater(end.x - start.x, 0.3)
        self.assertLess(abs(end.y - start.y), 0.05)
        self.assertAlmostEqual(self.gz.position("tb3_waffle_pi")[0], end.x, delta=0.05)

    def test_4_xacro_from_a_launch_file(self):
        """<param command="$(find xacro)/xacro ..."> in xacro_robots.test: the expanded text."""
        text = rospy.get_param("/xacro_check")
        self.assertIn('<material name="orange">', text)
        self.assertIn('rgba="1.0 0.4235294117647059 0.0392156862745098 1.0"', text)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "xacro_robots", XacroRobots)
