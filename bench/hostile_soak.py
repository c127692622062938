#!/usr/bin/env python3
"""Hostile soak: the hostile requests that once killed, froze or choked the sim, replayed in a
loop against one sim for ``--minutes`` wall minutes, beside a /clock watcher.

    hostile_soak.py [--minutes 10]

The sim: sim.launch with a Burger in the empty world at real time, on a master of its own (as
run_bench's SimRun). Each round sends, through the real /gazebo services: robots whose plugin
numbers are beyond the limits (laser <max> 1e39, IMU noise 1e200, 16385 samples, a 1e-300 m
wheel), includes of /dev/zero, /dev/stdin and a FIFO, a polyline of 3,000 corners, 2,000
ground planes, a 100 x 100 fan-out of includes, a 10 MB model name, meshes whose vertices are
1e12 m or become infinite when scaled, a spawn and delete of 20 boxes of distinct sizes and of
a 20,000-triangle mesh, NaN and 1e308 teleports, pause and unpause, reset_world; and the third
round's: URDF chains of 150 revolute, 400 and 1,000 fixed links, a joint's damping 1e308 and
friction -1, a model.config whose version has 5,000 digits, max_update_rate 5e-324 and cfm 1e6,
a NaN com orientation, requests whose bodies do not deserialize or are cut short, a
publisherUpdate of /cmd_vel naming 300 publishers that accept and never answer and 300 on a
closed port (then an empty one), 100 subscribers of /gazebo/parameter_updates that never read
(closed at the round's end). Beside the
rounds, the whole time: three processes flooding /gazebo/set_model_state (each for a minute,
then again), a client subscribed to /scan whose rate is measured, and the /clock watcher, which
notes the longest wall time between two messages. The sim's threads are counted at the start
and the end.

It prints one line a round, then ``RESULT clock_gap_s rss_start_mb rss_end_mb cpu_start cpu_end
alive rss_idle_mb rounds threads_start threads_end scan_hz``. The start is after a first round
(the mesh readers are imported then, about 40 MB, and the caches filled); rss_idle_mb is before
any request. CPU per sim second: the sim's CPU seconds over 20 quiet wall seconds at the start
and at the end, divided by the sim seconds run meanwhile. make bench's ``hostile`` group runs it
(not a default group: it takes --minutes plus about a minute).
Run from a shell where ``source catkin_ws/devel/setup.bash`` was done.
"""
import argparse
import math
import os
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time
import xmlrpc.client

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, os.pardir, "src"))

from run_bench import SimRun, cpu_seconds, free_port, rss_mb  # noqa: E402

QUIET = 20.0   # wall s of the CPU windows
FLOODERS = 3   # processes flooding /gazebo/set_model_state beside the rounds
FLOOD_SECONDS = 60.0   # wall s of one flooder's life (then another takes its place)
FLOODER = os.path.join(HERE, os.pardir, "test", "state_flooder.py")


def _sdf(body, static=True):
    return ("<sdf version='1.6'><model name='m'><static>%s</static>%s</model></sdf>"
            % ("true" if static else "false", body))


def _link(geometry):
    return ("<link name='l'><collision name='c'><geometry>%s</geometry></collision>"
            "<visual name='v'><geometry>%s</geometry></visual></link>" % (geometry, geometry))


def _model_dir(root, name, body):
    folder = os.path.join(root, name)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "model.config"), "w") as f:
        f.write("<model><name>%s</name><sdf version='1.6'>model.sdf</sdf></model>" % name)
    with open(os.path.join(folder, "model.sdf"), "w") as f:
        f.write("<sdf version='1.6'><model name='%s'>%s</model></sdf>" % (name, body))
    return folder


def _grid_obj(path, n, z_scale=0.01):
    """An OBJ of a wavy n x n grid over 1 x 1 m: 2 n^2 triangles."""
    rows = []
    for j in range(n + 1):
        for i in range(n + 1):
            rows.append("v %.5f %.5f %.5f" % (i / n, j / n, z_scale * math.sin(i) * math.cos(j)))
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            rows.append("f %d %d %d" % (a, a + 1, a + n + 2))
            rows.append("f %d %d %d" % (a, a + n + 2, a + n + 1))
    with open(path, "w") as f:
        f.write("\n".join(rows) + "\n")
    return path


