#!/usr/bin/env python3
"""make corpus: the ROS side of one world's run (bench/corpus.py starts it beside roslaunch).

    corpus_probe.py startup TIMEOUT
    corpus_probe.py measure TIMEOUT YAW_DRIVE
Waits for the master and the first /scan (at most TIMEOUT wall s) and prints ``{"first_scan":
WALL_TIME}`` (time.time()). ``startup`` then exits. ``measure`` reads the sim's pid from its
stdin and goes on, printing one JSON line at the end:

- ``models``: the names in /gazebo/model_states (one message);
- ``laser``: the share of finite ranges over a second of scans;
- ``colours``, ``in_colour``: the Waffle Pi's camera (camera/rgb/image_raw) at four headings,
  0, 90, 180 and 270 degrees from YAW_DRIVE, the robot turned in place by
  /gazebo/set_model_state: distinct quantized colours over the four images, and whether any of
  them is more than grey (bench/corpus_metrics.py);
- ``drive``: put back at YAW_DRIVE (the most open direction), 0.2 m/s for 2 sim s, then
  0.5 rad/s for 2 sim s; poses from /gazebo/model_states (drive_result in
  bench/corpus_metrics.py);
- ``cpu``, ``cpu_camera``: the sim process's CPU seconds per sim second over CPU_WINDOW sim s
  with /scan and /odom subscribed, then with the camera image subscribed too;
- ``errors``: what could not be measured, one line each.
"""
import json
import math
import os
import sys
import threading
import time

import numpy as np
import rospy
from gazebo_msgs.msg import ModelState, ModelStates
from gazebo_msgs.srv import SetModelState
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import Image, LaserScan

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, os.pardir, "test"))
from corpus_metrics import camera_summary, drive_result, finite_share  # noqa: E402
from process_helpers import cpu_seconds  # noqa: E402

CAMERA = "/camera/rgb/image_raw"
SPEED, TURN_RATE, DRIVE_TIME = 0.2, 0.5, 2.0   # m/s, rad/s, sim s
SETTLE = 0.5          # sim s after a teleport or a stop
CPU_WINDOW = 5.0      # sim s per CPU window
WAIT = 20.0           # wall s at most for one message or one window
FIRST_IMAGE_WAIT = 60.0   # wall s for the first camera image (the renderer starts)
BUFFER = 1 << 24      # bytes of a subscriber's receive buffer


class Latest:
    """The latest message of a topic, and an event for each new one."""

    def __init__(self, topic, msg_type):
        self.msg = None
        self.count = 0
        self.event = threading.Event()
        # a buffer larger than an image: rospy's default (64 KB) delivers large messages late
        self.sub = rospy.Subscriber(topic, msg_type, self.on_msg, queue_size=1,
                                    buff_size=BUFFER)

    def on_msg(self, msg):
        self.msg = msg
        self.count += 1
        self.event.set()

    def next(self, after=None, timeout=WAIT):
        """The next message (stamped at or after ``after``, a rospy.Time) within ``timeout``
        wall s, or None."""
        deadline = time.time() + timeout
        while time.time() < deadline and not rospy.is_shutdown():
            self.event.clear()
            msg = self.msg
            if msg is not None and (after is None or msg.header.stamp >= after):
                self.msg = None
                return msg
            self.event.wait(0.1)
        return None


def save_images(images):
    """Write the camera images as PPM files into $CORPUS_IMAGES (if set): 0.ppm .. 3.ppm."""
    folder = os.environ.get("CORPUS_IMAGES")
    if not folder:
        return
    os.makedirs(folder, exist_ok=True)
    for number, image in enumerate(images):
        with open(os.path.join(folder, "%d.ppm" % number), "wb") as f:
            f.write(b"P6 %d %d 255\n" % (image.shape[1], image.shape[0]) + image.tobytes())


def yaw_of(q):
    return math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y * q.y + q.z * q.z))


def sim_sleep(seconds):
    """Sleep ``seconds`` of sim time, at most WAIT wall s."""
    end = rospy.Time.now() + rospy.Duration(seconds)
    deadline = time.time() + WAIT
    while rospy.Time.now() < end and time.time() < deadline and not rospy.is_shutdown():
        time.sleep(0.01)


