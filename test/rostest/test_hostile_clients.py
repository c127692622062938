#!/usr/bin/env python3
"""rostest node: careless and hostile clients against the real sim.

- Raw sockets on the sim's TCPROS port (the one its topics and services share): headers that
  stop after 2 bytes, HTTP requests, 20 of them held open, one streaming a 100 MB header.
  Meanwhile a new subscriber gets /odom and a service answers within 1 s, and the sim's RSS
  stays within a few MB.
- A pace too slow to run (max_update_rate 1e-6) is refused, by the service and by
  dynamic_reconfigure, and /clock goes on; at the slowest pace allowed and while paused a
  service answers within 1 s.
- Ctrl-C (SIGINT) ends a sim of its own (own master on a free port) within 2 s: at real time,
  as fast as possible, paused, at the slowest pace, in the middle of a robot's spawn, and
  while a heavy spawn is being prepared (the convex hull of a 60,000-vertex movable mesh: about
  8 s of work in the service's thread).
"""
import math
import os
import shutil
import socket
import struct
import subprocess
import tempfile
import threading
import time
import unittest
import xmlrpc.client

import rosgraph
import rosgraph.masterapi
import rospy
import rostest
from gazebo_msgs.srv import (GetModelState, GetPhysicsProperties, GetWorldProperties,
                             SetPhysicsProperties)
from gazebo_msgs.srv import SpawnModel
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty

from sim_test_support import (WAIT, NodeProcess, Recorder, executable, free_port, rss_kb,
                              wait_for)

ANSWER = 1.0          # s: the longest a service may take while the sim is under attack
STOP = 2.0            # s: the longest from SIGINT to the sim's exit
RSS_GROWTH = 8 << 10  # KB the sim may grow by under attack
SLOWEST_FACTOR = 0.01


def sim_pid_and_port():
    """The sim's pid (from its XML-RPC API) and its TCPROS address (from a service's URI)."""
    master = rosgraph.masterapi.Master(rospy.get_name())
    uri = master.lookupNode("/gazebo")
    _, _, pid = xmlrpc.client.ServerProxy(uri).getPid(rospy.get_name())
    service_uri = master.lookupService("/gazebo/get_world_properties")
    host, port = service_uri[len("rosrpc://"):].rstrip("/").rsplit(":", 1)
    return pid, (host, int(port))


def timed(call, *args, **kwargs):
    start = time.monotonic()
    result = call(*args, **kwargs)
    return time.monotonic() - start, result


class Attack:
    """Hostile connections to ``address``, held until close()."""

    def __init__(self, address):
        self.address = address
        self.socks = []
        self.streamed = 0
        self.stream_ended = threading.Event()

    def half_open(self, count):
        for _ in range(count):
            sock = socket.create_connection(self.address, timeout=5.0)
            sock.sendall(b"\x40\x00")  # 2 of the 4 bytes of a length field, then nothing
            self.socks.append(sock)

    def http(self, count):
        for _ in range(count):
            sock = socket.create_connection(self.address, timeout=5.0)
            sock.sendall(b"GET / HTTP/1.1\r\nHost: sim\r\n\r\n")
            self.socks.append(sock)

    def stream_header(self, size=100_000_000, at_most=50_000_000):
        """A header announcing ``size`` bytes and sending them (up to ``at_most`` or until the
        sim closes it), in a thread."""
        def run():
            sock = socket.create_connection(self.address, timeout=5.0)
            self.socks.append(sock)
            chunk = b"message_definition=" + b"x" * 65517
            try:
                sock.sendall(struct.pack("<I", size))
                while self.streamed < at_most:
                    self.streamed += sock.send(chunk)
            except OSError:  # reset, broken pipe or a timeout: the sim stopped reading
                pass
            self.stream_ended.set()
        threading.Thread(target=run, daemon=True).start()

    def close(self):
        for sock in self.socks:
            try:
                sock.close()
            except OSError:
                pass


class HostileClientsTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_hostile_clients")
        for name in ("get_world_properties", "get_physics_properties", "set_physics_properties",
                     "pause_physics", "unpause_physics"):
            rospy.wait_for_service("/gazebo/" + name, timeout=WAIT)
        cls.world = rospy.ServiceProxy("/gazebo/get_world_properties", GetWorldProperties)
        cls.get_physics = rospy.ServiceProxy("/gazebo/get_physics_properties",
                                             GetPhysicsProperties)
        cls.set_physics = rospy.ServiceProxy("/gazebo/set_physics_properties",
                                             SetPhysicsProperties)
        cls.pause = rospy.ServiceProxy("/gazebo/pause_physics", Empty)
        cls.unpause = rospy.ServiceProxy("/gazebo/unpause_physics", Empty)
        cls.clock = Recorder("/clock", Clock)
        assert cls.clock.latest(WAIT) is not None, "no /clock"

    def tearDown(self):
        self.unpause()
        self.set_rate(1.0 / self.get_physics().time_step)  # real time

    def set_rate(self, max_update_rate):
        physics = self.get_physics()
        return self.set_physics(time_step=physics.time_step, max_update_rate=max_update_rate,
                                gravity=physics.gravity, ode_config=physics.ode_config)

    def assert_answers(self, what, times=5):
        """get_world_properties, each call on a new connection, within ANSWER s."""
        for _ in range(times):
            took, resp = timed(self.world)
            self.assertTrue(resp.success)
            self.assertLess(took, ANSWER, "%s: get_world_properties took %.2f s" % (what, took))
        return took

    def clock_moves(self, wall=3.0) -> bool:
        start = self.clock.latest().clock
        return wait_for(lambda: self.clock.latest().clock > start, wall)

    # --- hostile connections ---------------------------------------------------------------------

    def test_hostile_connections_lock_nobody_out(self):
        pid, address = sim_pid_and_port()
        rss_before = rss_kb(pid)
        attack = Attack(address)
        try:
            attack.half_open(15)
            attack.http(5)
            attack.stream_header()
            time.sleep(0.3)
            took = self.assert_answers("20 stalled connections and a 100 MB header")
            start = time.monotonic()
            odom = Recorder("/odom", Odometry)
            self.assertIsNotNone(odom.latest(10.0), "a new /odom subscriber got nothing")
            first_odom = time.monotonic() - start
            odom.sub.unregister()
            self.assertTrue(attack.stream_ended.wait(10.0), "the 100 MB header is still read")
            self.assertLess(attack.streamed, 20_000_000,
                            "the sim read %d bytes of a 100 MB header" % attack.streamed)
            rss_during = rss_kb(pid)
            rospy.loginfo("under attack: service %.3f s, first /odom %.3f s, header streamed "
                          "%d bytes, RSS %+.1f MB", took, first_odom, attack.streamed,
                          (rss_during - rss_before) / 1024.0)
            # Held open past the time limit: closed by the sim, and the others still pass.
            time.sleep(2.5)
            for sock in attack.socks[:20]:
                sock.settimeout(2.0)
                try:
                    self.assertEqual(sock.recv(1), b"", "a stalled connection is still open")
                except ConnectionResetError:
                    pass
            attack.half_open(20)
            self.assertLess(rss_kb(pid) - rss_before, RSS_GROWTH)
            self.assert_answers("20 more stalled connections")
        finally:
            attack.close()
        self.assertLess(rss_kb(pid) - rss_before, RSS_GROWTH)

    # --- pace ----------------------------------------------------------------------------------

    def test_a_pace_too_slow_is_refused_and_the_clock_goes_on(self):
        resp = self.set_rate(1e-6)
        self.assertFalse(resp.success)
        self.assertIn("max_update_rate", resp.status_message)
        self.assertNotEqual(self.get_physics().max_update_rate, 1e-6)
        self.assertTrue(self.clock_moves(), "/clock stopped")
        from dynamic_reconfigure.client import Client
        client = Client("/gazebo", timeout=WAIT)
        config = client.update_configuration({"max_update_rate": 1e-6})
        self.assertNotEqual(config["max_update_rate"], 1e-6)
        self.assertNotEqual(self.get_physics().max_update_rate, 1e-6)
        self.assertTrue(self.clock_moves(), "/clock stopped")

    def test_services_answer_at_the_slowest_pace_and_paused(self):
        physics = self.get_physics()
        resp = self.set_rate(SLOWEST_FACTOR / physics.time_step)
        self.assertTrue(resp.success, resp.status_message)
        self.assertTrue(self.clock_moves(3.0), "/clock stopped at the slowest pace")
        slow = self.assert_answers("slowest pace")
        self.pause()
        paused = self.assert_answers("paused")
        self.unpause()
        rospy.loginfo("get_world_properties: %.3f s at the slowest pace, %.3f s paused",
                      slow, paused)

    # --- malformed requests -------------------------------------------------------------------

    def test_malformed_requests_are_one_line_per_client_never_a_traceback(self):
        """Bodies that do not deserialize (a string length of 0xffffffff) and bodies cut short,
        30 of each from two clients: the sim (a sim of its own: its stderr is read) writes one
        warning per client and no traceback, and answers a good request after them."""
        sim = OwnSim()
        try:
            self.assertTrue(wait_for(lambda: sim.service("get_model_state") is not None,
                                     WAIT), "the sim's services did not come up")
            address = sim.service("get_model_state")
            # GetModelState's request begins with a string: its length 0xffffffff
            bad_length = struct.pack("<I", 8) + struct.pack("<I", 0xffffffff) + b"abcd"
            for client, body in (("/garbage", bad_length), ("/cut_short", b"\x64\0\0\0abc")):
                for _ in range(30):
                    send_raw_request(address, "/gazebo/get_model_state", GetModelState, client,
                                     body)
            self.assertEqual(sim.call("get_world_properties", GetWorldProperties), b"\x01")
            time.sleep(1.0)
        finally:
            sim.close()
        err = sim.sim.stderr
        self.assertNotIn("Traceback", err)
        self.assertEqual(err.count("malformed request from /garbage"), 1, err[-2000:])
        self.assertLessEqual(err.count("from /cut_short"), 1, err[-2000:])
        self.assertNotIn("[ERROR]", err)     # (rospy's "incoming connection failed" line)

    # --- Ctrl-C ----------------------------------------------------------------------------------

    def test_ctrl_c_in_every_state(self):
        urdf = subprocess.run([executable("robot_description"), "burger"], check=True,
                              stdout=subprocess.PIPE, text=True).stdout
        times = {}
        for state, args in (("real time", []), ("as fast as possible", ["_real_time_factor:=0"]),
                            ("paused", ["_paused:=true"]),
                            ("slowest pace", ["_real_time_factor:=%g" % SLOWEST_FACTOR]),
                            ("spawning", []), ("preparing a heavy spawn", [])):
            sim = OwnSim(*args)
            try:
                self.assertTrue(wait_for(lambda: sim.service("get_world_properties"), WAIT),
                                "the sim did not start: %s" % sim.sim.stderr[-2000:])
                time.sleep(1.0)
                if state == "spawning":
                    threading.Thread(target=sim.call, daemon=True,
                                     args=("spawn_urdf_model", SpawnModel),
                                     kwargs=dict(model_name="tb3_1", model_xml=urdf,
                                                 robot_namespace="tb3_1",
                                                 reference_frame="world")).start()
                    time.sleep(0.05)
                if state == "preparing a heavy spawn":
                    threading.Thread(target=sim.call, daemon=True,
                                     args=("spawn_sdf_model", SpawnModel),
                                     kwargs=dict(model_name="ball", model_xml=self.ball_sdf(),
                                                 reference_frame="world")).start()
                    time.sleep(1.5)   # the spawn is read, its hull being built
                times[state] = sim.interrupt()
            finally:
                sim.close()
        rospy.loginfo("SIGINT to exit: %s", ", ".join(
            "%s %s" % (state, "never" if t is None else "%.2f s" % t)
            for state, t in times.items()))
        for state, took in times.items():
            self.assertIsNotNone(took, "%s: the sim ignored SIGINT for 10 s" % state)
            self.assertLess(took, STOP, "%s: the sim took %.2f s to stop" % (state, took))

    def ball_sdf(self):
        """A movable model whose mesh is 60,000 points on a 0.2 m sphere (an OBJ of our own,
        in a temporary folder): every point is a corner of its convex hull."""
        folder = tempfile.mkdtemp(prefix="ctrl_c_ball_")
        self.addCleanup(shutil.rmtree, folder, True)
        path = os.path.join(folder, "ball.obj")
        count = 60000
        golden = math.pi * (3.0 - math.sqrt(5.0))
        with open(path, "w") as f:
            for i in range(count):   # a Fibonacci sphere: evenly spread, all on the hull
                z = 1.0 - 2.0 * (i + 0.5) / count
                r = math.sqrt(1.0 - z * z)
                f.write("v %.6f %.6f %.6f\n" % (0.2 * r * math.cos(golden * i),
                                                0.2 * r * math.sin(golden * i), 0.2 * z))
            for i in range(0, count - 2, 3):
                f.write("f %d %d %d\n" % (i + 1, i + 2, i + 3))
        mesh = "<geometry><mesh><uri>file://%s</uri></mesh></geometry>" % path
        return ("<sdf version='1.6'><model name='ball'><pose>0 0 1 0 0 0</pose><link name='l'>"
                "<inertial><mass>1</mass></inertial><collision name='c'>%s</collision>"
                "<visual name='v'>%s</visual></link></model></sdf>" % (mesh, mesh))


