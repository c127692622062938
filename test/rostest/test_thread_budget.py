#!/usr/bin/env python3
"""rostest node: the sim's threads are a budget (thread_budget.test).

- publisherUpdate of /cmd_vel naming 1,000 publishers that accept and never answer (one
  listener of this test on 127.0.0.1) and 2,000 on a closed port: the sim's threads stay within
  MAX_PUBLISHERS_PER_TOPIC (+ slack) of its count before, /clock keeps pace, and after an empty
  update the connect threads end.
- Up to 2,000 subscribers of /gazebo/parameter_updates with valid handshakes and distinct
  callerids that never read (as many as the sim accepts in ATTACK s, at least AT_LEAST):
  the threads stay within MAX_SUBSCRIBERS_PER_TOPIC + the handshake guard's
  MAX_PENDING (+ slack), a fresh get_physics_properties is answered, and once they close their
  writer threads end within a few seconds.
All traffic is on 127.0.0.1; every loop is bounded in count and time.
"""
import socket
import threading
import time
import unittest
import xmlrpc.client

import rosgraph.masterapi
import rospy
import rostest
from dynamic_reconfigure.msg import Config
from gazebo_msgs.srv import GetPhysicsProperties
from rosgraph.network import write_ros_handshake_header
from rosgraph_msgs.msg import Clock

from sim_test_support import WAIT, Recorder, free_port, wait_for
from tutorial_turtlebot.gazebo.impl.connection_caps import MAX_SUBSCRIBERS_PER_TOPIC
from tutorial_turtlebot.gazebo.impl.publisher_connects import MAX_PUBLISHERS_PER_TOPIC
from tutorial_turtlebot.gazebo.impl.tcpros_guard import MAX_PENDING

HANGING = 1000
CLOSED = 2000
SUBSCRIBERS = 2000
SLACK = 12             # threads the sim may start meanwhile for its own work
ANSWER = 2.0           # s: the longest a fresh service call may take under attack
AT_LEAST = 500        # of them opened within ATTACK (a loaded 2-core machine: about 1,100)
ATTACK = 75.0         # s: the longest the test takes to open its subscribers
SETTLE = 30.0          # s: the longest for threads to end once the attack is over


def threads_of(pid) -> int:
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith("Threads:"):
                return int(line.split()[1])
    return 0


class Sampler:
    """The sim's thread count every 0.1 s, in a thread, until stop(); its maximum."""

    def __init__(self, pid):
        self.pid, self.peak, self._stop = pid, threads_of(pid), threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self):
        while not self._stop.wait(0.1):
            self.peak = max(self.peak, threads_of(self.pid))

    def stop(self) -> int:
        self._stop.set()
        self._thread.join(2.0)
        return self.peak


class HangingListener:
    """Accepts on 127.0.0.1 and never answers; holds at most ``limit`` sockets."""

    def __init__(self, limit=400):
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(128)
        self.port = self.sock.getsockname()[1]
        self.limit, self.held = limit, []
        threading.Thread(target=self._accept, daemon=True).start()

    def _accept(self):
        self.sock.settimeout(1.0)
        deadline = time.monotonic() + 200.0
        while len(self.held) < self.limit and time.monotonic() < deadline:
            try:
                self.held.append(self.sock.accept()[0])
            except socket.timeout:
                continue
            except OSError:
                return

    def close(self):
        self.limit = 0
        self.sock.close()
        for sock in self.held:
            sock.close()


class ThreadBudgetTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_thread_budget")
        rospy.wait_for_service("/gazebo/get_physics_properties", timeout=WAIT)
        cls.get_physics = rospy.ServiceProxy("/gazebo/get_physics_properties",
                                             GetPhysicsProperties)
        cls.clock = Recorder("/clock", Clock)
        assert cls.clock.latest(WAIT) is not None, "no /clock"
        master = rosgraph.masterapi.Master(rospy.get_name())
        port = int(master.lookupNode("/gazebo").rstrip("/").rsplit(":", 1)[1])
        cls.sim_uri = "http://127.0.0.1:%d/" % port    # loopback only, whatever the hostname
        _, _, cls.pid = xmlrpc.client.ServerProxy(cls.sim_uri).getPid(rospy.get_name())
        uri = master.lookupService("/gazebo/get_physics_properties")
        cls.tcpros = ("127.0.0.1", int(uri.rstrip("/").rsplit(":", 1)[1]))

    def settled_threads(self) -> int:
        """The sim's thread count once it stopped changing (at most 10 s)."""
        last = threads_of(self.pid)
        for _ in range(20):
            time.sleep(0.5)
            now = threads_of(self.pid)
            if now == last:
                return now
            last = now
        return last

    def sim_time_pace(self, wall=3.0) -> float:
        """Sim seconds per wall second over ``wall`` s."""
        start_sim, start = self.clock.latest().clock.to_sec(), time.monotonic()
        time.sleep(wall)
        return (self.clock.latest().clock.to_sec() - start_sim) / (time.monotonic() - start)

    def publisher_update(self, uris):
        sim = xmlrpc.client.ServerProxy(self.sim_uri)
        code, msg, _ = sim.publisherUpdate("/master", "/cmd_vel", uris)
        self.assertEqual(code, 1, msg)

    def test_hanging_publishers_are_bounded_and_given_up(self):
        before = self.settled_threads()
        listener = HangingListener()
        sampler = Sampler(self.pid)
        try:
            uris = ["http://127.0.0.1:%d/hang%d" % (listener.port, i) for i in range(HANGING)]
            closed = free_port()
            uris += ["http://127.0.0.1:%d/closed%d" % (closed, i) for i in range(CLOSED)]
            self.publisher_update(uris)
            pace = self.sim_time_pace(5.0)
            during = threads_of(self.pid)
            self.publisher_update([])
            ended = wait_for(lambda: threads_of(self.pid) <= before + 2, SETTLE)
            after = threads_of(self.pid)
        finally:
            peak = sampler.stop()
            listener.close()
        rospy.loginfo("hanging publishers: threads %d before, %d during, peak %d, %d after; "
                      "sim time pace %.2f; the listener held %d connections", before, during,
                      peak, after, pace, len(listener.held))
        self.assertLessEqual(peak, before + MAX_PUBLISHERS_PER_TOPIC + SLACK)
        self.assertGreater(pace, 0.8, "/clock did not keep pace")
        self.assertTrue(ended, "connect threads still running: %d, %d before" % (after, before))
        self.assertLessEqual(len(listener.held), 3 * MAX_PUBLISHERS_PER_TOPIC + 10)

    def subscribe_never_reading(self, socks, count, workers=8):
        """``count`` subscribers of parameter_updates (valid handshakes, distinct callerids)
        that never read, from ``workers`` threads, within ATTACK s; their sockets in socks."""
        deadline = time.monotonic() + ATTACK
        lock = threading.Lock()
        numbers = iter(range(count))

        def run():
            while time.monotonic() < deadline:
                with lock:
                    i = next(numbers, None)
                if i is None:
                    return
                try:
                    sock = socket.create_connection(self.tcpros, timeout=5.0)
                except OSError:
                    continue
                with lock:
                    socks.append(sock)
                try:
                    write_ros_handshake_header(sock, {
                        "topic": "/gazebo/parameter_updates", "md5sum": Config._md5sum,
                        "type": Config._type, "callerid": "/never_reads_%d" % i})
                except OSError:
                    pass   # refused and closed by the sim already
        threads = [threading.Thread(target=run, daemon=True) for _ in range(workers)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join(ATTACK + 10.0)

    def test_subscribers_that_never_read_are_capped_and_end_with_their_connection(self):
        before = self.settled_threads()
        sampler = Sampler(self.pid)
        socks = []
        try:
            self.subscribe_never_reading(socks, SUBSCRIBERS)
            opened = len(socks)
            self.assertGreaterEqual(opened, AT_LEAST, "only %d subscribers in %.0f s"
                                    % (opened, ATTACK))
            time.sleep(1.0)
            start = time.monotonic()
            physics = self.get_physics()
            took = time.monotonic() - start
            during = threads_of(self.pid)
        finally:
            for sock in socks:
                sock.close()
        ended = wait_for(lambda: threads_of(self.pid) <= before + 2, SETTLE)
        after = threads_of(self.pid)
        peak = sampler.stop()
        rospy.loginfo("%d never-reading subscribers: threads %d before, %d during, peak %d, "
                      "%d after they closed; get_physics_properties %.3f s", opened, before,
                      during, peak, after, took)
        self.assertGreater(physics.time_step, 0.0)
        self.assertLess(took, ANSWER)
        self.assertLessEqual(peak, before + MAX_SUBSCRIBERS_PER_TOPIC + MAX_PENDING + SLACK)
        self.assertTrue(ended, "writer threads still running: %d, %d before" % (after, before))


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "thread_budget", ThreadBudgetTest)
