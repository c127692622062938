#!/usr/bin/env python3
"""rostest node: the rest of Gazebo's world API on /gazebo (Burger in the empty world, real
time): wrenches, efforts, link and joint properties, set_model_configuration (and
spawn_model -J), lights, ~performance_metrics and geom_names.

Every wait is on wall time with a limit. Each test deletes what it spawned."""
import math
import os
import subprocess
import tempfile
import time

import rospy
import rostest
from gazebo_msgs.msg import PerformanceMetrics
from gazebo_msgs.srv import (ApplyBodyWrench, ApplyJointEffort, BodyRequest, GetJointProperties,
                             GetJointPropertiesResponse, GetLightProperties, GetLinkProperties,
                             JointRequest, SetLightProperties, SetLinkProperties,
                             SetModelConfiguration)
from geometry_msgs.msg import Point, Vector3, Wrench
from sensor_msgs.msg import Imu, LaserScan
from std_msgs.msg import ColorRGBA

from sim_test_support import ROBOT, Recorder, SimTestCase, executable, pose, wait_for
from sim_test_support import SHORT_WAIT as WAIT

BOX = """<sdf version="1.6"><model name="box"><link name="link">
  <inertial><mass>2</mass><inertia><ixx>0.0075</ixx><iyy>0.0075</iyy><izz>0.0075</izz></inertia></inertial>
  <collision name="collision"><geometry><box><size>0.15 0.15 0.15</size></box></geometry>\
</collision>
</link></model></sdf>"""
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "fixtures",
                       "wheel.urdf")) as _f:
    WHEEL = _f.read().rstrip("\n")   # a disc on a vertical joint over a heavy base
SERVICES = {"apply_body_wrench": ApplyBodyWrench, "clear_body_wrenches": BodyRequest,
            "apply_joint_effort": ApplyJointEffort, "clear_joint_forces": JointRequest,
            "get_link_properties": GetLinkProperties, "set_link_properties": SetLinkProperties,
            "get_joint_properties": GetJointProperties,
            "set_model_configuration": SetModelConfiguration,
            "get_light_properties": GetLightProperties, "set_light_properties": SetLightProperties}
MODELS = ("box", "wheel", "wheel2")


class WorldApiMoreTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        for name, srv in SERVICES.items():
            rospy.wait_for_service("/gazebo/" + name, timeout=WAIT)
            setattr(cls, name, rospy.ServiceProxy("/gazebo/" + name, srv))
        assert cls.gz.wait_names(lambda n: ROBOT in n, WAIT), cls.gz.names()

    def tearDown(self):
        for name in MODELS:
            self.gz.delete_model(model_name=name)
        self.gz.unpause_physics()

    def spawn(self, name, xml, where, kind="sdf"):
        spawner = self.gz.spawn_sdf_model if kind == "sdf" else self.gz.spawn_urdf_model
        resp = spawner(model_name=name, model_xml=xml, robot_namespace="", initial_pose=where,
                       reference_frame="")
        self.assertTrue(resp.success, resp.status_message)

    def twist(self, name):
        resp = self.gz.get_model_state(model_name=name)
        self.assertTrue(resp.success, resp.status_message)
        return resp.twist

    def spawn_weightless_box(self, where):
        """A 2 kg box in the air that stays there: paused while it is spawned and set."""
        self.gz.pause_physics()
        self.spawn("box", BOX, where)
        self.weightless("box::link")
        self.gz.unpause_physics()

    def weightless(self, link):
        p = self.get_link_properties(link_name=link)
        self.assertTrue(p.success, p.status_message)
        resp = self.set_link_properties(link_name=link, com=p.com, gravity_mode=False,
                                        mass=p.mass, ixx=p.ixx, ixy=p.ixy, ixz=p.ixz, iyy=p.iyy,
                                        iyz=p.iyz, izz=p.izz)
        self.assertTrue(resp.success, resp.status_message)
        self.assertEqual(resp.status_message, "SetLinkProperties: properties set")

    # --- wrenches ------------------------------------------------------------------------------

    def test_body_wrench_pushes_a_weightless_box_then_stops(self):
        self.spawn_weightless_box(pose(1.0, 1.0, 1.0))
        p = self.get_link_properties(link_name="box::link")
        self.assertFalse(p.gravity_mode)
        self.assertAlmostEqual(p.mass, 2.0, places=6)
        self.assertEqual(p.status_message, "GetLinkProperties: got properties")
        resp = self.apply_body_wrench(body_name="box::link", reference_frame="world",
                                      reference_point=Point(0, 0, 0),
                                      wrench=Wrench(force=Vector3(4.0, 0, 0),
                                                    torque=Vector3(0, 0, 0.015)),
                                      start_time=rospy.Time(0),
                                      duration=rospy.Duration(0.5))
        self.assertTrue(resp.success, resp.status_message)
        self.assertEqual(resp.status_message, "")       # as Gazebo
        # a = 2 m/s^2 and alpha = 2 rad/s^2 for 0.5 s of sim time: then 1 m/s and 1 rad/s
        self.assertTrue(wait_for(lambda: self.twist("box").linear.x > 0.99, WAIT))
        time.sleep(1.0)
        twist = self.twist("box")
        self.assertAlmostEqual(twist.linear.x, 1.0, delta=0.02)
        self.assertAlmostEqual(twist.angular.z, 1.0, delta=0.03)
        self.assertAlmostEqual(self.gz.position("box")[2], 1.0, delta=0.01)

    def test_a_wrench_until_cleared(self):
        self.spawn_weightless_box(pose(-1.0, 1.0, 1.0))
        resp = self.apply_body_wrench(body_name="box::link", reference_frame="",
                                      wrench=Wrench(force=Vector3(0, 0.4, 0)),
                                      duration=rospy.Duration(-1))
        self.assertTrue(resp.success, resp.status_message)
        self.assertTrue(wait_for(lambda: self.twist("box").linear.y > 0.05, WAIT))
        self.clear_body_wrenches(body_name="box::link")
        speed = self.twist("box").linear.y
        time.sleep(0.5)
        self.assertAlmostEqual(self.twist("box").linear.y, speed, delta=0.01)

    # --- joints --------------------------------------------------------------------------------

    def test_joint_effort_and_properties(self):
        self.spawn("wheel", WHEEL, pose(1.5, -1.0, 0.06), kind="urdf")
        props = self.gz.get_model_properties(model_name="wheel")
        self.assertEqual(list(props.geom_names), ["base_collision", "disc_collision"])
        resp = self.apply_joint_effort(joint_name="spin", effort=0.02,
                                       start_time=rospy.Time(0), duration=rospy.Duration(1.0))
        self.assertTrue(resp.success)
        self.assertEqual(resp.status_message, "ApplyJointEffort: effort set")

        def rate():
            j = self.get_joint_properties(joint_name="spin")
            self.assertTrue(j.success, j.status_message)
            return j.rate[0]
        self.assertTrue(wait_for(lambda: rate() > 0.95, WAIT), rate())   # 1 rad/s^2 for 1 s
        time.sleep(0.5)
        self.assertAlmostEqual(rate(), 1.0, delta=0.06)
        j = self.get_joint_properties(joint_name="wheel::spin")
        self.assertEqual(j.type, GetJointPropertiesResponse.REVOLUTE)
        self.assertEqual(j.status_message, "GetJointProperties: got properties")
        self.assertEqual((len(j.damping), len(j.position), len(j.rate)), (1, 1, 1))
        self.assertTrue(self.apply_joint_effort(joint_name="spin", effort=-0.02,
                                                duration=rospy.Duration(-1)).success)
        self.assertTrue(wait_for(lambda: rate() < 0.7, WAIT))
        self.clear_joint_forces(joint_name="spin")
        now = rate()
        time.sleep(0.5)
        self.assertAlmostEqual(rate(), now, delta=0.03)

    def test_robot_wheel_joint_properties_and_configuration(self):
        j = self.get_joint_properties(joint_name="wheel_left_joint")
        self.assertTrue(j.success, j.status_message)
        self.assertEqual(j.type, GetJointPropertiesResponse.REVOLUTE)
        resp = self.set_model_configuration(model_name=ROBOT, urdf_param_name="whatever",
                                            joint_names=["wheel_left_joint"],
                                            joint_positions=[j.position[0] + 1.0])
        self.assertTrue(resp.success, resp.status_message)
        self.assertEqual(resp.status_message, "SetModelConfiguration: success")
        after = self.get_joint_properties(joint_name="wheel_left_joint").position[0]
        self.assertAlmostEqual(after, j.position[0] + 1.0, delta=0.05)

    def test_spawn_model_J_sets_a_joint(self):
        with tempfile.NamedTemporaryFile("w", suffix=".urdf", delete=False) as f:
            f.write(WHEEL)
        try:
            done = subprocess.run([executable("spawn_model"), "-urdf", "-file", f.name,
                                   "-model", "wheel2", "-x", "-1.5", "-y", "-1", "-z", "0.06",
                                   "-J", "spin", "1.2"],
                                  capture_output=True, text=True, timeout=60)
        finally:
            os.unlink(f.name)
        self.assertEqual(done.returncode, 0, done.stdout + done.stderr)
        self.assertIn("Set model configuration status: SetModelConfiguration: success",
                      done.stdout)
        j = self.get_joint_properties(joint_name="wheel2::spin")
        self.assertAlmostEqual(j.position[0], 1.2, delta=0.02)

    # --- lights, geoms -------------------------------------------------------------------------

    def test_sun_light_properties(self):
        sun = self.get_light_properties(light_name="sun")
        self.assertTrue(sun.success, sun.status_message)
        self.assertAlmostEqual(sun.diffuse.r, 0.8, places=6)
        self.assertAlmostEqual(sun.attenuation_constant, 0.9, places=6)
        resp = self.set_light_properties(light_name="sun", cast_shadows=True,
                                         diffuse=ColorRGBA(0.5, 0.4, 0.3, 1.0),
                                         specular=ColorRGBA(0.2, 0.2, 0.2, 1.0),
                                         attenuation_constant=0.7, attenuation_linear=0.02,
                                         attenuation_quadratic=0.003,
                                         direction=Vector3(-0.5, 0.1, -0.9), pose=pose(0, 0, 10))
        self.assertTrue(resp.success, resp.status_message)
        sun = self.get_light_properties(light_name="sun")
        self.assertEqual((round(sun.diffuse.r, 6), round(sun.diffuse.g, 6)), (0.5, 0.4))
        self.assertEqual((round(sun.attenuation_constant, 6), round(sun.attenuation_linear, 6),
                          round(sun.attenuation_quadratic, 6)), (0.7, 0.02, 0.003))
        moon = self.get_light_properties(light_name="moon")
        self.assertFalse(moon.success)
        self.assertEqual(moon.status_message, "getLightProperties: Requested light moon not found!")

    def test_robot_geom_names(self):
        props = self.gz.get_model_properties(model_name=ROBOT)
        self.assertTrue(props.success)
        self.assertEqual(list(props.geom_names), [
            "base_footprint_fixed_joint_lump__base_link_collision",
            "base_footprint_fixed_joint_lump__caster_back_link_collision_1",
            "base_footprint_fixed_joint_lump__base_scan_collision_2",
            "wheel_left_link_collision", "wheel_right_link_collision"])

    # --- performance_metrics -------------------------------------------------------------------

    def test_performance_metrics(self):
        scan, imu = Recorder("scan", LaserScan), Recorder("imu", Imu)   # readings are made
        metrics = Recorder("/gazebo/performance_metrics", PerformanceMetrics)
        try:
            self.assertTrue(wait_for(lambda: len(metrics.msgs) >= 4, WAIT), len(metrics.msgs))
            msgs, arrived = metrics.snapshot()
        finally:
            for recorder in (scan, imu, metrics):
                recorder.sub.unregister()
        last = msgs[-1]
        # about once a wall second, stamped with sim time (real time: a second apart too)
        gaps = [(b.header.stamp - a.header.stamp).to_sec() for a, b in zip(msgs, msgs[1:])]
        self.assertTrue(all(0.6 < g < 1.5 for g in gaps), gaps)
        self.assertAlmostEqual(last.real_time_factor, 1.0, delta=0.25)
        sensors = {s.name: s for s in last.sensors}
        laser = sensors.get("default::%s::base_footprint::lds_lfcd_sensor" % ROBOT)
        gyro = sensors.get("default::%s::base_footprint::imu_plugin" % ROBOT)
        self.assertIsNotNone(laser, list(sensors))
        self.assertIsNotNone(gyro, list(sensors))
        self.assertEqual(len(sensors), 2, list(sensors))     # no camera on a burger
        self.assertAlmostEqual(laser.sim_update_rate, 5.0, delta=1.5)
        self.assertAlmostEqual(gyro.sim_update_rate, 200.0, delta=25.0)
        self.assertAlmostEqual(gyro.real_update_rate,
                               gyro.sim_update_rate * last.real_time_factor, delta=25.0)
        self.assertEqual((laser.fps, gyro.fps), (-1.0, -1.0))

    # --- failures ------------------------------------------------------------------------------

    def test_failure_answers(self):
        nan = float("nan")
        for resp, text in [
                (self.apply_body_wrench(body_name="nobody::link",
                                        wrench=Wrench(force=Vector3(1, 0, 0))),
                 "ApplyBodyWrench: body does not exist"),
                (self.apply_body_wrench(body_name=ROBOT + "::base_footprint",
                                        wrench=Wrench(force=Vector3(nan, 0, 0))),
                 "ApplyBodyWrench: NaN or infinite value in the wrench or the reference point"),
                (self.apply_body_wrench(body_name=ROBOT + "::base_footprint",
                                        reference_frame="moon"),
                 "ApplyBodyWrench: reference_frame not found"),
                (self.apply_joint_effort(joint_name="elbow", effort=1.0),
                 "ApplyJointEffort: joint not found"),
                (self.set_link_properties(link_name=ROBOT + "::wheel_left_link", mass=-1.0,
                                          ixx=1, iyy=1, izz=1),
                 "SetLinkProperties: mass -1 kg must be > 0"),
                (self.get_link_properties(link_name="wheel_left_link"),
                 "GetLinkProperties: link not found, did you forget to scope the link by model "
                 "name?"),
                (self.get_joint_properties(joint_name="elbow"),
                 "GetJointProperties: joint not found"),
                (self.set_model_configuration(model_name=ROBOT, joint_names=["wheel_left_joint"],
                                              joint_positions=[]),
                 "SetModelConfiguration: joint name and position list have different lengths"),
                (self.set_model_configuration(model_name="nobody"),
                 "SetModelConfiguration: model does not exist"),
                (self.set_light_properties(light_name="moon"),
                 "setLightProperties: Requested light moon not found!")]:
            self.assertFalse(resp.success, text)
            self.assertEqual(resp.status_message, text)
        # the robot is as it was: not pushed, its wheel's mass unchanged
        self.assertLess(math.hypot(*self.gz.position(ROBOT)[:2]), 0.05)
        self.assertGreater(self.get_link_properties(
            link_name=ROBOT + "::wheel_left_link").mass, 0.0)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "world_api_more", WorldApiMoreTest)
