"""The /gazebo node's hold on its robots (gazebo/sim_node, no ROS master: stand-in publishers,
subscriber and service; a real Simulation): a robot whose topics cannot be made is taken out of
the world again with a one-line error, and one robot's output that fails is skipped and named
in one line while the others go on (both once ended the node)."""
import pytest

from tutorial_turtlebot.errors import RequestError, UserError
from tutorial_turtlebot.gazebo import (camera_rate_watch, node_start, robot_topics, sim_node,
                                       world_api)
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

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


def test_the_start_logs_every_warning_through_rospy_in_lines_of_at_most_200_characters(
        tmp_path, monkeypatch):
    """A world of three missing includes and a textured crate over a lowered texture budget:
    each warning (the world's, its building's) one rospy line of at most 200 characters but
    the folders searched, said once."""
    import os
    import unit_paths
    from tutorial_turtlebot.sim.engine import physics as physics_module, texture_budget
    monkeypatch.setenv("GAZEBO_MODEL_PATH", os.path.join(unit_paths.FIXTURES, "gazebo_models"))
    world = tmp_path / "w.world"
    world.write_text('<?xml version="1.0"?><sdf version="1.6"><world name="w">%s%s</world></sdf>'
                     % ("".join("<include><uri>model://missing_%d</uri></include>" % i
                                for i in range(3)),
                        "<include><uri>model://max_style_crate</uri></include>"))
    monkeypatch.setattr(texture_budget, "MAX_TEXTURE_PIXELS", 300)
    monkeypatch.setattr(physics_module, "enable_egl", lambda cid: False)
    logged = []
    monkeypatch.setattr(sim_node.rospy, "logwarn", lambda text, *args: logged.append(
        text % args))
    monkeypatch.setattr(sim_node.rospy, "loginfo", lambda *args: None)
    config = SimConfig(model="burger", world=str(world), x=-2.0, y=0.0)
    sim = Simulation(config)
    try:
        node_start._log_start(sim, config, 1.0)
    finally:
        sim.close()
    searched = [line for line in logged if "model:// searched" in line]
    assert len(searched) == 1 and "https://github.com/osrf/gazebo_models" in searched[0]
    rest = [line for line in logged if line not in searched]
    assert sum("<include> left out: model://missing_" in line for line in rest) == 3
    assert any("texture budget of 300 px" in line for line in rest)
    assert all(len(line) <= 200 and "\n" not in line for line in rest), rest


class StubPacer:
    """LoopPacer.frame_in_time as told: whether the loop is in time."""

    def __init__(self):
        self.in_time = True

    def frame_in_time(self, _sim_time):
        return self.in_time


def test_a_camera_frame_due_while_the_loop_is_late_is_skipped(node):
    node.control.spawn("tb3", urdf_text("waffle_pi"), at(0.0, 0.0), kind="urdf",
                       robot_namespace="tb3")
    node.sync_robots()
    topics = node.robot_topics["tb3"]
    drawn = []
    topics.publishers["camera"] = drawn.append
    node.pacer = StubPacer()
    for in_time in (True, False, False, True):        # one camera tick (30 Hz) each
        node.pacer.in_time = in_time
        due = []
        while not any(name == "camera" for _, name in due):
            due = node.sim.step()
            node._publish_due(due)
    assert len(drawn) == 2 and topics.frames_skipped == 2
    assert drawn[0] < drawn[1]                          # stamps of the first and last tick
    assert node.robot_topics["tb3"].pubs["odom"].sent > 0   # the rest goes on


def test_a_request_error_is_a_user_error():
    assert issubclass(RequestError, UserError)


def test_the_world_api_answers_a_refusal_with_success_false_and_its_text(node):
    """refusals_answered (every handler of world_api's service table): a RequestError is the
    answer, success False and its text; anything else goes on to the caller (_answered)."""
    from gazebo_msgs.srv import DeleteModel, GetLightProperties, SpawnModel
    api = object.__new__(world_api.WorldApi)
    api.node, api.sim, api.control = node, node.sim, node.control
    answer = world_api.refusals_answered(DeleteModel, api._delete_model)(
        DeleteModel._request_class(model_name="nothing"))
    assert (answer.success, answer.status_message) == (False,
                                                       "DeleteModel: model does not exist")
    answer = world_api.refusals_answered(GetLightProperties, api._get_light_properties)(
        GetLightProperties._request_class(light_name="moon"))
    assert (answer.success, answer.status_message) == (
        False, "getLightProperties: Requested light moon not found!")

    def refused(_request):
        raise RequestError("SpawnModel: Failure - entity already exists.")
    answer = world_api.refusals_answered(SpawnModel, refused)(None)
    assert (answer.success, answer.status_message) == (
        False, "SpawnModel: Failure - entity already exists.")
    with pytest.raises(ZeroDivisionError):
        world_api.refusals_answered(SpawnModel, lambda _request: 1 / 0)(None)


def test_a_spawned_models_warning_is_one_log_line_of_at_most_200_characters():
    from tutorial_turtlebot.gazebo.world_api import spawn_warning
    assert spawn_warning("crate", "x.dae: texture halved") == "spawn crate: x.dae: texture halved"
    line = spawn_warning("m" * 256, "w" * 200)
    assert len(line) == 200 and line.startswith("spawn " + "m" * 37 + "...: w")


def test_a_camera_that_keeps_too_few_frames_says_so_once(node, monkeypatch):
    """Subscribed, a camera that skips frames warns once with the rate it keeps."""
    node.control.spawn("tb3", urdf_text("waffle_pi"), at(0.0, 0.0), kind="urdf",
                       robot_namespace="tb3")
    node.sync_robots()
    topics = node.robot_topics["tb3"]
    topics.publishers["camera"] = lambda stamp: None
    monkeypatch.setattr(topics, "frame_wanted", lambda output: True)
    said = []
    monkeypatch.setattr(sim_node.rospy, "logwarn", lambda fmt, *args: said.append(fmt % args))
    node.pacer = StubPacer()
    ticks = 0
    while ticks < 2 * 30 * camera_rate_watch.WINDOW_SECONDS:     # two windows at 30 Hz
        node.pacer.in_time = ticks % 3 != 0                      # one frame in three is late
        due = node.sim.step()
        ticks += any(name == "camera" for _, name in due)
        node._publish_due(due)
    assert said == ["gazebo: robot tb3: its camera keeps 20.0 of its 30 images per sim second: "
                    "the loop is behind the wall clock and skips frames (a smaller image or "
                    "rate keeps them all)"]


def test_the_camera_rate_watch_is_quiet_while_frames_are_kept():
    watch = camera_rate_watch.CameraRateWatch(10.0)
    assert all(watch.count(i % 20 == 0) is None for i in range(200))    # 95 % kept
    assert watch.count(True) is None and not watch.said
