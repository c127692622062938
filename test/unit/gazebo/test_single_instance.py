"""gazebo/single_instance.py without a master: where nothing listens at the master's address no
simulator runs, and that is found with a plain connect (robot_description --new-sim runs before
roscore starts, on the way of every sim.launch: no rosgraph, no XML-RPC). No ROS master."""
import os
import socket
import subprocess
import sys

from tutorial_turtlebot.gazebo import single_instance


def free_port() -> int:
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def test_nothing_listening_is_no_master_and_no_simulator():
    uri = "http://127.0.0.1:%d" % free_port()
    assert single_instance._no_master_listens(uri)
    assert single_instance.running_simulator(master_uri=uri) is None
    # a fresh Python finds it without importing XML-RPC (nor rosgraph, which imports it)
    check = ("import sys; from tutorial_turtlebot.gazebo.single_instance import "
             "running_simulator as r; assert r(master_uri=%r) is None; "
             "print(sorted(m for m in ('xmlrpc.client', 'rosgraph') if m in sys.modules))" % uri)
    out = subprocess.run([sys.executable, "-c", check], capture_output=True, text=True,
                         env=dict(os.environ), check=True)
    assert out.stdout.strip() == "[]"


def test_something_listening_is_asked_as_a_master(monkeypatch):
    with socket.socket() as server:
        server.bind(("127.0.0.1", 0))
        server.listen(1)
        uri = "http://127.0.0.1:%d" % server.getsockname()[1]
        assert not single_instance._no_master_listens(uri)
        monkeypatch.setenv("ROS_MASTER_URI", uri)
        assert not single_instance._no_master_listens(None)
    # an address it cannot read: left to rosgraph, as before
    assert not single_instance._no_master_listens("not a uri")
