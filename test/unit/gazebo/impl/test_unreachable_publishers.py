"""The line about an unreachable publisher, and the master watch's decisions, without a master:
fake masters and closed local ports."""
import socket

import pytest

from tutorial_turtlebot.gazebo.impl import unreachable_publishers
from tutorial_turtlebot.gazebo.impl.unreachable_publishers import UnreachableLog, describe_error

from unit_helpers import free_port as closed_port

HINT = "is ROS_IP or ROS_HOSTNAME set on its machine?"


def test_one_line_per_topic_and_publisher():
    lines = []
    log = UnreachableLog(lines.append, name_of=lambda topic, uri: "/teleop")
    refused = ConnectionRefusedError(111, "Connection refused")
    assert log.report("/cmd_vel", "http://badhost:4567/", refused, ("10.0.0.5", 40123))
    assert not log.report("/cmd_vel", "http://badhost:4567/", refused)
    assert not log.report("/cmd_vel", "http://badhost:4567/", socket.timeout("timed out"))
    assert log.report("/cmd_vel", "http://other:1/", socket.gaierror(-2, "Name or service not "
                                                                     "known"))
    assert log.report("/tb3_0/cmd_vel", "http://badhost:4567/", refused)
    assert lines == [
        "cannot reach /teleop's publisher of /cmd_vel at http://badhost:4567/ (TCPROS "
        "10.0.0.5:40123): connection refused; " + HINT,
        "cannot reach /teleop's publisher of /cmd_vel at http://other:1/: name or service not "
        "known; " + HINT,
        "cannot reach /teleop's publisher of /tb3_0/cmd_vel at http://badhost:4567/: connection "
        "refused; " + HINT]


def test_a_publisher_whose_name_is_not_known_is_still_named_by_its_address():
    lines = []

    def no_master(topic, uri):
        raise OSError("no master")
    UnreachableLog(lines.append, name_of=no_master).report(
        "/cmd_vel", "http://h:1/", socket.timeout("timed out"))
    assert lines == ["cannot reach a publisher of /cmd_vel at http://h:1/: timed out; " + HINT]


def test_describe_error_reads_the_socket_error_under_rospy_s():
    try:
        try:
            raise ConnectionRefusedError(111, "Connection refused")
        except OSError as err:
            raise RuntimeError(str(err))
    except RuntimeError as wrapped:
        assert describe_error(wrapped) == "connection refused"
    assert describe_error(ValueError("odd")) == "odd"


def test_rospy_s_failures_are_reported_and_still_raised():
    """install() wraps rospy's requestTopic proxy and its subscriber connect; both still fail
    as rospy expects, after one line each."""
    pytest.importorskip("rospy")
    import rospy.impl.masterslave as masterslave
    from rospy.exceptions import TransportInitError
    from rospy.impl.tcpros_base import TCPROSTransport
    from rospy.impl.tcpros_pubsub import TCPROSSub
    from std_msgs.msg import String

    lines = []
    unreachable_publishers.install(UnreachableLog(lines.append, name_of=lambda t, u: None))
    uri = "http://127.0.0.1:%d/" % closed_port()
    with pytest.raises(OSError):
        masterslave.xmlrpcapi(uri, cache=False).requestTopic("/sim", "/cmd_vel", [["TCPROS"]])
    port = closed_port()
    conn = TCPROSTransport(TCPROSSub("/chatter", String), "/chatter")
    with pytest.raises(TransportInitError):
        conn.connect("127.0.0.1", port, "http://fake:1/", timeout=5.0)
    assert lines == [
        "cannot reach a publisher of /cmd_vel at %s: connection refused; %s" % (uri, HINT),
        "cannot reach a publisher of /chatter at http://fake:1/ (TCPROS 127.0.0.1:%d): "
        "connection refused; %s" % (port, HINT)]


class FakeMaster:
    def __init__(self, pid, nodes, params):
        self.pid, self.nodes, self.params = pid, nodes, params

    def getPid(self, caller_id):  # noqa: N802 - the XML-RPC names
        return 1, "", self.pid

    def lookupNode(self, caller_id, node):  # noqa: N802
        return (1, "", "http://sim:1/") if node in self.nodes else (-1, "unknown node", "")

    def getParam(self, caller_id, name):  # noqa: N802
        return (1, "", self.params[name]) if name in self.params else (-1, "no", 0)

    def hasParam(self, caller_id, name):  # noqa: N802
        return 1, "", name in self.params

    def setParam(self, caller_id, name, value):  # noqa: N802
        self.params[name] = value
        return 1, "", 0


def test_master_watch_registers_again_only_with_a_new_master(monkeypatch):
    pytest.importorskip("rospy")
    import rospy.impl.registration as registration
    from tutorial_turtlebot.gazebo.impl import master_watch

    class Registrar:
        added = []

        def reg_added(self, name, type_or_uri, kind):
            self.added.append((name, kind))

    class Manager:
        def get_publications(self):
            return [("/odom", "nav_msgs/Odometry"), ("/clock", "rosgraph_msgs/Clock")]

        def get_subscriptions(self):
            return [("/cmd_vel", "geometry_msgs/Twist"), ("/odom", "nav_msgs/Odometry")]

        def get_services(self):
            return [("/gazebo/reset_world", "rosrpc://sim:2")]

    monkeypatch.setattr(master_watch, "rospy_registrar", Registrar)
    monkeypatch.setattr(registration, "get_topic_manager", Manager)
    monkeypatch.setattr(registration, "get_service_manager", Manager)
    old = FakeMaster(10, {"/gazebo"}, {"/use_sim_time": True, "/robot_description": "<r/>",
                                       "/tb3_0/robot_description": "<r0/>"})
    current = [old]
    monkeypatch.setattr(master_watch, "master_proxy", lambda uri: current[0])
    lines = []
    namespaces = [[""]]
    watch = master_watch.MasterWatch(lambda: namespaces[0], log=lines.append)
    watch.caller_id, watch.namespace = "/gazebo", "/"
    assert not watch.check() and not watch.check()       # the same master: nothing
    namespaces[0] = ["", "/tb3_0/"]                      # a robot spawned in a namespace
    assert not watch.check()
    assert watch.params == {"/robot_description": "<r/>", "/tb3_0/robot_description": "<r0/>"}
    assert Registrar.added == [] and lines == []

    new = FakeMaster(20, set(), {"/robot_description": "set by the new launch"})
    current[0] = new
    assert watch.check()
    assert lines == ["ROS master restarted: registered again 3 topics, 1 services, "
                     "2 parameters"]
    assert new.params == {"/robot_description": "set by the new launch", "/use_sim_time": True,
                          "/tb3_0/robot_description": "<r0/>"}
    assert len(Registrar.added) == 5
    new.nodes.add("/gazebo")
    assert not watch.check()                               # registered: nothing more
    current[0] = FakeMaster(30, {"/gazebo"}, {})           # restarted, and a spawn already
    assert watch.check()                                   # registered one topic: the pid says


def test_master_watch_waits_while_the_master_is_down(monkeypatch):
    pytest.importorskip("rospy")
    from tutorial_turtlebot.gazebo.impl import master_watch
    monkeypatch.setattr(master_watch, "master_proxy",
                        lambda uri: master_watch.xmlrpc.client.ServerProxy(
                            "http://127.0.0.1:%d/" % closed_port()))
    watch = master_watch.MasterWatch(log=lambda line: None)
    assert not watch.check() and watch.master_pid is None
