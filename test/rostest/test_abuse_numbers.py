#!/usr/bin/env python3
"""rostest node: numbers beyond the world's limits (sim/limits) through the real /gazebo
services and the /gazebo/set_model_state topic. Each is refused with one line naming the
field (or, a huge quaternion, normalised); the robot, /odom and /scan stay finite; reset_world
puts the robot back at its spawn on the floor. Every wait is on wall time with a limit."""
import math
import time

import rospy
import rostest
from gazebo_msgs.msg import ModelState, ODEPhysics
from geometry_msgs.msg import Point, Pose, Quaternion, Twist, Vector3
from sensor_msgs.msg import LaserScan

from sim_test_support import ROBOT, Driver, Recorder, SimTestCase, wait_for
from sim_test_support import SHORT_WAIT as WAIT

SPAWN = (-2.0, -0.5)
NAN = float("nan")


def pose(x, y, z=0.0, q=(0.0, 0.0, 0.0, 1.0)):
    return Pose(position=Point(x, y, z), orientation=Quaternion(*q))


def twist(linear=(0, 0, 0), angular=(0, 0, 0)):
    return Twist(linear=Vector3(*linear), angular=Vector3(*angular))


def box_sdf(size="0.2 0.2 0.2", mass="1"):
    return ("<sdf version='1.6'><model name='b'><link name='link'><inertial><mass>%s</mass>"
            "</inertial><collision name='c'><geometry><box><size>%s</size></box></geometry>"
            "</collision></link></model></sdf>" % (mass, size))


def urdf(mass="1", ixx="1", size="0.2 0.2 0.2"):
    return ('<robot name="u"><link name="l"><inertial><mass value="%s"/><inertia ixx="%s" '
            'iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry>'
            '<box size="%s"/></geometry></collision></link></robot>' % (mass, ixx, size))


def finite(*values):
    return all(math.isfinite(v) for v in values)


class AbuseNumbersTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.drive = Driver()
        cls.scan = Recorder("scan", LaserScan)
        assert cls.drive.odom.latest(WAIT) is not None, "no odom"
        cls.topic = rospy.Publisher("/gazebo/set_model_state", ModelState, queue_size=10)
        wait_for(lambda: cls.topic.get_num_connections() > 0, 20.0)

    def tearDown(self):
        self.drive.send(0.0, 0.0)
        for name in ("far", "heavy", "big", "u", "chain"):
            self.gz.delete_model(model_name=name)
        self.gz.reset_world()

    def refused(self, resp, field):
        self.assertFalse(resp.success, resp.status_message)
        self.assertIn(field, resp.status_message)
        self.assertNotIn("\n", resp.status_message)
        self.assertNotIn("did not answer", resp.status_message)

    def assert_world_finite(self):
        """The robot's state, /odom, /gazebo/model_states and /scan are finite now."""
        time.sleep(1.0)
        resp = self.gz.get_model_state(model_name=ROBOT)
        p, q, v = resp.pose.position, resp.pose.orientation, resp.twist.linear
        self.assertTrue(finite(p.x, p.y, p.z, q.x, q.y, q.z, q.w, v.x, v.y, v.z), resp)
        odom = self.drive.odom.latest(WAIT).pose.pose.position
        self.assertTrue(finite(odom.x, odom.y, odom.z))
        for state in self.gz.latest_states().pose:
            self.assertTrue(finite(state.position.x, state.position.y, state.position.z))
        start = rospy.Time.now()
        scan = self.scan.after(start, WAIT)
        self.assertIsNotNone(scan, "no /scan")
        self.assertTrue(any(math.isfinite(r) for r in scan.ranges), "no finite range in /scan")

    def assert_at_spawn(self):
        self.gz.reset_world()
        time.sleep(2.5)      # a broken body would have fallen through the floor by now
        x, y, z = self.gz.position(ROBOT)
        self.assertAlmostEqual(x, SPAWN[0], delta=0.02)
        self.assertAlmostEqual(y, SPAWN[1], delta=0.02)
        self.assertLess(abs(z), 0.02)

    def test_set_model_state_refuses_huge_numbers(self):
        for t, field in ((twist(linear=(1e200, 0, 0)), "twist.linear.x"),
                         (twist(angular=(0, 0, 1e308)), "twist.angular.z")):
            self.refused(self.gz.set_model_state(ModelState(ROBOT, pose(*SPAWN), t, "")),
                         field)
        self.refused(self.gz.set_model_state(ModelState(ROBOT, pose(1e308, 0), twist(), "")),
                     "pose.position.x")
        for component in (1e155, 1e200, 1e308):   # normalised without overflow
            resp = self.gz.set_model_state(ModelState(
                ROBOT, pose(*SPAWN, 0.0, (0, 0, component, component)), twist(), ""))
            self.assertTrue(resp.success, resp.status_message)
        self.assert_world_finite()
        self.assert_at_spawn()

    def test_the_topic_ignores_huge_numbers(self):
        for t in (twist(linear=(1e308, 0, 0)), twist(angular=(1e200, 0, 0))):
            self.topic.publish(ModelState(ROBOT, pose(*SPAWN), t, ""))
        self.topic.publish(ModelState(ROBOT, pose(*SPAWN, 0.0, (1e308, 0, 0, 1e308)),
                                      twist(), ""))
        self.assert_world_finite()
        self.assert_at_spawn()

    def test_spawns_with_huge_or_bad_numbers_are_refused(self):
        far = pose(1e308, 0, 0)
        here = pose(1.5, 1.5, 0.5)
        self.refused(self.gz.spawn_sdf_model("far", box_sdf(), "", far, ""),
                     "initial_pose.position.x")
        self.refused(self.gz.spawn_sdf_model("heavy", box_sdf(mass="1e308"), "", here, ""),
                     "<mass>")
        self.refused(self.gz.spawn_sdf_model("big", box_sdf(size="1e308 1 1"), "", here, ""),
                     "<size>")
        for xml, field in ((urdf(mass="-1"), "mass"), (urdf(mass="nan"), "mass"),
                           (urdf(ixx="-1"), "ixx"), (urdf(ixx="nan"), "ixx"),
                           (urdf(size="nan 1 1"), "size"), (urdf(size="-1 1 1"), "size")):
            self.refused(self.gz.spawn_urdf_model("u", xml, "", here, ""), field)
        self.assertTrue(self.gz.wait_names(lambda names: "u" not in names and "big" not in names))
        self.assert_world_finite()
        self.assert_at_spawn()

    def test_physics_properties_refuse_out_of_range_fields(self):
        now = self.gz.get_physics_properties()
        ode = now.ode_config
        bad = ODEPhysics(ode.auto_disable_bodies, ode.sor_pgs_precon_iters, 4294967295,
                         ode.sor_pgs_w, ode.sor_pgs_rms_error_tol, ode.contact_surface_layer,
                         ode.contact_max_correcting_vel, ode.cfm, ode.erp, ode.max_contacts)
        self.refused(self.gz.set_physics_properties(now.time_step, now.max_update_rate,
                                                    now.gravity, bad), "sor_pgs_iters")
        self.refused(self.gz.set_physics_properties(now.time_step, now.max_update_rate,
                                                    Vector3(0, 0, -1e300), ode), "gravity.z")
        self.assertEqual(self.gz.get_physics_properties().ode_config.sor_pgs_iters,
                         ode.sor_pgs_iters)
        self.assert_world_finite()

    def test_cmd_vel_of_1e9_is_clamped(self):
        self.drive.send(1e9, -1e9)
        time.sleep(1.0)
        self.drive.send(0.0, 0.0)
        self.assert_world_finite()
        self.assert_at_spawn()

    def test_a_long_one_line_urdf_spawns(self):
        links = "".join('<link name="l%d"><inertial><mass value="0.1"/><inertia ixx="0.001" '
                        'iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>'
                        '<collision><geometry><box size="0.05 0.05 0.05"/></geometry>'
                        '</collision></link>' % i for i in range(100))
        joints = "".join('<joint name="j%d" type="fixed"><parent link="l%d"/><child '
                         'link="l%d"/><origin xyz="0.005 0 0"/></joint>' % (i, i - 1, i)
                         for i in range(1, 100))
        xml = '<robot name="chain">%s%s</robot>' % (links, joints)
        self.assertGreater(len(xml), 30000)
        resp = self.gz.spawn_urdf_model("chain", xml, "", pose(1.5, 1.5, 1.0), "")
        self.assertTrue(resp.success, resp.status_message)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_abuse_numbers", AbuseNumbersTest)
