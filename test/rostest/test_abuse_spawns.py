#!/usr/bin/env python3
"""rostest node: spawns that once killed, froze or choked the sim, through the real /gazebo
services. Each is answered in one line naming the file, line or field, and the sim
lives on: its clock runs, its robot's /odom and /scan keep coming, the world API answers, and
nothing of the refused model is left. A world whose model.config is /dev/zero ends a sim's
start-up in one line. Every wait is on wall time with a limit."""
import math
import os
import shutil
import subprocess
import tempfile
import time

import rospkg
import rospy
import rostest
from geometry_msgs.msg import Point, Pose, Quaternion
from rosgraph_msgs.msg import Clock
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan

from sim_test_support import SHORT_WAIT, NodeProcess, Recorder, SimTestCase, free_port, wait_for

ANSWER = 8.0      # wall s: a refusal comes at once; the node gives up on its loop after 10 s
PACKAGE = rospkg.RosPack().get_path("tutorial_turtlebot")
with open(os.path.join(PACKAGE, "urdf", "turtlebot3_burger.urdf")) as _f:
    BURGER = _f.read()
NAMES = ("tb3", "tb3_a", "tb3_b", "cabinet", "painted")


def burger(*edits):
    """The Burger's URDF with each (old, new) made (old must be there once)."""
    text = BURGER
    for old, new in edits:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    return text


def pose(x, y, z=0.0):
    return Pose(position=Point(x, y, z), orientation=Quaternion(0, 0, 0, 1))


def sdf_with(body):
    return ("<sdf version='1.6'><model name='m'><static>true</static><link name='l'>%s</link>"
            "</model></sdf>" % body)


