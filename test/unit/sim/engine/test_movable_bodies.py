"""Jointed SDF models simulated (engine.movable_bodies through Simulation): a pendulum keeps the
period its length gives, a cart rests level on its wheels, limits, damping, ball, universal and
fixed joints act as Gazebo's do, a loop runs as its nearest tree, and the world API reads and
drives the joints. The worlds are this project's fixtures (test/fixtures/joints/)."""
import math
import os

import numpy as np
import pytest

from tutorial_turtlebot.sim.kinematics import rpy_from_quat
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

import unit_paths

JOINTS = os.path.join(unit_paths.FIXTURES, "joints")
STEPS_PER_S = 400          # Simulation's 2.5 ms steps


@pytest.fixture(scope="module")
def joints():
    """The joints fixture world stepped 5 s from rest: (sim, wc, link poses at the start)."""
    sim = Simulation(SimConfig(world=os.path.join(JOINTS, "joints.world"), spawn_robot=False))
    start = {name: links(sim, name) for name in sim.models.names()}
    for _ in range(5 * STEPS_PER_S):
        sim.step()
    yield sim, WorldControl(sim), start
    sim.close()


def links(sim, model):
    """{scoped link: world pose} of ``model`` now."""
    return {name: pose for name, pose, _ in sim.models.get(model).link_states()}


def swing(world, steps, link="pendulum::bob", model="pendulum"):
    """A new Simulation of ``world`` stepped ``steps`` times: (times s, x of ``link``, sim)."""
    sim = Simulation(SimConfig(world=os.path.join(JOINTS, world), spawn_robot=False))
    xs, ts = [], []
    for _ in range(steps):
        sim.step()
        xs.append(links(sim, model)[link][0][0])
        ts.append(sim.time)
    return np.array(ts), np.array(xs), sim


def upward_crossings(ts, xs, centre=0.0):
    return [ts[i] for i in range(1, len(xs)) if xs[i - 1] < centre <= xs[i]]


def test_pendulum_period_matches_its_length():
    ts, xs, sim = swing("pendulum.world", 12 * STEPS_PER_S)
    sim.close()
    period = float(np.mean(np.diff(upward_crossings(ts, xs))))
    length, bob_i = 1.0, 0.001      # pendulum.world: the bob 1 m out, its own moment
    expected = 2 * math.pi * math.sqrt((length ** 2 + bob_i) / (9.8 * length))
    assert abs(period - expected) / expected < 0.02
    # nothing damps it: the swing keeps its 0.1 rad (0.0998 m) amplitude
    assert xs[-2 * STEPS_PER_S:].max() > 0.095


def test_pendulum_hinge_stays_put():
    """The bob stays 1 m from the hinge at (0, 0, 2) however it swings."""
    ts, xs, sim = swing("pendulum.world", 3 * STEPS_PER_S)
    pos = links(sim, "pendulum")["pendulum::bob"][0]
    sim.close()
    assert abs(math.dist(pos, (0.0, 0.0, 2.0)) - 1.0) < 1e-3


def test_links_start_where_the_file_puts_them(joints):
    _, _, start = joints
    cart = start["cart"]
    assert np.allclose(cart["cart::left_wheel"][0], (-0.1, 0.18, 0.1), atol=1e-9)
    assert np.allclose(rpy_from_quat(cart["cart::left_wheel"][1]), (-math.pi / 2, 0, 0),
                       atol=1e-6)
    assert np.allclose(start["welded"]["welded::upper"][0], (15.0, 0.0, 0.8), atol=1e-9)


def test_cart_rests_level_on_its_wheels(joints):
    sim, _, start = joints
    chassis = links(sim, "cart")["cart::chassis"]
    roll, pitch, _ = rpy_from_quat(chassis[1])
    assert abs(roll) < 0.01 and abs(pitch) < 0.01
    assert abs(chassis[0][2] - 0.15) < 0.01
    # the wheels stay on their axles: 0.18 m either side of the chassis
    wheels = links(sim, "cart")
    assert abs(wheels["cart::left_wheel"][0][1] - chassis[0][1] - 0.18) < 1e-3


def test_prismatic_slider_stops_at_its_lower_limit(joints):
    sim, wc, _ = joints
    assert abs(links(sim, "slider")["slider::block"][0][2] - 0.8) < 0.005
    assert abs(wc.get_joint_properties("rail").position[0] + 0.2) < 0.005


def test_the_world_api_knows_each_joint_as_built(joints):
    sim, wc, _ = joints
    [slider] = sim.models.get("slider").parts
    [rail] = slider.body.joints()
    assert (rail.name, rail.kind, rail.child_link) == ("rail", "prismatic", "block")
    assert slider.body.joint_stops(rail.index) == (-0.2, 0.2)
    assert wc.get_joint_properties("damped::hinge").damping == [0.5]
    [gimbal] = sim.models.get("gimbal").parts
    assert [j.name for j in gimbal.body.joints()] == ["cross", ""]   # two axes, one name


