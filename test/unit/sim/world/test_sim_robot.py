"""Several robots in one Simulation (no ROS): each made from its URDF's plugins, in its own
namespace, seeing and bumping into the others; spawn refusals leave the running ones alone."""
import math
import os

import numpy as np
import pytest

from tutorial_turtlebot.errors import RequestError, UserError
from tutorial_turtlebot.sim.engine.physics import MAX_ROBOTS
from tutorial_turtlebot.sim.world.sim_robot import normalize_namespace
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import at, run, urdf_text
import unit_paths

IDENTITY = (0.0, 0.0, 0.0, 1.0)


@pytest.mark.parametrize("given, normal", [("", ""), ("/", ""), ("tb3_0", "/tb3_0/"),
                                           ("/tb3_0/", "/tb3_0/"), ("a/b1", "/a/b1/")])
def test_namespaces_are_normalized(given, normal):
    assert normalize_namespace(given) == normal


@pytest.mark.parametrize("bad", ["tb 3", "tb3-1", "3tb", "a//b", "a/b.c", "~x"])
def test_illegal_namespaces_are_refused(bad):
    with pytest.raises(UserError, match="not a legal ROS namespace"):
        normalize_namespace(bad)


def test_a_spawned_robot_has_its_own_outputs_at_its_plugins_rates(empty):
    """A Waffle Pi spawned by spawn_urdf_model in tb3_1: its odom, joint states, scan, IMU and
    camera are due at its URDF's rates beside the first robot's; the clock once for both."""
    sim, wc = empty
    wc.spawn("tb3_1", urdf_text("waffle_pi"), at(1.0, 1.0), kind="urdf",
             robot_namespace="tb3_1")
    robot = sim.robots["tb3_1"]
    assert robot.namespace == "/tb3_1/" and sim.robot.namespace == ""
    sim.step()                                  # everything is due at its first step
    counts = run(sim, 1.0)
    for name in ("turtlebot3_burger", "tb3_1"):
        assert counts[(name, "odom")] == 30 and counts[(name, "scan")] == 5
        assert counts[(name, "imu")] == 200 and counts[(name, "joint_states")] == 30
    assert counts[("tb3_1", "camera")] == 30 and ("turtlebot3_burger", "camera") not in counts
    assert counts[(None, "clock")] == 100
    assert "tb3_1" in sim.models.names()
    assert robot.ground_truth()[0][:2] == pytest.approx((1.0, 1.0), abs=0.01)


def test_robots_see_each_other_but_never_themselves(empty):
    """Burgers 1 m apart face each other: each scan's ray straight ahead ends at the other's
    laser housing, and nothing else is in view (each robot's own body is not)."""
    sim, wc = empty
    wc.spawn("other", urdf_text("burger"), at(1.0, 0.0, yaw=math.pi), kind="urdf",
             robot_namespace="other")
    run(sim, 0.2)
    for robot in (sim.robot, sim.robots["other"]):
        ranges = robot.scan()
        assert ranges[0] == pytest.approx(0.96, abs=0.05)
        seen = np.flatnonzero(np.isfinite(ranges))
        assert len(seen) > 0 and set(seen) <= set(range(0, 8)) | set(range(352, 360))


def test_robots_collide(empty):
    """A Burger driving at a standing Waffle does not pass through it: the Waffle is pushed
    or the Burger is held back, and the Burger ends on the near side."""
    sim, wc = empty
    wc.spawn("waffle", urdf_text("waffle"), at(0.8, 0.0), kind="urdf", robot_namespace="w")
    waffle = sim.robots["waffle"]
    sim.robot.command(0.22, 0.0)
    run(sim, 8.0)
    burger_x = sim.robot.ground_truth()[0][0]
    waffle_x = waffle.ground_truth()[0][0]
    assert burger_x < waffle_x - 0.15       # centres never closer than the two half-bodies
    assert burger_x > 0.3                   # it did drive up to the waffle


def test_each_robot_obeys_its_own_commands(empty):
    sim, wc = empty
    wc.spawn("tb3_1", urdf_text("burger"), at(0.0, 2.0), kind="urdf", robot_namespace="tb3_1")
    sim.robots["tb3_1"].command(0.2, 0.0)
    run(sim, 2.0)
    assert sim.robots["tb3_1"].odom().position[0] > 0.3
    assert abs(sim.robot.odom().position[0]) < 0.01


def test_namespace_and_name_conflicts_are_refused(empty):
    """The first robot holds the root namespace; a second tb3_1, a second robot in /tb3_1/ and
    an illegal namespace are refused with Gazebo's status prefix, changing nothing."""
    sim, wc = empty
    wc.spawn("tb3_1", urdf_text("burger"), at(0.0, 2.0), kind="urdf", robot_namespace="tb3_1")
    before = sim.models.names()
    cases = [("tb3_2", "", "already uses namespace '/'"),
             ("tb3_2", "/tb3_1/", "already uses namespace '/tb3_1/'"),
             ("tb3_1", "tb3_9", "entity already exists"),
             ("tb3_3", "tb 3", "not a legal ROS namespace")]
    for name, namespace, words in cases:
        with pytest.raises(RequestError) as err:
            wc.spawn(name, urdf_text("burger"), at(2.0, 2.0), kind="urdf",
                     robot_namespace=namespace)
        assert str(err.value).startswith("SpawnModel: Failure - ") and words in str(err.value)
    assert sim.models.names() == before and set(sim.robots) == {"turtlebot3_burger", "tb3_1"}