def hostile_inputs(tmp, burger):
    """[(label, service, model name, text)] of one round."""
    def robot(old, new):
        assert burger.count(old) == 1, old
        return burger.replace(old, new)
    fifo = os.path.join(tmp, "fifo.sdf")
    os.mkfifo(fifo)
    far = os.path.join(tmp, "far.obj")
    with open(far, "w") as f:
        f.write("v 0 0 0\nv 1e12 0 0\nv 0 1e12 0\nv 0 0 1e12\nf 1 3 2\nf 1 2 4\nf 1 4 3\n"
                "f 2 3 4\n")
    huge = os.path.join(tmp, "e308.obj")
    with open(huge, "w") as f:
        f.write("v 0 0 0\nv 1e308 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    box = _model_dir(tmp, "fan_box", "<static>true</static>" + _link(
        "<box><size>0.1 0.1 0.1</size></box>"))
    row = _model_dir(tmp, "fan_row", "<static>true</static>" + "".join(
        "<include><uri>%s</uri><name>b%d</name><pose>%g 0 0 0 0 0</pose></include>"
        % (box, k, 0.2 * k) for k in range(100)))
    digits = _model_dir(tmp, "digits", "<static>true</static>" + _link(
        "<box><size>0.1 0.1 0.1</size></box>"))
    with open(os.path.join(digits, "model.config"), "w") as f:
        f.write("<model><name>d</name><sdf version='1.%s'>model.sdf</sdf></model>" % ("6" * 5000))
    corners = "".join("<point>%g %g</point>" % (math.cos(a), 0.5 * math.sin(a))
                      for a in (k * 2 * math.pi / 3000 for k in range(3000)))
    return [
        ("laser max 1e39", "urdf", "tb3_x", robot("<max>3.5</max>", "<max>1e39</max>")),
        ("IMU noise 1e200", "urdf", "tb3_x", robot("<gaussianNoise>0.0</gaussianNoise>",
                                                   "<gaussianNoise>1e200</gaussianNoise>")),
        ("16385 samples", "urdf", "tb3_x", robot("<samples>360</samples>",
                                                 "<samples>16385</samples>")),
        ("1e-300 m wheel", "urdf", "tb3_x", robot("<wheelDiameter>0.066</wheelDiameter>",
                                                  "<wheelDiameter>1e-300</wheelDiameter>")),
        ("include /dev/zero", "sdf", "z", _sdf("<include><uri>/dev/zero</uri></include>")),
        ("include /dev/stdin", "sdf", "z", _sdf("<include><uri>/dev/stdin</uri></include>")),
        ("include a FIFO", "sdf", "z", _sdf("<include><uri>%s</uri></include>" % fifo)),
        ("polyline of 3000 corners", "sdf", "z", _sdf(
            "<link name='l'><collision name='c'><geometry><polyline>%s<height>1</height>"
            "</polyline></geometry></collision></link>" % corners)),
        ("2000 ground planes", "sdf", "z", _sdf("".join(
            "<include><uri>model://ground_plane</uri><name>g%d</name></include>" % k
            for k in range(2000)))),
        ("fan-out 100 x 100", "sdf", "z", _sdf("".join(
            "<include><uri>%s</uri><name>r%d</name><pose>0 %g 0 0 0 0</pose></include>"
            % (row, k, 0.2 * k) for k in range(100)))),
        ("10 MB model name", "sdf", "m" * 10_000_000, _sdf("")),
        ("movable mesh of 1e12 m", "sdf", "z", _sdf(_link("<mesh><uri>%s</uri></mesh>" % far),
                                                    static=False)),
        ("mesh of 1e308 scaled by 10", "sdf", "z", _sdf(_link(
            "<mesh><uri>%s</uri><scale>10 10 10</scale></mesh>" % huge))),
        ("chain of 150 revolute links", "urdf", "z", _chain(150, "revolute")),
        ("chain of 400 fixed links", "urdf", "z", _chain(400, "fixed")),
        ("chain of 1000 fixed links", "urdf", "z", _chain(1000, "fixed")),
        ("joint damping 1e308", "urdf", "z", _chain(3, "revolute", 'damping="1e308"')),
        ("joint friction -1", "urdf", "z", _chain(3, "revolute", 'friction="-1"')),
        ("a version of 5000 digits", "sdf", "z", _sdf("<include><uri>%s</uri></include>"
                                                      % digits)),
    ]