def test_damping_takes_the_swing_out(joints):
    sim, _, start = joints
    x0 = start["damped"]["damped::bob"][0][0] - 6.0
    x = links(sim, "damped")["damped::bob"][0][0] - 6.0
    assert abs(x0) > 0.09 and abs(x) < 0.5 * abs(x0)


@pytest.mark.parametrize("model", ["ball", "gimbal"])
def test_two_axis_bobs_swing_about_their_pivot(joints, model):
    sim, _, start = joints
    pivot = np.array(start[model][model + "::bob"][0]) + (-0.1, -0.1, 0.98)
    now = np.array(links(sim, model)[model + "::bob"][0])
    assert abs(np.linalg.norm(now - pivot) - np.linalg.norm((0.1, 0.1, 0.98))) < 2e-3
    assert np.linalg.norm(now[:2] - np.array(start[model][model + "::bob"][0][:2])) > 0.05


def test_welded_links_fall_together(joints):
    sim, _, start = joints
    now = links(sim, "welded")
    lower, upper = now["welded::lower"], now["welded::upper"]
    assert abs(lower[0][2] - 0.1) < 0.01           # resting on the ground
    assert np.allclose(np.subtract(upper[0], lower[0]), (0, 0, 0.3), atol=1e-3)
    assert abs(rpy_from_quat(upper[1])[2] - 0.5) < 1e-3


def test_a_loop_runs_as_its_nearest_tree(joints):
    sim, wc, _ = joints
    assert any("joint ca closes a loop" in w for w in sim.world.warnings)
    assert wc.get_joint_properties("bc").kind == "revolute"
    assert len(links(sim, "loop")) == 3


