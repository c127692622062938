"""The node's surface as gazebo_ros offers it (no ROS master: stand-in publishers, a real
Simulation): /tf only while a robot with a drive plugin is in the world, ~enable_ros_network
false leaving only /clock, and the answers of ~delete_light and ~set_joint_properties."""
import re

import pytest
from gazebo_msgs.msg import ODEJointProperties
from gazebo_msgs.srv import DeleteLight, SetJointProperties

from tutorial_turtlebot.gazebo import robot_topics, sim_node, world_api
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import WHEEL, at, urdf_text


class FakeEndpoint:
    """A publisher, subscriber or service that records what is done with it."""

    made = []

    def __init__(self, name, *args, **kwargs):
        self.name, self.closed = name, False
        FakeEndpoint.made.append(self)

    def get_num_connections(self):
        return 0

    def unregister(self):
        self.closed = True

    shutdown = unregister


def advertised(name):
    return [p for p in FakeEndpoint.made if p.name == name]


@pytest.fixture
def node(monkeypatch):
    """A SimNode of the empty world with no robot, as __init__ leaves it before its world API
    (no /tf yet); robots come by WorldControl.spawn."""
    monkeypatch.setattr(robot_topics.rospy, "Subscriber", FakeEndpoint)
    monkeypatch.setattr(robot_topics.rospy, "Service", FakeEndpoint)
    FakeEndpoint.made = []
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    node = object.__new__(sim_node.SimNode)
    node.sim, node.robot_topics, node._topics, node._output_errors = sim, {}, [], {}
    node.advertise, node.tf_pub = FakeEndpoint, None
    node.control = WorldControl(sim)
    yield node
    sim.close()


def spawn_robot(node, name, text=None):
    node.control.spawn(name, text or urdf_text("burger"), at(0.0, 3.0 * len(node.sim.robots)),
                       kind="urdf", robot_namespace=name)
    node.sync_robots()


def without_drive(text):
    """A Burger URDF without its gazebo_ros_diff_drive plugin (still a robot: laser, IMU)."""
    out = re.sub(r"<gazebo>\s*<plugin[^>]*libgazebo_ros_diff_drive\.so.*?</gazebo>", "", text,
                 flags=re.S)
    assert out != text
    return out


# --- /tf -----------------------------------------------------------------------------------------

def test_tf_comes_with_the_first_robot_that_drives_and_goes_with_the_last(node):
    node.sync_robots()
    assert node.tf_pub is None and advertised("/tf") == []      # no robot: no /tf
    spawn_robot(node, "scout", without_drive(urdf_text("burger")))
    assert "scout" in node.robot_topics and node.tf_pub is None  # a robot that publishes no TF
    spawn_robot(node, "tb3_0")
    assert advertised("/tf") == [node.tf_pub]
    assert node.robot_topics["tb3_0"].tf_pub is node.tf_pub
    spawn_robot(node, "tb3_1")
    assert advertised("/tf") == [node.tf_pub]                    # one /tf for every robot
    assert node.robot_topics["tb3_1"].tf_pub is node.tf_pub
    node.control.delete("tb3_0")
    node.sync_robots()
    assert node.tf_pub is not None and not node.tf_pub.closed
    first = node.tf_pub
    node.control.delete("tb3_1")
    node.sync_robots()
    assert node.tf_pub is None and first.closed                  # the last one went
    spawn_robot(node, "tb3_2")                                   # and it comes back
    assert len(advertised("/tf")) == 2 and node.tf_pub is advertised("/tf")[1]


# --- ~enable_ros_network --------------------------------------------------------------------------

@pytest.mark.parametrize("enabled", [True, False])
def test_enable_ros_network_false_offers_only_the_clock(monkeypatch, enabled):
    """gazebo_ros's api plugin with enable_ros_network false advertises /clock and nothing of
    the world API (services, model and link states, their topic twins, the physics'
    dynamic_reconfigure: all of WorldApi)."""
    made, apis = [], []
    monkeypatch.setattr(sim_node.SimNode, "advertise",
                        lambda self, topic, msg_type, queue_size=1: made.append(topic))
    monkeypatch.setattr(world_api, "WorldApi", lambda node, rate: apis.append(rate) or "api")
    monkeypatch.setattr(sim_node.rospy, "loginfo", lambda *args: None)
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    try:
        node = sim_node.SimNode(sim, 1.0, False, 0.0, enable_ros_network=enabled,
                                model_states_rate=50.0)
        # the states' schedule starts with the world's, before the first step; the API after
        assert ("model_states" in sim.schedules) == enabled and node.world_api is None
        node.start_world_api()
    finally:
        sim.close()
    assert made == ["/clock"]
    assert (node.world_api is not None) == enabled and apis == [50.0] * int(enabled)


# --- the answers of the new services --------------------------------------------------------------

@pytest.fixture
def api():
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    api = object.__new__(world_api.WorldApi)
    api.sim, api.control = sim, WorldControl(sim)
    yield api
    sim.close()


def test_delete_light_answers_as_gazebo(api):
    delete = world_api.refusals_answered(DeleteLight, api._delete_light)
    answer = delete(DeleteLight._request_class(light_name="sun"))
    assert (answer.success, answer.status_message) == (True, "DeleteLight: sun successfully "
                                                             "deleted")
    answer = delete(DeleteLight._request_class(light_name="sun"))
    assert (answer.success, answer.status_message) == (False, "DeleteLight: Requested light sun "
                                                              "not found!")


def test_set_joint_properties_answers_as_gazebo_and_hands_every_field_on(api):
    api.control.spawn("w", WHEEL, at(0, 0, 0.06), kind="urdf")
    set_joint = world_api.refusals_answered(SetJointProperties, api._set_joint_properties)
    config = ODEJointProperties(damping=[0.25], hiStop=[0.5], loStop=[-0.5], erp=[0.2],
                                cfm=[0.0], stop_erp=[0.2], stop_cfm=[0.0], fudge_factor=[1.0],
                                fmax=[0.1], vel=[0.3])
    answer = set_joint(SetJointProperties._request_class(joint_name="spin",
                                                         ode_joint_config=config))
    assert (answer.success, answer.status_message) == (True, "SetJointProperties: properties "
                                                             "set")
    body = api.control.models.get("w").parts[0].body
    assert (body.joint_damping(0), body.joint_stops(0), body.joint_motor(0)) == (
        0.25, (-0.5, 0.5), (0.3, 0.1))
    config.stop_cfm = [float("nan")]
    answer = set_joint(SetJointProperties._request_class(joint_name="spin",
                                                         ode_joint_config=config))
    assert (answer.success, answer.status_message) == (
        False, "SetJointProperties: ode_joint_config.stop_cfm[0]: NaN or infinite value")
    answer = set_joint(SetJointProperties._request_class(joint_name="elbow"))
    assert (answer.success, answer.status_message) == (False, "SetJointProperties: joint not "
                                                              "found")