@pytest.mark.parametrize("edit, words", [
    (("<samples>360</samples>", "<samples>-5</samples>"), "<samples>"),
    (("<leftJoint>wheel_left_joint</leftJoint>", "<leftJoint>wheel_lft_joint</leftJoint>"),
     "wheel_lft_joint"),
    (("<frameName>base_scan</frameName>", "<frameName>laser_frame</frameName>"),
     "laser_frame"),
])
def test_a_bad_plugin_block_refuses_the_spawn(empty, edit, words):
    """A wrong plugin block: success=false naming the element (model_xml of NAME:LINE); the
    running robot steps on as before."""
    sim, wc = empty
    text = urdf_text("burger")
    assert edit[0] in text
    with pytest.raises(RequestError) as err:
        wc.spawn("bad", text.replace(*edit), at(2.0, 2.0), kind="urdf", robot_namespace="bad")
    message = str(err.value)
    assert message.startswith("SpawnModel: Failure - model_xml of bad:") and words in message
    assert "\n" not in message
    assert "bad" not in sim.models.names() and set(sim.robots) == {"turtlebot3_burger"}
    sim.robot.command(0.2, 0.0)
    run(sim, 1.0)
    assert sim.robot.odom().position[0] > 0.1


def test_delete_removes_a_robot_and_frees_its_place(empty):
    """delete: the robot, its outputs and its body go; its name and namespace can be used
    again, and the robot limit counts it no longer."""
    sim, wc = empty
    wc.spawn("tb3_1", urdf_text("burger"), at(1.0, 0.0), kind="urdf", robot_namespace="tb3_1")
    wc.delete("tb3_1")
    assert "tb3_1" not in sim.robots and all(robot is not None and robot.name != "tb3_1"
                                             for robot, _ in run_due(sim))
    assert np.isinf(sim.robot.scan()[0])                 # nothing ahead any more
    wc.spawn("tb3_1", urdf_text("burger"), at(1.0, 0.0), kind="urdf", robot_namespace="tb3_1")
    assert "tb3_1" in sim.robots


def run_due(sim):
    """The robot outputs due over 0.2 s."""
    out = []
    for _ in range(80):
        out.extend((robot, name) for robot, name in sim.step() if robot is not None)
    return out


