"""The ROS names of robots driven by the drive plugins besides the diff drive
(robot_topics with test/fixtures/drives' robots; no master: stand-in publishers and
subscriber, a real Simulation)."""
from pathlib import Path

import pytest
import rospy
from geometry_msgs.msg import Twist, Vector3

from tutorial_turtlebot.gazebo import robot_topics
from tutorial_turtlebot.gazebo.robot_topics import RobotTopics
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl
import unit_paths

DRIVES = Path(unit_paths.FIXTURES) / "drives"


class FakeEndpoint:
    """A publisher or subscriber that records what is done with it."""

    def __init__(self, name, *args, **kwargs):
        self.name, self.sent, self.closed, self.connections = name, [], False, 1

    def get_num_connections(self):
        return self.connections

    def publish_packed(self, packed):
        msg = packed.message()
        self.sent.extend(msg.transforms if self.name == "/tf" else [msg])

    def unregister(self):
        self.closed = True


@pytest.fixture
def world(monkeypatch):
    monkeypatch.setattr(robot_topics.rospy, "Subscriber", FakeEndpoint)
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    yield sim
    sim.close()


def spawn(sim, fixture, name, edits=()):
    text = (DRIVES / (fixture + ".urdf")).read_text()
    for old, new in edits:
        assert old in text
        text = text.replace(old, new)
    WorldControl(sim).spawn(name, text, ((0.0, 0.0, 0.0), (0, 0, 0, 1)), kind="urdf",
                            robot_namespace=name)
    return RobotTopics(sim.robots[name], FakeEndpoint, FakeEndpoint("/tf"))


def published(topics):
    for publish in topics.publishers.values():
        publish(rospy.Time(1))
    out = {pub.name: pub.sent for pub in topics.pubs.values()}
    out["/tf"] = topics.tf_pub.sent
    return out


def test_a_skid_steer_subscribes_cmd_vel_and_publishes_odom_and_its_tf(world):
    """/skid/cmd_vel in; /skid/odom in skid/odom -> skid/base_footprint with the plugin's
    covariances; the TF with broadcastTF, none without; no joint states."""
    topics = spawn(world, "skid_steer", "skid")
    assert topics.subscriber.name == "/skid/cmd_vel"
    assert sorted(p.name for p in topics.pubs.values()) == ["/skid/odom"]
    sent = published(topics)
    odom = sent["/skid/odom"][0]
    assert (odom.header.frame_id, odom.child_frame_id) == ("skid/odom", "skid/base_footprint")
    assert (odom.pose.covariance[0], odom.pose.covariance[35]) == (1e-4, 1e-2)
    assert [t.child_frame_id for t in sent["/tf"]] == ["skid/base_footprint"]
    quiet = spawn(world, "skid_steer", "quiet", [("<broadcastTF>true</broadcastTF>", "")])
    sent = published(quiet)
    assert sent["/tf"] == [] and len(sent["/quiet/odom"]) == 1


def test_topic_and_frame_parameters_are_used(world):
    topics = spawn(world, "skid_steer", "rover", [(
        "<broadcastTF>true</broadcastTF>",
        "<commandTopic>base/cmd</commandTopic><odometryTopic>base/odom</odometryTopic>"
        "<odometryFrame>wheel_odom</odometryFrame>")])
    assert topics.subscriber.name == "/rover/base/cmd"
    odom = published(topics)["/rover/base/odom"][0]
    assert odom.header.frame_id == "rover/wheel_odom"


def test_a_planar_moves_command_carries_linear_y(world):
    """A planar move reads linear.y: the command handed to the robot moves it sideways."""
    topics = spawn(world, "planar_move", "planar")
    topics._on_cmd_vel(Twist(linear=Vector3(0.0, 0.2, 0.0)))
    assert topics.command == (0.0, 0.0, 0.2)
    topics.apply_command()
    for _ in range(400):
        world.step()
    assert world.robots["planar"].ground_truth()[0][1] == pytest.approx(0.2, rel=0.05)
    sent = published(topics)
    assert sent["/tf"][0].header.frame_id == "planar/odom"      # planar move: always a TF


def test_a_tricycle_publishes_its_four_joints_when_asked(world):
    """publishWheelJointState: joint_states names the steering, actuated and encoder joints,
    in the plugin's order; without it, none."""
    topics = spawn(world, "tricycle", "tri", [(
        "<odometrySource>world</odometrySource>",
        "<publishWheelJointState>true</publishWheelJointState>")])
    assert sorted(p.name for p in topics.pubs.values()) == ["/tri/joint_states", "/tri/odom"]
    world.robots["tri"].command(0.3, 0.2)
    for _ in range(200):
        world.step()
    msg = published(topics)["/tri/joint_states"][0]
    assert list(msg.name) == ["front_steering_joint", "front_wheel_joint", "left_wheel_joint",
                              "right_wheel_joint"]
    assert msg.position[0] == pytest.approx(0.2, abs=0.01)      # the steering angle
    assert msg.velocity[1] == pytest.approx(6.0, rel=0.05)      # 0.3 m/s on a 0.05 m wheel
    plain = spawn(world, "tricycle", "plain")
    assert sorted(p.name for p in plain.pubs.values()) == ["/plain/odom"]