def _chain(links, joint, dynamics=""):
    """A URDF chain of ``links`` links 1 cm apart joined by ``joint`` joints."""
    inertial = ('<inertial><mass value="0.1"/><inertia ixx="0.001" iyy="0.001" izz="0.001" '
                'ixy="0" ixz="0" iyz="0"/></inertial>')
    limit = '<limit lower="-1" upper="1" effort="1" velocity="1"/>' if joint == "revolute" else ""
    extra = "<dynamics %s/>" % dynamics if dynamics else ""
    return '<robot name="chain">%s%s</robot>' % (
        "".join('<link name="l%d">%s</link>' % (i, inertial) for i in range(links)),
        "".join('<joint name="j%d" type="%s"><parent link="l%d"/><child link="l%d"/><origin '
                'xyz="0 0 0.01"/><axis xyz="0 0 1"/>%s%s</joint>'
                % (i, joint, i - 1, i, limit, extra) for i in range(1, links)))


def threads_of(pid) -> int:
    """How many threads process ``pid`` has now."""
    return len(os.listdir("/proc/%d/task" % pid))


class Flooders:
    """FLOODERS processes publishing /gazebo/set_model_state as fast as they can, each renewed
    when its FLOOD_SECONDS are over, until ``stop``."""

    def __init__(self, model: str):
        self.model = model
        self.sent = 0
        self._stop = threading.Event()
        self._threads = [threading.Thread(target=self._keep_one, daemon=True)
                         for _ in range(FLOODERS)]

    def start(self):
        for thread in self._threads:
            thread.start()

    def _keep_one(self):
        while not self._stop.is_set():
            proc = subprocess.Popen([sys.executable, FLOODER, self.model, str(FLOOD_SECONDS)],
                                    stdout=subprocess.PIPE, stderr=subprocess.DEVNULL)
            out, _ = proc.communicate(timeout=FLOOD_SECONDS + 60)
            words = out.split()
            self.sent += int(words[-1]) if words else 0

    def stop(self):
        self._stop.set()
        for thread in self._threads:
            thread.join(FLOOD_SECONDS + 70)


def malformed_requests(address, count):
    """``count`` requests to get_world_properties at ``address`` whose bodies do not
    deserialize or are cut short, from two callerids."""
    from io import BytesIO
    from gazebo_msgs.srv import GetWorldProperties
    from rosgraph.network import read_ros_handshake_header, write_ros_handshake_header
    bodies = (struct.pack("<I", 8) + struct.pack("<I", 0xffffffff) + b"abcd", b"\x64\0\0\0abc")
    for k in range(count):
        try:
            with socket.create_connection(address, timeout=2.0) as sock:
                write_ros_handshake_header(sock, {
                    "callerid": "/malformed_%d" % (k % 2), "persistent": "0",
                    "service": "/gazebo/get_world_properties",
                    "md5sum": GetWorldProperties._md5sum})
                read_ros_handshake_header(sock, BytesIO(), 4096)
                sock.sendall(bodies[k % 2])
                sock.settimeout(0.2)
                sock.recv(100)
        except OSError:
            pass


class HangingListener:
    """Accepts on 127.0.0.1 and never answers, holding at most ``limit`` sockets; ``drop()``
    closes what it holds."""

    def __init__(self, limit=400):
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(128)
        self.sock.settimeout(0.5)
        self.port = self.sock.getsockname()[1]
        self.limit, self.held, self.open = limit, [], True
        threading.Thread(target=self._accept, daemon=True).start()

    def _accept(self):
        while self.open:
            try:
                conn = self.sock.accept()[0]
            except socket.timeout:
                continue
            except OSError:
                return
            if len(self.held) < self.limit:
                self.held.append(conn)
            else:
                conn.close()

    def drop(self):
        held, self.held = self.held, []
        for conn in held:
            conn.close()

    def close(self):
        self.open = False
        self.sock.close()
        self.drop()


def never_reading_subscribers(address, count):
    """``count`` sockets subscribed to /gazebo/parameter_updates (valid handshakes, distinct
    callerids) that never read: the caller closes them."""
    from dynamic_reconfigure.msg import Config
    from rosgraph.network import write_ros_handshake_header
    socks = []
    for k in range(count):
        try:
            sock = socket.create_connection(address, timeout=2.0)
            socks.append(sock)
            write_ros_handshake_header(sock, {
                "topic": "/gazebo/parameter_updates", "md5sum": Config._md5sum,
                "type": Config._type, "callerid": "/never_reads_%d" % k})
        except OSError:
            pass
    return socks