class OwnSim:
    """A sim of its own on its own master (``rosmaster --core`` on a free port)."""

    def __init__(self, *args):
        port = free_port()
        self.env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d" % port)
        self.master = subprocess.Popen(["rosmaster", "--core", "-p", str(port)], env=self.env,
                                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.sim = NodeProcess("sim", "_world:=empty", "_status_period:=0", *args, env=self.env)

    def service(self, name):
        """(host, port) of one of its services, None while it is not there."""
        master = xmlrpc.client.ServerProxy(self.env["ROS_MASTER_URI"])
        try:
            code, _, uri = master.lookupService("/ctrl_c_test", "/gazebo/" + name)
        except OSError:
            return None
        if code != 1:
            return None
        host, port = uri[len("rosrpc://"):].rstrip("/").rsplit(":", 1)
        return host, int(port)

    def call(self, name, srv_type, **fields):
        """Call one of its services by hand (the test's own node is on the other master)."""
        return call_service(self.service(name), "/gazebo/" + name, srv_type, fields)

    def interrupt(self):
        """SIGINT: the wall s until it ended (None if it did not within 10 s)."""
        start = time.monotonic()
        status = self.sim.interrupt(10.0)
        return None if status is None else time.monotonic() - start

    def close(self):
        self.sim.kill()
        if self.master.poll() is None:
            self.master.terminate()
            self.master.wait(10.0)


def send_raw_request(address, name, srv_type, callerid, body):
    """A valid handshake for service ``name``, then ``body`` as the request's bytes; the
    connection is closed after at most 1 s of waiting for an answer."""
    from io import BytesIO
    from rosgraph.network import read_ros_handshake_header, write_ros_handshake_header
    with socket.create_connection(address, timeout=5.0) as sock:
        write_ros_handshake_header(sock, {"callerid": callerid, "service": name,
                                          "md5sum": srv_type._md5sum, "persistent": "0"})
        read_ros_handshake_header(sock, BytesIO(), 4096)
        sock.sendall(body)
        sock.settimeout(1.0)
        try:
            sock.recv(100)
        except OSError:
            pass


def call_service(address, name, srv_type, fields):
    """One call of service ``name`` at ``address`` over a plain TCPROS socket."""
    from io import BytesIO
    from rosgraph.network import read_ros_handshake_header, write_ros_handshake_header
    request = srv_type._request_class(**fields)
    with socket.create_connection(address, timeout=30.0) as sock:
        write_ros_handshake_header(sock, {"callerid": "/ctrl_c_test", "service": name,
                                          "md5sum": srv_type._md5sum, "persistent": "0"})
        read_ros_handshake_header(sock, BytesIO(), 4096)
        data = BytesIO()
        request.serialize(data)
        sock.sendall(struct.pack("<I", len(data.getvalue())) + data.getvalue())
        return sock.recv(1)  # the ok byte (or nothing if the sim stopped)


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "hostile_clients", HostileClientsTest)