def test_the_robot_limit_is_a_clear_answer(empty):
    """Up to MAX_ROBOTS robots run; one more is refused with the limit named."""
    sim, wc = empty
    for i in range(1, MAX_ROBOTS):
        wc.spawn("r%d" % i, urdf_text("burger"), at(i % 6, 1.0 + i // 6), kind="urdf",
                 robot_namespace="r%d" % i)
    assert len(sim.robots) == MAX_ROBOTS
    with pytest.raises(RequestError, match="at most %d robots" % MAX_ROBOTS):
        wc.spawn("one_more", urdf_text("burger"), at(-3.0, -3.0), kind="urdf",
                 robot_namespace="one_more")
    run(sim, 0.1)


def test_launch_overrides_apply_to_spawned_robots():
    """lidar_samples and lidar_model of the config apply to a spawned robot too; its command
    limits are its own model's (a Waffle's 0.26 m/s), named by its URDF's robot name."""
    sim = Simulation(SimConfig(model="burger", world="empty", lidar_samples=24,
                               lidar_model="lds01"))
    try:
        WorldControl(sim).spawn("w", urdf_text("waffle"), at(2.0, 0.0), kind="urdf",
                                robot_namespace="w")
        waffle = sim.robots["w"]
        assert waffle.laser.samples == 24 and waffle.laser.no_return == 0.0
        assert waffle.laser.angle_increment == pytest.approx(2 * math.pi / 24)
        problems = waffle.command(1.0, 0.0)
        assert problems and "0.26" in problems[0]
    finally:
        sim.close()


def test_an_empty_world_takes_robots_later():
    """spawn_robot False: no robot of its own (the world's models only); spawned robots run."""
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    try:
        assert sim.robot is None and sim.robots == {} and sim.models.names() == ["ground_plane"]
        sim.step()
        assert run(sim, 0.1) == {(None, "clock"): 10}
        WorldControl(sim).spawn("tb3_0", urdf_text("burger"), at(0.0, 0.0), kind="urdf",
                                robot_namespace="tb3_0")
        sim.step()
        assert run(sim, 1.0)[("tb3_0", "scan")] == 5
    finally:
        sim.close()


def test_the_urdf_makes_the_robot(tmp_path):
    """An edited URDF changes the simulated robot: 24 samples and a wider wheel track."""
    text = urdf_text("burger")
    edited = (text.replace("<samples>360</samples>", "<samples>24</samples>")
              .replace("<wheelSeparation>0.160</wheelSeparation>",
                       "<wheelSeparation>0.200</wheelSeparation>"))
    assert edited.count("24</samples>") == 1 and "0.200" in edited
    path = tmp_path / "my_burger.urdf"
    path.write_text(edited)
    sim = Simulation(SimConfig(model="burger", world="empty", urdf=str(path)))
    try:
        assert len(sim.robot.scan()) == 24
        assert sim.robot.laser.angle_increment == pytest.approx(6.28319 / 23)
        assert sim.robot.drive.separation == 0.200
    finally:
        sim.close()
    assert read_urdf(path).plugins.laser.laser.samples == 24


def test_a_camera_added_to_the_burger_is_simulated(tmp_path):
    """doc/robots.md's snippet (test/unit/data/burger_camera.xml) pasted into the Burger's URDF:
    the Burger gets a 640x480 camera at 30 Hz, rendering from camera_link along its +x."""
    with open(os.path.join(unit_paths.DATA, "burger_camera.xml")) as f:
        snippet = f.read()
    path = tmp_path / "burger_camera.urdf"
    path.write_text(urdf_text("burger").replace("</robot>", snippet + "</robot>"))
    sim = Simulation(SimConfig(model="burger", world="turtlebot3_world", urdf=str(path)))
    try:
        spec = sim.robot.camera_spec
        assert (spec.width, spec.height, spec.rate) == (640, 480, 30.0)
        assert sim.robot.camera_sensor.frame == "camera_optical_frame"
        rgb, _ = sim.robot.camera_image()
        assert rgb.shape == (480, 640, 3) and rgb.std() > 5   # the arena, not a blank image
    finally:
        sim.close()


def test_a_camera_looks_along_its_links_x_axis():
    """Gazebo renders a camera along +x of its <gazebo reference> link (camera_rgb_frame on a
    Waffle Pi): the image equals one rendered from the URDF's optical frame, which the
    TurtleBot3 URDF puts on that axis (rpy -1.57 0 -1.57: within 1 mrad of it)."""
    from tutorial_turtlebot.sim.engine.rendering import CameraRenderer
    sim = Simulation(SimConfig(model="waffle_pi", world="turtlebot3_world"))
    try:
        assert sim.robot.camera_sensor.link == "camera_rgb_frame"
        rgb, _ = sim.robot.camera_image()
        position, rotation = sim.robot.body.frame_pose("camera_rgb_optical_frame")
        reference, _ = CameraRenderer(sim.physics.client, sim.robot.camera_spec,
                                      use_egl=sim.physics.egl).render(position, rotation)
        assert rgb.std() > 5
        assert np.mean(np.abs(rgb.astype(int) - reference.astype(int))) < 2.0
        flipped = reference[::-1]
        assert np.mean(np.abs(rgb.astype(int) - flipped.astype(int))) > 5.0
    finally:
        sim.close()


# --- a failed robot spawn leaves nothing ----------------------------------------------------------

def _nothing_at(sim, x, y):
    """No body but the ground between 0.01 and 1 m above (x, y): what another robot's laser
    or a dropped box would meet."""
    from tutorial_turtlebot.sim.engine.bullet import pybullet
    hit = pybullet.rayTest((x, y, 1.0), (x, y, 0.01), physicsClientId=sim.physics.client)[0]
    return hit[0] == -1


@pytest.mark.parametrize("stage", ["rays", "camera", "model"])
def test_a_spawn_that_fails_at_any_stage_leaves_no_body(empty, monkeypatch, stage):
    """The robot's body is made first; whatever fails after it (the laser's rays, the camera,
    the world model) takes the body out again, and the name is free for the next spawn."""
    from tutorial_turtlebot.sim.world import sim_robot, simulation

    def boom(*_args, **_kwargs):
        raise RuntimeError("broken on purpose")
    target = {"rays": (sim_robot, "ray_directions"), "camera": (sim_robot, "CameraRenderer"),
              "model": (simulation, "urdf_model")}[stage]
    sim, wc = empty
    names = sim.models.names()
    assert _nothing_at(sim, 1.0, 1.0)
    with monkeypatch.context() as patch:
        patch.setattr(*target, boom)
        with pytest.raises(RuntimeError, match="broken on purpose"):
            wc.spawn("tb3_1", urdf_text("waffle_pi"), at(1.0, 1.0), kind="urdf",
                     robot_namespace="tb3_1")
    assert sim.models.names() == names and "tb3_1" not in sim.robots
    assert _nothing_at(sim, 1.0, 1.0)
    run(sim, 0.2)
    assert _nothing_at(sim, 1.0, 1.0)
    wc.spawn("tb3_1", urdf_text("waffle_pi"), at(1.0, 1.0), kind="urdf",
             robot_namespace="tb3_1")                          # and it can be spawned again
    assert not _nothing_at(sim, 1.0, 1.0)