def test_apply_joint_effort_lifts_the_slider(joints):
    """20 N up on the 1 kg block for 0.5 s lifts it from its lower stop to its upper one."""
    sim, wc, _ = joints
    assert wc.get_joint_properties("slider::rail").position[0] < -0.19
    wc.apply_joint_effort("slider::rail", 20.0, 0, int(0.5e9))
    for _ in range(STEPS_PER_S // 2):
        sim.step()
    assert wc.get_joint_properties("slider::rail").position[0] > 0.19


def test_each_link_keeps_its_own_friction(joints):
    """The cart's wheels and chassis grip with their collisions' mu 1, not pybullet's 0.5."""
    sim, _, _ = joints
    [cart] = sim.models.get("cart").parts
    client = cart.body.client
    for index in range(-1, cart.body.joint_count()):
        assert client.getDynamicsInfo(cart.body.uid, index)[1] == 1.0


def test_reset_world_puts_every_joint_back(joints):
    sim, _, start = joints
    sim.reset_world()
    for model in ("cart", "slider", "ball", "gimbal", "damped"):
        for name, pose in links(sim, model).items():
            assert np.allclose(pose[0], start[model][name][0], atol=1e-6), name


def test_a_spawned_jointed_model_deleted_and_spawned_again_swings_the_same():
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    wc = WorldControl(sim)
    with open(os.path.join(JOINTS, "pendulum.world")) as f:
        text = f.read()
    model = text[text.index('<model name="pendulum">'):text.index("</world>")]
    xml = '<sdf version="1.6">%s</sdf>' % model
    pose = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
    runs = []
    for _ in range(2):
        wc.spawn("swing", xml, pose)
        out = []
        for _ in range(STEPS_PER_S):
            sim.step()
            out.append(links(sim, "swing")["swing::bob"][0])
        runs.append(out)
        wc.delete("swing")
    sim.close()
    assert np.allclose(runs[0], runs[1], atol=1e-9)
    assert abs(runs[0][0][2] - 1.005) < 1e-3          # the hinge at 2 m, the bob 0.995 below


def test_one_top_speed_a_body_the_fastest_of_its_joints_limits():
    from tutorial_turtlebot.sim.engine.movable_bodies import _top_speed
    from tutorial_turtlebot.sim.files.world_types import Joint

    def joint(kind, velocity):
        return Joint("j", kind, "m::a", "m::b", (0.0,) * 6, velocity=velocity)

    assert _top_speed([joint("revolute", 0.5), joint("prismatic", 2.0)]) == 2.0
    assert _top_speed([joint("revolute", 0.5), joint("fixed", -1.0)]) == 0.5
    # one joint without a limit: no cap that would hold it (pybullet keeps one per body)
    assert _top_speed([joint("revolute", 0.5), joint("continuous", -1.0)]) is None
    assert _top_speed([joint("fixed", -1.0)]) is None


def test_a_joints_velocity_limit_holds_its_swing(tmp_path):
    text = open(os.path.join(JOINTS, "pendulum.world")).read().replace(
        "<axis><xyz>0 1 0</xyz></axis>",
        "<axis><xyz>0 1 0</xyz><limit><velocity>0.05</velocity></limit></axis>")
    assert "<velocity>0.05</velocity>" in text
    world = tmp_path / "slow_pendulum.world"
    world.write_text(text)
    sim = Simulation(SimConfig(world=str(world), spawn_robot=False))
    try:
        xs = []
        for _ in range(STEPS_PER_S):
            sim.step()
            xs.append(links(sim, "pendulum")["pendulum::bob"][0][0])
    finally:
        sim.close()
    speeds = np.abs(np.diff(xs)) * STEPS_PER_S       # m/s of the bob, 1 m out: rad/s
    assert speeds.max() < 0.05 * 1.05
    assert xs[-1] - xs[0] > 0.03                     # it swings, at its top speed


def test_a_jointed_link_swings_with_the_files_inertia_not_its_shapes(tmp_path):
    # the bob's own moment 0.5 kg m^2 (its 5 cm sphere alone would give 0.001): the period
    # grows from 2.007 s to 2 pi sqrt((1 + 0.5) / 9.8) = 2.458 s
    text = open(os.path.join(JOINTS, "pendulum.world")).read().replace(
        "<ixx>0.001</ixx><iyy>0.001</iyy><izz>0.001</izz>",
        "<ixx>0.5</ixx><iyy>0.5</iyy><izz>0.5</izz>")
    assert "<iyy>0.5</iyy>" in text
    world = tmp_path / "heavy_bob.world"
    world.write_text(text)
    sim = Simulation(SimConfig(world=str(world), spawn_robot=False))
    try:
        ts, xs = [], []
        for _ in range(12 * STEPS_PER_S):
            sim.step()
            xs.append(links(sim, "pendulum")["pendulum::bob"][0][0])
            ts.append(sim.time)
    finally:
        sim.close()
    period = float(np.mean(np.diff(upward_crossings(np.array(ts), np.array(xs)))))
    expected = 2 * math.pi * math.sqrt((1.0 + 0.5) / 9.8)
    assert abs(period - expected) / expected < 0.02


def test_each_joint_moves_the_link_it_names_in_a_branching_tree(client):
    """A joint found by name (Body.joints, the world API, a drive's wheels) is the one pybullet
    built for it: each link's frame is where its joint puts it, in a tree whose links pybullet
    numbers depth first (a tricycle: a fork and its wheel ahead, two wheels behind)."""
    from tutorial_turtlebot.sim.engine.bodies import Body
    from unit_helpers import urdf_body

    link = ('<link name="%s"><inertial><mass value="0.3"/><inertia ixx="0.001" iyy="0.001" '
            'izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>')
    joint = ('<joint name="%s" type="continuous"><parent link="%s"/><child link="%s"/>'
             '<origin xyz="%s"/><axis xyz="0 1 0"/></joint>')
    urdf = "<robot name='tri'>%s</robot>" % "".join(
        [link % name for name in ("base", "fork", "front", "left", "right")]
        + [joint % ("fork_steer", "base", "fork", "0.25 0 0.05"),
           joint % ("left_wheel", "base", "left", "-0.15 0.2 0.05"),
           joint % ("right_wheel", "base", "right", "-0.15 -0.2 0.05"),
           joint % ("spin", "fork", "front", "0 0 -0.01")])
    body = Body(client, urdf_body(client, urdf))
    where = {j.name: tuple(np.round(body.link_frame(j.index)[0][0], 6)) for j in body.joints()}
    assert where == {"fork_steer": (0.25, 0.0, 0.05), "spin": (0.25, 0.0, 0.04),
                     "left_wheel": (-0.15, 0.2, 0.05), "right_wheel": (-0.15, -0.2, 0.05)}
    assert {j.name: j.child_link for j in body.joints()} == {
        "fork_steer": "fork", "spin": "front", "left_wheel": "left", "right_wheel": "right"}


def test_principal_axes_diagonalise_the_tensor_right_handed_and_ascending():
    """Jacobi's rotations in plain floats (not numpy's eigh, whose last bits differ between
    numpy builds): R^T I R is diagonal with the moments ascending, R a rotation."""
    from tutorial_turtlebot.sim.engine.movable_bodies import principal_axes
    rng = np.random.default_rng(7)
    tensors = [np.array([[0.00717896283442594, -1.2294101e-05, 0.0005767404678225616],
                         [-1.2294101e-05, 0.007218044692567651, -5.0120904e-06],
                         [0.0005767404678225616, -5.0120904e-06, 0.004138580358141712]])]
    for _ in range(50):
        q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
        tensors.append(q @ np.diag(rng.uniform(1e-6, 1.0, 3)) @ q.T)
    tensors.append(np.array([[2.0, 1.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.0, 3.0]]))  # a repeated 3
    for tensor in tensors:
        moments, axes = principal_axes(tensor.tolist())
        r = np.array(axes)
        assert list(moments) == sorted(moments)
        assert np.allclose(r.T @ r, np.eye(3), atol=1e-12) and np.linalg.det(r) > 0
        scale = np.abs(tensor).max()
        assert np.allclose(r.T @ tensor @ r, np.diag(moments), atol=1e-12 * scale)
        assert np.allclose(moments, np.linalg.eigvalsh(tensor), atol=1e-12 * scale)