def soak(minutes: float) -> dict:
    from tutorial_turtlebot.sim.files.urdf.urdf_file import urdf_path
    with open(urdf_path("burger", False)) as f:
        burger = f.read()
    tmp = tempfile.mkdtemp(prefix="hostile_soak_")
    run = SimRun(["real_time_factor:=1", "world:=empty"])
    try:
        inputs = hostile_inputs(tmp, burger)
        mesh = _grid_obj(os.path.join(tmp, "grid.obj"), 100)      # 20,000 triangles
        run.start()
        pid = run.sim_pid()
        os.environ["ROS_MASTER_URI"] = run.env["ROS_MASTER_URI"]
        return _replay(pid, minutes * 60.0, inputs, mesh)
    finally:
        run.stop()
        shutil.rmtree(tmp, ignore_errors=True)


def _replay(pid, seconds, inputs, mesh):
    import rospy
    import rosgraph
    from gazebo_msgs.msg import ModelState
    from gazebo_msgs.srv import (DeleteModel, GetLinkProperties, GetPhysicsProperties,
                                 GetWorldProperties, SetLinkProperties, SetModelState,
                                 SetPhysicsProperties, SpawnModel)
    from geometry_msgs.msg import Pose, Twist
    from rosgraph_msgs.msg import Clock
    from sensor_msgs.msg import LaserScan
    from std_srvs.srv import Empty

    rospy.init_node("hostile_soak", anonymous=True, disable_signals=True)
    for name in ("spawn_sdf_model", "get_world_properties"):
        rospy.wait_for_service("/gazebo/" + name, timeout=60)
    spawn = {"sdf": rospy.ServiceProxy("/gazebo/spawn_sdf_model", SpawnModel),
             "urdf": rospy.ServiceProxy("/gazebo/spawn_urdf_model", SpawnModel)}
    delete = rospy.ServiceProxy("/gazebo/delete_model", DeleteModel)
    world = rospy.ServiceProxy("/gazebo/get_world_properties", GetWorldProperties)
    set_state = rospy.ServiceProxy("/gazebo/set_model_state", SetModelState)
    empties = {n: rospy.ServiceProxy("/gazebo/" + n, Empty)
               for n in ("pause_physics", "unpause_physics", "reset_world")}
    get_physics = rospy.ServiceProxy("/gazebo/get_physics_properties", GetPhysicsProperties)
    set_physics = rospy.ServiceProxy("/gazebo/set_physics_properties", SetPhysicsProperties)
    get_link = rospy.ServiceProxy("/gazebo/get_link_properties", GetLinkProperties)
    set_link = rospy.ServiceProxy("/gazebo/set_link_properties", SetLinkProperties)
    service_uri = rosgraph.Master("/hostile_soak").lookupService("/gazebo/get_world_properties")
    host, port = service_uri[len("rosrpc://"):].rstrip("/").rsplit(":", 1)
    service_address = (host, int(port))
    scans = {"count": 0, "counting": False}

    def on_scan(_msg):
        if scans["counting"]:
            scans["count"] += 1
    rospy.Subscriber("/scan", LaserScan, on_scan, queue_size=10)
    flooders = Flooders("ground_plane")
    flooders.start()
    listener = HangingListener()
    master = rosgraph.Master("/hostile_soak")
    sim_api = xmlrpc.client.ServerProxy("http://127.0.0.1:%s/" % master.lookupNode(
        "/gazebo").rstrip("/").rsplit(":", 1)[1])
    closed_port = free_port()
    clock = {"sim": 0.0, "wall": None, "gap": 0.0, "watch": False}
    lock = threading.Lock()

    def on_clock(msg):
        now = time.monotonic()
        with lock:
            if clock["wall"] is not None and clock["watch"]:
                clock["gap"] = max(clock["gap"], now - clock["wall"])
            clock["wall"], clock["sim"] = now, msg.clock.to_sec()
    rospy.Subscriber("/clock", Clock, on_clock, queue_size=100)

    def cpu_per_sim_second():
        time.sleep(2.0)
        cpu0, sim0 = cpu_seconds(pid), clock["sim"]
        time.sleep(QUIET)
        return (cpu_seconds(pid) - cpu0) / max(clock["sim"] - sim0, 1e-9)

    def call(service, *args):
        try:
            return service(*args)
        except rospy.ServiceException as err:
            return err

    box_pose = Pose()
    box_pose.position.x, box_pose.position.y, box_pose.position.z = 3.0, 3.0, 0.5
    box_pose.orientation.w = 1.0
    result = {"rss_idle": rss_mb(pid)}
    clock["watch"] = True
    start, rounds = time.monotonic(), 0
    while rounds < 2 or time.monotonic() - start < seconds:
        if rounds == 1:   # after one round: the mesh readers imported, the caches warm
            clock["watch"] = False
            result["rss_start"], result["cpu_start"] = rss_mb(pid), cpu_per_sim_second()
            result["threads_start"] = threads_of(pid)
            clock["watch"] = True
            start = time.monotonic()
            scans["count"], scans["counting"], scan_start = 0, True, clock["sim"]
        rounds += 1
        took = time.monotonic()
        for label, kind, name, text in inputs:
            answer = call(spawn[kind], name, text, "", box_pose, "world")
            if getattr(answer, "success", False):
                call(delete, name)
                print("  accepted: %s" % label, flush=True)
        for k in range(20):                       # 20 distinct sizes, the same each round
            size = 0.1 + 0.01 * k
            box = _sdf(_link("<box><size>%g %g %g</size></box>" % (size, size, size)))
            call(spawn["sdf"], "box", box, "", box_pose, "world")
            call(delete, "box")
        call(spawn["sdf"], "grid", _sdf(_link("<mesh><uri>%s</uri></mesh>" % mesh)), "",
             box_pose, "world")
        call(delete, "grid")
        for value in (float("nan"), 1e308):
            bad = Pose()
            bad.position.x, bad.orientation.w = value, 1.0
            call(set_state, ModelState("ground_plane", bad, Twist(), "world"))
        physics = call(get_physics)
        if getattr(physics, "success", False):
            ode = physics.ode_config
            for rate, cfm in ((5e-324, ode.cfm), (physics.max_update_rate, 1e6)):
                bad_ode = type(ode)(ode.auto_disable_bodies, ode.sor_pgs_precon_iters,
                                    ode.sor_pgs_iters, ode.sor_pgs_w, ode.sor_pgs_rms_error_tol,
                                    ode.contact_surface_layer, ode.contact_max_correcting_vel,
                                    cfm, ode.erp, ode.max_contacts)
                answer = call(set_physics, physics.time_step, rate, physics.gravity, bad_ode)
                if getattr(answer, "success", False):
                    print("  accepted: max_update_rate %g, cfm %g" % (rate, cfm), flush=True)
        link = call(get_link, "turtlebot3_burger::base_footprint")
        if getattr(link, "success", False):
            link.com.orientation.x = float("nan")
            answer = call(set_link, "turtlebot3_burger::base_footprint", link.com,
                          link.gravity_mode, link.mass, link.ixx, link.ixy, link.ixz, link.iyy,
                          link.iyz, link.izz)
            if getattr(answer, "success", False):
                print("  accepted: a NaN com orientation", flush=True)
        malformed_requests(service_address, 20)
        hanging = ["http://127.0.0.1:%d/hang%d" % (listener.port, k) for k in range(300)]
        hanging += ["http://127.0.0.1:%d/closed%d" % (closed_port, k) for k in range(300)]
        sim_api.publisherUpdate("/master", "/cmd_vel", hanging)
        readers = never_reading_subscribers(service_address, 100)
        time.sleep(2.0)
        for sock in readers:
            sock.close()
        sim_api.publisherUpdate("/master", "/cmd_vel", [])
        listener.drop()
        call(empties["pause_physics"])
        call(empties["unpause_physics"])
        call(empties["reset_world"])
        print("round %d: %.1f s, sim RSS %.1f MB, longest /clock gap so far %.2f s"
              % (rounds, time.monotonic() - took, rss_mb(pid), clock["gap"]), flush=True)
    clock["watch"] = False
    scans["counting"] = False
    result["scan_hz"] = scans["count"] / max(clock["sim"] - scan_start, 1e-9)
    flooders.stop()
    listener.close()
    result["cpu_end"] = cpu_per_sim_second()
    result["rss_end"] = rss_mb(pid)
    result["threads_end"] = threads_of(pid)
    result["gap"] = clock["gap"]
    result["flooded"] = flooders.sent
    answer = call(world)
    result["alive"] = bool(getattr(answer, "success", False))
    result["rounds"] = rounds
    print("RESULT %.2f %.1f %.1f %.4f %.4f %s %.1f %d %d %d %.2f" % (
        result["gap"], result["rss_start"], result["rss_end"], result["cpu_start"],
        result["cpu_end"], "alive" if result["alive"] else "DEAD", result["rss_idle"], rounds,
        result["threads_start"], result["threads_end"], result["scan_hz"]), flush=True)
    print("set_model_state messages flooded: %d" % result["flooded"], flush=True)
    rospy.signal_shutdown("hostile soak done")
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--minutes", type=float, default=10.0, help="wall minutes of replay")
    args = parser.parse_args()
    soak(args.minutes)


if __name__ == "__main__":
    main()
