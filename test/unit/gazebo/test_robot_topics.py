"""One robot's ROS names as its URDF's plugins make them (no master: stand-in publishers,
subscriber and service; a real Simulation)."""
import pytest
import rospy

from tutorial_turtlebot.gazebo import robot_topics
from tutorial_turtlebot.gazebo.robot_topics import RobotTopics, frame_prefix
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.files.urdf.urdf_file import urdf_path
from tutorial_turtlebot.sim.world.world_control import WorldControl


class FakeEndpoint:
    """A publisher, subscriber or service that records what is done with it."""

    def __init__(self, name, *args, **kwargs):
        self.name, self.sent, self.closed, self.connections = name, [], False, 1

    def get_num_connections(self):
        return self.connections

    def publish(self, msg):
        self.sent.append(msg)

    def publish_packed(self, packed):
        """As the node's publishers: the kept bytes, decoded here to check them."""
        msg = packed.message()
        self.sent.extend(msg.transforms if self.name == "/tf" else [msg])

    def unregister(self):
        self.closed = True

    shutdown = unregister


@pytest.fixture
def world(monkeypatch):
    monkeypatch.setattr(robot_topics.rospy, "Subscriber", FakeEndpoint)
    monkeypatch.setattr(robot_topics.rospy, "Service", FakeEndpoint)
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    yield sim
    sim.close()


def spawn(sim, name, namespace, edits=()):
    with open(urdf_path("burger")) as f:
        text = f.read()
    for old, new in edits:
        assert old in text
        text = text.replace(old, new)
    WorldControl(sim).spawn(name, text, ((0.0, 0.0, 0.0), (0, 0, 0, 1)), kind="urdf",
                            robot_namespace=namespace)
    return RobotTopics(sim.robots[name], FakeEndpoint, FakeEndpoint("/tf"))


def published(topics, stamp=rospy.Time(1)):
    """Publish every output once; the messages sent, by topic."""
    for publish in topics.publishers.values():
        publish(stamp)
    out = {pub.name: pub.sent for pub in topics.pubs.values()}
    out["/tf"] = topics.tf_pub.sent
    return out


@pytest.mark.parametrize("namespace, prefix", [("", ""), ("/tb3_0/", "tb3_0/"),
                                               ("/a/b/", "a/b/")])
def test_frame_prefix(namespace, prefix):
    assert frame_prefix(namespace) == prefix


def test_names_in_a_namespace(world):
    """In tb3_0: /tb3_0/{cmd_vel,odom,joint_states,scan,imu,imu_service}; frames tb3_0/..."""
    topics = spawn(world, "tb3_0", "tb3_0")
    assert sorted(p.name for p in topics.pubs.values()) == [
        "/tb3_0/imu", "/tb3_0/joint_states", "/tb3_0/odom", "/tb3_0/scan"]
    assert topics.subscriber.name == "/tb3_0/cmd_vel"
    assert [s.name for s in topics.services] == ["/tb3_0/imu_service"]
    sent = published(topics)
    odom = sent["/tb3_0/odom"][0]
    assert (odom.header.frame_id, odom.child_frame_id) == ("tb3_0/odom", "tb3_0/base_footprint")
    assert sent["/tf"][0].child_frame_id == "tb3_0/base_footprint"
    assert sent["/tb3_0/scan"][0].header.frame_id == "tb3_0/base_scan"
    assert sent["/tb3_0/imu"][0].header.frame_id == "tb3_0/imu_link"
    assert list(sent["/tb3_0/joint_states"][0].name) == ["wheel_left_joint", "wheel_right_joint"]
    topics.close()
    assert all(p.closed for p in topics.pubs.values()) and topics.subscriber.closed
    assert all(s.closed for s in topics.services)


def test_the_root_namespace_keeps_relative_names(world):
    """The robot of sim.launch: relative names (they resolve in the node's namespace) and
    unprefixed frames, as before several robots existed."""
    topics = spawn(world, "turtlebot3_burger", "")
    assert sorted(p.name for p in topics.pubs.values()) == ["imu", "joint_states", "odom", "scan"]
    assert published(topics)["odom"][0].header.frame_id == "odom"


def test_plugin_switches(world):
    """publishTf false: no odometry at all; publishWheelJointState false: no joint states;
    publishOdomTF false: odometry without its TF."""
    topics = spawn(world, "quiet", "quiet", [
        ("<publishTf>true</publishTf>", "<publishTf>false</publishTf>"),
        ("<publishWheelJointState>true</publishWheelJointState>",
         "<publishWheelJointState>false</publishWheelJointState>")])
    assert sorted(topics.pubs) == ["imu", "scan"]
    assert published(topics)["/tf"] == []
    topics = spawn(world, "no_tf", "no_tf", [("<publishOdomTF>true</publishOdomTF>",
                                              "<publishOdomTF>false</publishOdomTF>")])
    sent = published(topics)
    assert len(sent["/no_tf/odom"]) == 1 and sent["/tf"] == []


def test_a_plugins_own_namespace_wins(world):
    """A plugin with its own <robotNamespace> keeps it (Gazebo appends the spawn's only to
    plugins without one)."""
    topics = spawn(world, "tb3_5", "tb3_5", [
        ("<topicName>scan</topicName>",
         "<topicName>scan</topicName><robotNamespace>/lidar_ns</robotNamespace>")])
    assert topics.pubs["scan"].name == "/lidar_ns/scan"
    assert topics.pubs["odom"].name == "/tb3_5/odom"


def test_imu_noise_and_covariance(world):
    """gaussianNoise 0.01: every covariance diagonal is 1e-4 and the readings at rest scatter
    by about 0.01 (Gazebo's plugin); 0 (the TurtleBot3's): covariances 0, readings exact."""
    topics = spawn(world, "noisy", "noisy", [("<gaussianNoise>0.0</gaussianNoise>",
                                              "<gaussianNoise>0.01</gaussianNoise>")])
    for _ in range(40):
        world.step()
    msg = published(topics)["/noisy/imu"][0]
    assert msg.angular_velocity_covariance[0] == pytest.approx(1e-4)
    assert msg.linear_acceleration_covariance[8] == pytest.approx(1e-4)
    rates = [world.robots["noisy"].imu().angular_velocity[2]]
    for _ in range(200):
        if (world.robots["noisy"], "imu") in world.step():
            rates.append(world.robots["noisy"].imu().angular_velocity[2])
    spread = max(rates) - min(rates)
    assert 0.01 < spread < 0.1
