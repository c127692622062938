#!/usr/bin/env python3
"""rostest node: ``roslaunch tutorial_turtlebot sim.launch rviz:=true`` as a user runs it, on a
virtual X display (Xvfb, Mesa's software OpenGL), with the robot driving a circle.

Checks that RViz's 3D view stays readable (the dark background shows, the red laser points
and the robot at the centre of the view are drawn: no covariance ellipsoid paints it over),
that the camera panel is there exactly when expected (~expect_camera_panel), and that the sim
keeps ~min_rtf of real time while RViz runs (sim time advanced on /clock over ~measure_s wall
seconds). Logs what RViz and the sim cost in CPU and saves the screenshot (~screenshot, default
in the ROS log directory) for a human to look at.

Params: ~model (waffle), ~expect_camera_panel (false), ~min_rtf (0.9; 0 = do not check),
~max_sim_cost (CPU seconds the sim may spend per sim second with RViz running, a measure that
other load on the machine hardly changes; 0 = do not check), ~measure_s (20.0 wall s),
~screenshot (path of the PNG), ~launch_args (more sim.launch args, e.g. "rviz_camera:=true").
"""
import ctypes
import os
import shutil
import signal
import subprocess
import tempfile
import threading
import time
import unittest
import xmlrpc.client

import numpy as np
import rosgraph
import rospkg
import rospy
import rostest
from rosgraph_msgs.msg import Clock

from sim_test_support import Driver, cpu_seconds, stop_process, wait_for

WAIT = 90.0  # wall s for start-up: the sim, robot_state_publisher and RViz on a busy machine
BACKGROUND = (48, 48, 48)  # Global Options/Background Color of rviz/turtlebot3*.rviz
SCREEN = (1400, 900)  # the window size of rviz/turtlebot3*.rviz
CAMERA_TOPIC = "/camera/rgb/image_raw"


def _die_with_parent():
    """preexec_fn: the child gets SIGTERM when this test node dies, even by SIGKILL."""
    ctypes.CDLL("libc.so.6", use_errno=True).prctl(1, signal.SIGTERM)  # PR_SET_PDEATHSIG


def start_xvfb():
    """Xvfb on the first free display; returns (process, ':N') once it accepts clients."""
    if shutil.which("Xvfb") is None:
        raise RuntimeError("Xvfb not found: install it (Debian/Ubuntu: apt-get install xvfb)")
    read_fd, write_fd = os.pipe()
    proc = subprocess.Popen(
        ["Xvfb", "-displayfd", str(write_fd), "-screen", "0", "%dx%dx24" % SCREEN,
         "-nolisten", "tcp", "-noreset"],
        pass_fds=(write_fd,), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
        preexec_fn=_die_with_parent)
    os.close(write_fd)
    number = b""
    deadline = time.monotonic() + 30.0
    with os.fdopen(read_fd, "rb") as pipe:  # Xvfb writes "N\n" when it is ready
        while not number.endswith(b"\n") and time.monotonic() < deadline:
            chunk = pipe.read(1)
            if not chunk:
                break
            number += chunk
    if not number.strip():
        proc.kill()
        raise RuntimeError("Xvfb did not start: %s" % proc.stderr.read().decode(errors="replace"))
    return proc, ":" + number.decode().strip()


def node_pid(name):
    """The pid of a ROS node, asked from the node itself through the master."""
    master = rosgraph.Master("/test_rviz")
    return xmlrpc.client.ServerProxy(master.lookupNode(name)).getPid("/test_rviz")[2]


def subscriptions_of(node):
    """Topics ``node`` subscribes to, from the master."""
    _, subscribers, _ = rosgraph.Master("/test_rviz").getSystemState()
    return {topic for topic, nodes in subscribers if node in nodes}


