"""The /gazebo node's hold on its robots (gazebo/sim_node, no ROS master: stand-in publishers,
subscriber and service; a real Simulation): a robot whose topics cannot be made is taken out of
the world again with a one-line error, and one robot's output that fails is skipped and named
in one line while the others go on (both once ended the node)."""
import pytest

from tutorial_turtlebot.gazebo import robot_topics, sim_node
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import RequestError, WorldControl

from unit_helpers import at, urdf_text


class FakeEndpoint:
    """A publisher, subscriber or service that records what is done with it."""

    made = []

    def __init__(self, name, *args, **kwargs):
        self.name, self.closed, self.sent = name, False, 0
        FakeEndpoint.made.append(self)

    def get_num_connections(self):
        return 1

    def publish_packed(self, _packed):
        self.sent += 1

    def unregister(self):
        self.closed = True

    shutdown = unregister


def refusing(topic_end):
    """A make_publisher that refuses topics ending with ``topic_end`` as rospy can."""
    def make(name, msg_type, queue_size=1):
        if name.endswith(topic_end):
            raise ValueError("%s: refused" % name)
        return FakeEndpoint(name)
    return make


@pytest.fixture
def node(monkeypatch):
    """A SimNode of an empty world with no robot, only what sync_robots and _publish_due
    touch; robots come by WorldControl.spawn."""
    monkeypatch.setattr(robot_topics.rospy, "Subscriber", FakeEndpoint)
    monkeypatch.setattr(robot_topics.rospy, "Service", FakeEndpoint)
    FakeEndpoint.made = []
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    node = object.__new__(sim_node.SimNode)
    node.sim, node.robot_topics, node._topics, node._output_errors = sim, {}, [], {}
    node.advertise, node.tf_pub = FakeEndpoint, FakeEndpoint("/tf")
    node.publishers = {"clock": lambda stamp: None}
    node.control = WorldControl(sim)
    yield node
    sim.close()


def spawn(node, name, namespace):
    node.control.spawn(name, urdf_text("burger"), at(0.0, 3.0 * len(node.sim.robots)),
                       kind="urdf", robot_namespace=namespace)


def test_a_robot_whose_topics_fail_is_taken_out_again_in_one_line(node):
    spawn(node, "tb3_0", "tb3_0")
    node.sync_robots()
    node.advertise = refusing("/tb3_1/scan")     # after odom and joint_states
    spawn(node, "tb3_1", "tb3_1")
    made_before = len(FakeEndpoint.made)
    with pytest.raises(RequestError) as err:
        node.sync_robots()
    message = str(err.value)
    assert "\n" not in message
    assert message == ("robot 'tb3_1': its topics could not be made: ValueError: "
                       "/tb3_1/scan: refused")
    made = FakeEndpoint.made[made_before:]
    assert [p.name for p in made] == ["/tb3_1/odom", "/tb3_1/joint_states"]
    assert all(p.closed for p in made)                   # nothing of it is left advertised
    assert list(node.sim.robots) == ["tb3_0"] and "tb3_1" not in node.sim.models
    assert list(node.robot_topics) == ["tb3_0"] and len(node._topics) == 1
    for _ in range(400):                                 # the loop goes on (was: KeyError)
        node._publish_due(node.sim.step())
    node.advertise = FakeEndpoint
    spawn(node, "tb3_1", "tb3_1")                        # the name and namespace are free again
    node.sync_robots()
    assert sorted(node.robot_topics) == ["tb3_0", "tb3_1"]


def test_an_output_that_fails_is_skipped_and_named_once_and_the_others_go_on(node, monkeypatch):
    spawn(node, "tb3_0", "tb3_0")
    spawn(node, "tb3_1", "tb3_1")
    node.sync_robots()

    def broken(_stamp):
        raise MemoryError("scan of 300000000 rays")
    node.robot_topics["tb3_0"].publishers["scan"] = broken
    logged = []
    monkeypatch.setattr(sim_node.rospy, "logerr", lambda *args: logged.append(args[0] % args[1:]))
    for _ in range(round(2.0 / node.sim.config.time_step)):     # 10 scans of each robot
        node._publish_due(node.sim.step())
    assert logged == ["gazebo: robot tb3_0: its scan failed and was skipped: MemoryError: scan "
                      "of 300000000 rays"]
    scan_1 = node.robot_topics["tb3_1"].pubs["scan"]
    odom_0 = node.robot_topics["tb3_0"].pubs["odom"]
    assert scan_1.sent >= 9 and odom_0.sent >= 50         # the other outputs went on