class AbuseSpawnsTest(SimTestCase):
    @classmethod
    def setUpClass(cls):
        super().setUpClass()
        cls.odom = Recorder("odom", Odometry)
        cls.scan = Recorder("scan", LaserScan)
        assert cls.odom.latest(SHORT_WAIT) is not None, "no odom"
        cls.tmp = tempfile.mkdtemp(prefix="abuse_spawns_")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.tmp, ignore_errors=True)

    def tearDown(self):
        for name in NAMES:
            try:
                self.gz.delete_model(model_name=name)
            except rospy.ServiceException:
                pass

    def refused(self, call, name, *words):
        """``call()`` is answered within ANSWER wall s, success False, one line holding
        ``words``; then the sim is alive and model ``name`` is not in it."""
        start = time.monotonic()
        resp = call()
        took = time.monotonic() - start
        self.assertFalse(resp.success, resp.status_message)
        self.assertLess(took, ANSWER, resp.status_message)
        self.assertNotIn("\n", resp.status_message)
        self.assertLess(len(resp.status_message), 1000, resp.status_message[:1000])
        for word in words:
            self.assertIn(word, resp.status_message)
        self.assert_alive()
        self.assertNotIn(name, self.gz.get_world_properties().model_names)
        return resp.status_message

    def assert_alive(self):
        """The clock runs, the robot's /odom and /scan come, the world API answers."""
        start = rospy.Time.now()
        self.assertIsNotNone(self.odom.after(start, SHORT_WAIT), "no /odom since")
        self.assertIsNotNone(self.scan.after(start, SHORT_WAIT), "no /scan since")
        self.assertTrue(self.gz.get_world_properties().success)

    def spawn_robot(self, name, xml, x):
        return self.gz.spawn_urdf_model(name, xml, name, pose(x, 2.0), "")

    def test_robot_numbers_beyond_the_limits_are_refused_where_they_are_written(self):
        """1e39 and 1e200 once half-added the robot, then ended the node (KeyError); 16385
        samples ended it at the first scan subscriber; a 1e-300 m wheel flipped it over."""
        for old, new, words in (
                ("<max>3.5</max>", "<max>1e39</max>", ["<max>", "max 1e+39 is outside"]),
                ("<gaussianNoise>0.0</gaussianNoise>", "<gaussianNoise>1e200</gaussianNoise>",
                 ["<gaussianNoise>", "gaussianNoise 1e+200 is outside"]),
                ("<samples>360</samples>", "<samples>16385</samples>",
                 ["<samples>", "samples 16385 is outside [1, 3600]"]),
                ("<wheelDiameter>0.066</wheelDiameter>", "<wheelDiameter>1e-300</wheelDiameter>",
                 ["<wheelDiameter>", "wheelDiameter 1e-300 is outside [0.01, 10000] m"])):
            message = self.refused(lambda: self.spawn_robot("tb3", burger((old, new)), 1.0),
                                   "tb3", "model_xml of tb3:", *words)
            line = burger((old, new)).split(new)[0].count("\n") + 1
            self.assertIn("model_xml of tb3:%d:" % line, message)

    def test_a_robot_whose_topics_cannot_be_made_is_taken_out_again(self):
        """Two robots whose IMU plugins name the same absolute service: the second one's
        topics cannot be made (rospy: already registered). It once stayed half-added and the
        next step ended the node (KeyError)."""
        shared = burger(("<serviceName>imu_service</serviceName>",
                         "<serviceName>/shared_imu_service</serviceName>"))
        resp = self.spawn_robot("tb3_a", shared, 1.0)
        self.assertTrue(resp.success, resp.status_message)
        self.refused(lambda: self.spawn_robot("tb3_b", shared, 2.0), "tb3_b",
                     "SpawnModel: Failure - robot 'tb3_b': its topics could not be made:",
                     "/shared_imu_service")
        topics = [t for t, _ in rospy.get_published_topics()]
        self.assertIn("/tb3_a/odom", topics)
        self.assertNotIn("/tb3_b/odom", topics)
        resp = self.spawn_robot("tb3_b", burger(), 2.0)     # its name and namespace are free
        self.assertTrue(resp.success, resp.status_message)
        self.assertTrue(wait_for(lambda: "/tb3_b/scan" in
                                 [t for t, _ in rospy.get_published_topics()], SHORT_WAIT))

    def test_an_include_or_a_material_file_that_is_a_fifo_is_refused_without_waiting(self):
        """Such a FIFO once froze the sim's loop for good."""
        fifo = os.path.join(self.tmp, "model.sdf")
        os.mkfifo(fifo)
        self.refused(lambda: self.gz.spawn_sdf_model(
            "cabinet", "<sdf version='1.6'><model name='m'><include><uri>%s</uri></include>"
                       "</model></sdf>" % fifo, "", pose(1.0, -1.0), ""),
                     "cabinet", "<include> of %s" % fifo, "it is a FIFO, not a regular file")
        obj = os.path.join(self.tmp, "painted.obj")
        with open(obj, "w") as f:
            f.write("mtllib painted.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nusemtl red\n"
                    "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
        os.mkfifo(os.path.join(self.tmp, "painted.mtl"))
        mesh = "<geometry><mesh><uri>%s</uri></mesh></geometry>" % obj
        self.refused(lambda: self.gz.spawn_sdf_model(
            "painted", sdf_with("<collision name='c'>%s</collision>" % mesh), "",
            pose(1.0, -1.0), ""), "painted",
            "painted.mtl: cannot read a file the mesh names: it is a FIFO")

    def _model(self, name, body):
        folder = os.path.join(self.tmp, name)
        os.makedirs(folder)
        with open(os.path.join(folder, "model.config"), "w") as f:
            f.write("<model><name>%s</name><sdf version='1.6'>model.sdf</sdf></model>" % name)
        with open(os.path.join(folder, "model.sdf"), "w") as f:
            f.write("<sdf version='1.6'><model name='%s'>%s</model></sdf>" % (name, body))
        return folder

    def largest_clock_gap(self, call):
        """(what ``call()`` answered, the longest wall time between two /clock messages while
        it ran)."""
        arrivals = []
        sub = rospy.Subscriber("/clock", Clock, lambda _msg: arrivals.append(time.monotonic()))
        try:
            rospy.sleep(0.5)
            answer = call()
            rospy.sleep(0.5)
        finally:
            sub.unregister()
        gaps = [b - a for a, b in zip(arrivals, arrivals[1:])]
        return answer, max(gaps)

    def test_spawns_beyond_what_the_loop_may_build_are_refused_while_the_clock_runs(self):
        """A polyline of 3,000 corners froze the loop 8 s, 2,000 ground planes left a real-time
        factor of 0.009, and a 100 x 100 fan-out of includes (a 155-character request) took
        36 s to spawn: each is now read outside the loop and refused before it is built."""
        corners = "".join("<point>%g %g</point>" % (math.cos(a), 0.5 * math.sin(a))
                          for a in (k * 2 * math.pi / 3000 for k in range(3000)))
        polyline = sdf_with("<collision name='c'><geometry><polyline>%s<height>1</height>"
                            "</polyline></geometry></collision>" % corners)
        planes = ("<sdf version='1.6'><model name='m'><static>true</static>%s</model></sdf>"
                  % "".join("<include><uri>model://ground_plane</uri><name>g%d</name></include>"
                            % k for k in range(2000)))
        box = self._model("fan_box", "<static>true</static><link name='l'><collision name='c'>"
                                     "<geometry><box><size>0.1 0.1 0.1</size></box></geometry>"
                                     "</collision></link>")
        row = self._model("fan_row", "<static>true</static>" + "".join(
            "<include><uri>%s</uri><name>b%d</name><pose>%g 0 0 0 0 0</pose></include>"
            % (box, k, 0.2 * k) for k in range(100)))
        fan = ("<sdf version='1.6'><model name='m'><static>true</static>%s</model></sdf>"
               % "".join("<include><uri>%s</uri><name>r%d</name><pose>0 %g 0 0 0 0</pose>"
                         "</include>" % (row, k, 0.2 * k) for k in range(100)))
        for xml, words in ((polyline, "polyline points: 3000, more than the 256"),
                           (planes, "more than 1000 collisions and visuals in all"),
                           (fan, "more than 1000 collisions and visuals in all")):
            message, gap = self.largest_clock_gap(lambda: self.refused(
                lambda: self.gz.spawn_sdf_model("cabinet", xml, "", pose(5.0, 5.0), ""),
                "cabinet", words))
            self.assertLess(gap, 1.0, "/clock stalled %.1f s while %s" % (gap, message))

    def test_a_10_mb_model_name_is_refused(self):
        self.refused(lambda: self.gz.spawn_sdf_model(
            "m" * 10_000_000, sdf_with(""), "", pose(1.0, -1.0), ""), "m" * 10_000_000,
            "SpawnModel: Failure - model_name is 10000000 characters, more than the 256 allowed")

    def test_a_model_config_that_is_dev_zero_ends_start_up_in_one_line(self):
        """It once filled the memory and ended in a MemoryError traceback."""
        folder = os.path.join(self.tmp, "models", "zero")
        os.makedirs(folder)
        os.symlink("/dev/zero", os.path.join(folder, "model.config"))
        world = os.path.join(self.tmp, "zero.world")
        with open(world, "w") as f:
            f.write("<sdf version='1.6'><world name='w'><include><uri>model://zero</uri>"
                    "</include></world></sdf>\n")
        port = free_port()
        env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % port,
                   GAZEBO_MODEL_PATH=os.path.join(self.tmp, "models"))
        master = subprocess.Popen(["rosmaster", "--core", "-p", str(port)], env=env,
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        sim = NodeProcess("sim", "_world:=" + world, "_status_period:=0", env=env)
        try:
            status = sim.wait(SHORT_WAIT)
            out = sim.stdout + sim.stderr
            self.assertEqual(status, 2, out)
            fatal = [line for line in out.splitlines() if "model.config" in line]
            self.assertEqual(len(fatal), 1, out)
            self.assertIn("cannot read model.config: it is a character device, not a regular "
                          "file", fatal[0])
            self.assertNotIn("Traceback", out)
        finally:
            sim.kill()
            master.terminate()
            master.wait(10.0)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_abuse_spawns", AbuseSpawnsTest)