class Probe:
    def __init__(self):
        self.errors = []
        self.out = {}         # what was measured so far
        self.robot = None
        self.cmd = rospy.Publisher("/cmd_vel", Twist, queue_size=1)

    def robot_pose(self):
        """(x, y, z, yaw) of the robot from one /gazebo/model_states, and the names."""
        msg = rospy.wait_for_message("/gazebo/model_states", ModelStates, timeout=WAIT)
        robots = [n for n in msg.name if n.startswith("turtlebot3")]
        self.robot = robots[-1] if robots else msg.name[-1]
        pose = msg.pose[msg.name.index(self.robot)]
        p = pose.position
        return (p.x, p.y, p.z, yaw_of(pose.orientation)), list(msg.name)

    def turn_to(self, x, y, z, yaw):
        """Teleport the robot to (x, y, z) facing ``yaw``, at rest."""
        rospy.wait_for_service("/gazebo/set_model_state", timeout=WAIT)
        state = ModelState(model_name=self.robot, reference_frame="world")
        state.pose.position.x, state.pose.position.y, state.pose.position.z = x, y, z
        state.pose.orientation.z, state.pose.orientation.w = math.sin(yaw / 2), math.cos(yaw / 2)
        reply = rospy.ServiceProxy("/gazebo/set_model_state", SetModelState)(state)
        if not reply.success:
            raise RuntimeError("set_model_state: %s" % reply.status_message)
        sim_sleep(SETTLE)

    def drive(self, linear, angular, seconds):
        """Command (linear m/s, angular rad/s) for ``seconds`` of sim time, then stop."""
        deadline = time.time() + WAIT
        while self.cmd.get_num_connections() == 0 and time.time() < deadline:
            time.sleep(0.05)   # the sim has not connected to our /cmd_vel yet
        end = rospy.Time.now() + rospy.Duration(seconds)
        deadline = time.time() + WAIT
        twist = Twist()
        twist.linear.x, twist.angular.z = linear, angular
        while rospy.Time.now() < end and time.time() < deadline and not rospy.is_shutdown():
            self.cmd.publish(twist)
            time.sleep(0.02)
        self.cmd.publish(Twist())
        sim_sleep(SETTLE)

    def cpu_window(self, pid, wanted):
        """CPU s of ``pid`` per sim s over CPU_WINDOW sim s."""
        sim_sleep(1.0)   # the subscriptions connected
        cpu0, t0 = cpu_seconds(pid), rospy.Time.now()
        sim_sleep(CPU_WINDOW)
        cpu1, t1 = cpu_seconds(pid), rospy.Time.now()
        span = (t1 - t0).to_sec()
        if span <= 0 or cpu0 is None or cpu1 is None:
            self.errors.append("cpu (%s): no sim time passed" % wanted)
            return None
        return round((cpu1 - cpu0) / span, 4)

    def measure(self, pid, drive_yaw):
        """Fill self.out (see the module docstring)."""
        out = self.out
        (x, y, z, _), names = self.robot_pose()
        out["models"] = len(names)
        scans = Latest("/scan", LaserScan)
        shares = []
        end = time.time() + WAIT
        while len(shares) < 5 and time.time() < end:
            msg = scans.next(timeout=5.0)
            if msg is not None:
                shares.append(finite_share(msg.ranges))
        out["laser"] = round(float(np.mean(shares)), 3) if shares else None
        images = []
        camera = Latest(CAMERA, Image)
        for quarter in range(4):
            self.turn_to(x, y, z, drive_yaw + quarter * math.pi / 2)
            wait = FIRST_IMAGE_WAIT if quarter == 0 else WAIT
            msg = camera.next(after=rospy.Time.now(), timeout=wait)
            if msg is None:
                self.errors.append("camera: no image within %g wall s" % wait)
                break
            images.append(np.frombuffer(msg.data, np.uint8).reshape(
                msg.height, msg.step)[:, :3 * msg.width].reshape(msg.height, msg.width, 3))
        camera.sub.unregister()
        save_images(images)
        if images:
            out["colours"], out["in_colour"] = camera_summary(images)
        self.turn_to(x, y, z, drive_yaw)
        start, _ = self.robot_pose()
        self.drive(SPEED, 0.0, DRIVE_TIME)
        after_line, _ = self.robot_pose()
        self.drive(0.0, TURN_RATE, DRIVE_TIME)
        after_turn, _ = self.robot_pose()
        out["drive"] = drive_result((start[0], start[1], start[3]),
                                    (after_line[0], after_line[1], after_line[3]),
                                    (after_turn[0], after_turn[1], after_turn[3]),
                                    SPEED * DRIVE_TIME, TURN_RATE * DRIVE_TIME)
        odom = Latest("/odom", Odometry)
        out["cpu"] = self.cpu_window(pid, "scan and odom")
        camera = Latest(CAMERA, Image)
        out["cpu_camera"] = self.cpu_window(pid, "and camera")
        camera.sub.unregister()
        odom.sub.unregister()
        scans.sub.unregister()


def wait_for_sim_time(timeout):
    """Wait (at most ``timeout`` wall s) until the master is up and roslaunch has set
    /use_sim_time: rospy reads it once, in init_node, and this probe starts first."""
    import rosgraph
    master = rosgraph.Master("/corpus_probe")
    deadline = time.time() + timeout
    while time.time() < deadline:
        try:
            if master.hasParam("/use_sim_time"):
                return
        except OSError:   # no master yet
            pass
        time.sleep(0.02)


def main():
    phase, timeout = sys.argv[1], float(sys.argv[2])
    wait_for_sim_time(timeout)
    rospy.init_node("corpus_probe", anonymous=True, disable_signals=True)
    if rospy.rostime.is_wallclock():
        sys.exit("corpus_probe.py: /use_sim_time is not set: ROS time would be wall time")
    first = threading.Event()
    stamp = []

    def on_scan(_msg):
        if not first.is_set():
            stamp.append(time.time())
            first.set()
    sub = rospy.Subscriber("/scan", LaserScan, on_scan, queue_size=1)
    first.wait(timeout)
    sub.unregister()
    print(json.dumps({"first_scan": stamp[0] if stamp else None}), flush=True)
    if phase != "measure" or not stamp:
        return
    pid = int(sys.stdin.readline())
    probe = Probe()
    try:
        probe.measure(pid, float(sys.argv[3]))
    except (rospy.ROSException, rospy.ServiceException, RuntimeError, ValueError) as err:
        probe.errors.append("%s: %s" % (type(err).__name__, err))
    probe.out["errors"] = probe.errors
    print(json.dumps(probe.out), flush=True)


if __name__ == "__main__":
    main()