def view_analysis(rgb):
    """What the screenshot shows: the 3D view's box (rows and columns where RViz's background
    colour dominates) and the counts the tests ask about."""
    background = np.all(rgb == BACKGROUND, axis=2)
    rows = np.flatnonzero(background.mean(axis=1) > 0.2)
    cols = np.flatnonzero(background.mean(axis=0) > 0.2)
    result = {"background_share": float(background.mean()), "box": None}
    if rows.size == 0 or cols.size == 0:
        return result
    top, bottom, left, right = rows[0], rows[-1] + 1, cols[0], cols[-1] + 1
    view = rgb[top:bottom, left:right].astype(int)
    colours, counts = np.unique(view.reshape(-1, 3), axis=0, return_counts=True)
    red = (view[..., 0] > 180) & (view[..., 1] < 70) & (view[..., 2] < 70)
    cy, cx = (bottom - top) // 2, (right - left) // 2
    centre = view[cy - 4:cy + 4, cx - 4:cx + 4]
    # the camera panel: a picture in the left dock, i.e. a long run of rows most of whose
    # pixels are darker than Qt's light widgets (borders and text make runs of a few rows)
    dock_rows = (rgb[top:bottom, :max(left - 10, 1)].max(axis=2) < 200).mean(axis=1) > 0.4
    run = longest = 0
    for dark in dock_rows:
        run = run + 1 if dark else 0
        longest = max(longest, run)
    result.update(
        box=(int(left), int(top), int(right), int(bottom)),
        dominant_share=float(counts.max() / counts.sum()),
        dominant_colour=tuple(int(c) for c in colours[counts.argmax()]),
        red_pixels=int(red.sum()),
        # share of the 8x8 pixels at the view's centre (the robot, as the view follows
        # base_footprint) that differ from the background
        centre_drawn=float(np.any(np.abs(centre - BACKGROUND) > 20, axis=2).mean()),
        dock_picture_rows=longest)
    return result


class RvizTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.procs = []
        cls.runtime_dir = tempfile.mkdtemp(prefix="test_rviz_")  # for Qt, mode 0700
        try:
            cls._start_and_measure()
        except BaseException:
            cls.tearDownClass()  # unittest does not, when setUpClass fails
            raise

    @classmethod
    def _start_and_measure(cls):
        rospy.init_node("test_rviz")
        cls.model = rospy.get_param("~model", "waffle")
        cls.expect_camera_panel = rospy.get_param("~expect_camera_panel", False)
        cls.min_rtf = float(rospy.get_param("~min_rtf", 0.9))
        cls.max_sim_cost = float(rospy.get_param("~max_sim_cost", 0.0))
        cls.measure_s = float(rospy.get_param("~measure_s", 20.0))
        launch_args = rospy.get_param("~launch_args", "").split()
        cls.screenshot_path = rospy.get_param(
            "~screenshot", os.path.join(rospkg.get_log_dir(), "test_rviz_%s.png" % cls.model))
        cls.launch_output = []
        cls.xvfb, cls.display = start_xvfb()
        cls.procs.append(cls.xvfb)
        env = dict(os.environ, DISPLAY=cls.display, XDG_RUNTIME_DIR=cls.runtime_dir)
        cls.launch = subprocess.Popen(
            ["roslaunch", "tutorial_turtlebot", "sim.launch", "model:=" + cls.model,
             "rviz:=true", "status_period:=0"] + launch_args,
            env=env, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
            preexec_fn=_die_with_parent)
        cls.procs.insert(0, cls.launch)
        threading.Thread(target=cls._drain, daemon=True).start()

        cls.clock = []  # (wall monotonic s, sim s) of each /clock message
        rospy.Subscriber("/clock", Clock, cls._on_clock, queue_size=100)
        ready = wait_for(lambda: cls.launch.poll() is not None
                         or ({"/scan", "/odom"} <= subscriptions_of("/rviz")
                             and len(cls.clock) > 10), WAIT, step=0.5)
        assert ready and cls.launch.poll() is None, (
            "RViz or the sim did not come up within %.0f s (roslaunch exit status %s):\n%s"
            % (WAIT, cls.launch.poll(), "".join(cls.launch_output[-40:])))
        cls.rviz_topics = subscriptions_of("/rviz")
        cls.drive = Driver()
        cls.drive.send(0.15, 0.4)  # a circle of 0.375 m by the spawn, clear of the pillars
        time.sleep(5.0)  # RViz draws a few scans and odometry arrows

        pids = {"rviz": node_pid("/rviz"), "sim": node_pid("/gazebo")}
        cpu_before = {name: cpu_seconds(pid) for name, pid in pids.items()}
        clock_start = len(cls.clock)
        time.sleep(cls.measure_s)
        cpu_after = {name: cpu_seconds(pid) for name, pid in pids.items()}
        window = cls.clock[clock_start:]
        wall = window[-1][0] - window[0][0] if len(window) > 1 else 0.0
        sim_advanced = window[-1][1] - window[0][1] if len(window) > 1 else 0.0
        cls.rtf = sim_advanced / wall if wall > 0 else 0.0
        cls.cpu = {name: (cpu_after[name] - cpu_before[name]) / cls.measure_s for name in pids}
        cls.sim_cost = ((cpu_after["sim"] - cpu_before["sim"]) / sim_advanced
                        if sim_advanced > 0 else float("inf"))
        cls.load = os.getloadavg()

        from PIL import ImageGrab
        shot = ImageGrab.grab(xdisplay=cls.display)
        shot.save(cls.screenshot_path)
        cls.analysis = view_analysis(np.asarray(shot.convert("RGB")))
        cls.drive.send(0.0, 0.0)
        rospy.loginfo(
            "%s, RViz on %s: real-time factor %.2f over %.0f wall s; CPU rviz %.0f%%, sim "
            "%.0f%% of one core (%.2f CPU s per sim s); load %.1f; screenshot %s; %s",
            cls.model, cls.display, cls.rtf, wall, 100 * cls.cpu["rviz"],
            100 * cls.cpu["sim"], cls.sim_cost, cls.load[0], cls.screenshot_path, cls.analysis)

    @classmethod
    def _drain(cls):
        for line in iter(cls.launch.stdout.readline, b""):
            cls.launch_output.append(line.decode("utf-8", "replace"))

    @classmethod
    def _on_clock(cls, msg):
        cls.clock.append((time.monotonic(), msg.clock.to_sec()))

    @classmethod
    def tearDownClass(cls):
        for proc in cls.procs:  # roslaunch first (it stops the sim and RViz), then Xvfb
            stop_process(proc)
        shutil.rmtree(cls.runtime_dir, ignore_errors=True)

    def view(self):
        """The screenshot's analysis, failing the test if no 3D view was found in it."""
        self.assertIsNotNone(self.analysis["box"],
                             "no RViz background on the screen: %s" % self.analysis)
        return self.analysis

    def test_rviz_subscribes_to_the_robot_topics(self):
        for topic in ("/scan", "/odom", "/tf", "/tf_static"):
            self.assertIn(topic, self.rviz_topics)

    def test_camera_panel_only_where_expected(self):
        self.assertEqual(CAMERA_TOPIC in self.rviz_topics, self.expect_camera_panel,
                         "RViz subscriptions: %s" % sorted(self.rviz_topics))
        if self.expect_camera_panel:
            self.assertGreater(self.view()["dock_picture_rows"], 100, self.analysis)
        else:
            self.assertLess(self.view()["dock_picture_rows"], 60, self.analysis)

    def test_3d_view_is_not_painted_over(self):
        a = self.view()
        left, top, right, bottom = a["box"]
        self.assertGreater((right - left) * (bottom - top), 0.4 * SCREEN[0] * SCREEN[1], a)
        self.assertGreater(a["background_share"], 0.3, a)
        self.assertEqual(a["dominant_colour"], BACKGROUND, a)
        self.assertGreater(1.0 - a["dominant_share"], 0.01, "the view is one colour: %s" % a)

    def test_laser_and_robot_are_drawn(self):
        a = self.view()
        self.assertGreater(a["red_pixels"], 300, a)
        self.assertGreater(a["centre_drawn"], 0.8, a)

    def test_sim_keeps_real_time(self):
        if self.min_rtf <= 0:
            self.skipTest("~min_rtf 0: not checked for this model")
        self.assertGreaterEqual(
            self.rtf, self.min_rtf,
            "real-time factor %.2f with RViz (CPU rviz %.0f%%, sim %.0f%%; load average %.1f "
            "on %d cores)" % (self.rtf, 100 * self.cpu["rviz"], 100 * self.cpu["sim"],
                              self.load[0], os.cpu_count()))

    def test_sim_cost_with_rviz(self):
        if self.max_sim_cost <= 0:
            self.skipTest("~max_sim_cost 0: not checked for this model")
        self.assertLessEqual(
            self.sim_cost, self.max_sim_cost,
            "the sim spends %.2f CPU s per sim s with RViz running (real-time factor %.2f)"
            % (self.sim_cost, self.rtf))


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "test_rviz", RvizTest)
