"""The ROS side of the drives of SDF models (model_plugin_topics' drive topic with
test/fixtures/sdf_drives' models; no master: stand-in publishers, subscriber and node, a real
Simulation): cmd_vel in, odom with the plugin's frames and covariance, the odom TF as the
plugin says, a planar move's linear.y, nothing read for nobody."""
from pathlib import Path

import pytest
import rospy
from geometry_msgs.msg import Twist, Vector3

from tutorial_turtlebot.gazebo import model_plugin_topics
from tutorial_turtlebot.gazebo.model_plugin_topics import ModelPluginTopics
from tutorial_turtlebot.sim.world.model_plugins import MODEL_PLUGINS
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl
import unit_paths

FIXTURES = Path(unit_paths.FIXTURES) / "sdf_drives"


class FakeEndpoint:
    """A publisher or subscriber that records what is done with it."""

    def __init__(self, name, *args, **kwargs):
        self.name, self.sent, self.closed, self.connections = name, [], False, 1
        self.callback = args[1] if len(args) > 1 else None

    def get_num_connections(self):
        return self.connections

    def publish_packed(self, packed):
        msg = packed.message()
        self.sent.extend(msg.transforms if self.name == "/tf" else [msg])

    def unregister(self):
        self.closed = True


class FakeNode:
    """The SimNode's part a drive uses: /tf and queue_in_loop (run at once here)."""

    def __init__(self):
        self.tf_pub = FakeEndpoint("/tf")
        self.subscribers = []

    def queue_in_loop(self, job, key=None):
        job()


@pytest.fixture
def world(monkeypatch):
    node = FakeNode()

    def subscriber(name, *args, **kwargs):
        node.subscribers.append(FakeEndpoint(name, *args, **kwargs))
        return node.subscribers[-1]
    monkeypatch.setattr(model_plugin_topics.rospy, "Subscriber", subscriber)
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    yield sim, node
    sim.close()


def spawned(world, fixture, name):
    """(ModelPluginTopics, {topic: publisher}) of the SDF model ``fixture`` spawned."""
    sim, node = world
    WorldControl(sim).spawn(name, (FIXTURES / fixture).read_text(),
                            ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)))
    sim.model_plugins.sync(sim.time_ns)      # as the node's loop does after a spawn
    pubs = {}

    def make_publisher(topic, msg_type, queue_size=1):
        pubs[topic] = FakeEndpoint(topic)
        return pubs[topic]
    return ModelPluginTopics(sim, make_publisher, node), pubs


def run(sim, topics, seconds):
    for _ in range(round(seconds / sim.config.time_step)):
        if (None, MODEL_PLUGINS) in sim.step():
            topics.publish(rospy.Time(0, sim.time_ns))


def test_a_skid_steer_model_drives_on_cmd_vel_with_its_odom_and_tf(world):
    sim, node = world
    topics, pubs = spawned(world, "skid_steer.sdf", "skidbot")
    (cmd,) = node.subscribers
    assert cmd.name == "cmd_vel" and set(pubs) == {"odom"}
    cmd.callback(Twist(linear=Vector3(0.3, 0, 0)))
    run(sim, topics, 1.0)
    odom = pubs["odom"].sent
    assert len(odom) == pytest.approx(100, abs=1)                   # its updateRate
    last = odom[-1]
    assert (last.header.frame_id, last.child_frame_id) == ("odom", "base_footprint")
    assert last.pose.pose.position.x > 0.2 and last.twist.twist.linear.x > 0.2
    assert last.pose.covariance[0] == 0.0001 and last.pose.covariance[35] == 0.01
    tf = node.tf_pub.sent
    assert len(tf) == len(odom) and (tf[-1].header.frame_id, tf[-1].child_frame_id) == (
        "odom", "base_footprint")


def test_a_planar_move_models_command_carries_linear_y_and_odom_is_at_its_rate(world):
    sim, node = world
    topics, pubs = spawned(world, "planar_move.sdf", "puck")
    (cmd,) = node.subscribers
    cmd.callback(Twist(linear=Vector3(0.0, 0.2, 0)))
    run(sim, topics, 1.0)
    odom = pubs["odom"].sent
    assert len(odom) == pytest.approx(20, abs=1)                    # odometryRate
    assert odom[-1].pose.pose.position.y > 0.15 and abs(odom[-1].pose.pose.position.x) < 0.01
    assert odom[-1].child_frame_id == "body"


def test_nobody_listening_reads_nothing(world):
    sim, node = world
    topics, pubs = spawned(world, "skid_steer.sdf", "skidbot")
    pubs["odom"].connections = node.tf_pub.connections = 0
    run(sim, topics, 0.2)
    assert pubs["odom"].sent == [] and node.tf_pub.sent == []
    topics.close()
    assert pubs["odom"].closed and node.subscribers[0].closed


def test_a_tricycle_model_publishes_its_four_joints_when_asked(world):
    sim, node = world
    topics, pubs = spawned(world, "tricycle.sdf", "trike")
    assert set(pubs) == {"odom", "joint_states"}
    node.subscribers[0].callback(Twist(linear=Vector3(0.3, 0, 0), angular=Vector3(0, 0, 0.5)))
    run(sim, topics, 0.5)
    last = pubs["joint_states"].sent[-1]
    assert list(last.name) == ["front_steering_joint", "front_wheel_joint", "left_wheel_joint",
                               "right_wheel_joint"]
    assert last.position[0] == pytest.approx(0.5, abs=0.02)         # the steering angle
