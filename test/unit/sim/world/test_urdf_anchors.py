"""Plain URDF models held in place as Gazebo holds them (sim/world/world_spawns.py,
world_models.py, files/urdf/urdf_to_sdf.py): a static one (<gazebo><static>true</static>) and one
joined to the world by a root link "world" stay where they were spawned while a plain one
falls, are listed as Gazebo lists them, are hit by a robot and seen by its laser, teleport, and
come back from the body pool; a mesh file found nowhere is left out with one warning. The
fixtures are test/fixtures/urdf_anchors/. Real pybullet, no ROS master."""
import math
import os

import numpy as np
import pytest

from tutorial_turtlebot.sim.engine import collision_filters
from tutorial_turtlebot.sim.engine.collision_groups import (WORLD_COLLISION_GROUP,
                                                            WORLD_COLLISION_MASK)

from unit_helpers import ROBOT, at, run
import unit_paths

ANCHORS = os.path.normpath(os.path.join(unit_paths.UNIT, os.pardir, "fixtures", "urdf_anchors"))
TEN_SECONDS = 4000            # steps of 2.5 ms
STILL = 1e-6                  # m, rad: what "did not move" allows


def fixture(name):
    with open(os.path.join(ANCHORS, name)) as f:
        return f.read()


ENV = fixture("static_env.urdf")
with open(os.path.join(ANCHORS, os.pardir, "urdf_pendulum", "pendulum.urdf")) as _f:
    PENDULUM = _f.read()
POST = fixture("world_anchored.urdf")
PLAIN_ENV = ENV.replace("<static>true</static>", "")
# a turntable on a revolute joint to the world: it turns about that joint and goes nowhere
TURNTABLE = """<robot name="turntable"><link name="world"/>
<joint name="spindle" type="revolute"><parent link="world"/><child link="table"/>
<origin xyz="0 0 0.5"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="5" velocity="5"/>
</joint>
<link name="table"><inertial><origin xyz="0.2 0 0"/><mass value="1"/>
<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><origin xyz="0.2 0 0"/><geometry><box size="0.4 0.1 0.05"/></geometry></collision>
</link></robot>"""


def moved(a, b):
    """The largest difference (m or quaternion component) between two poses."""
    return max(np.max(np.abs(np.subtract(a[0], b[0]))),
               min(np.max(np.abs(np.subtract(a[1], b[1]))),
                   np.max(np.abs(np.add(a[1], b[1])))))


def uids(model):
    """The model's pybullet bodies (a static one is a body per shape, as an SDF model's)."""
    return set(model.body_ids())


def test_static_and_world_anchored_models_stay_while_a_plain_one_falls(empty):
    sim, wc = empty
    spawned = {"env": (ENV, at(3.0, 0.0, 1.0, yaw=0.3)), "post": (POST, at(-2.0, 0.0, 1.0)),
               "plain": (PLAIN_ENV, at(-3.0, 3.0, 1.0))}
    for name, (text, pose) in spawned.items():
        wc.spawn(name, text, pose, kind="urdf")
    links = {name: pose for name, pose, _ in wc.link_states()}
    for _ in range(TEN_SECONDS):
        sim.step()
    for name in ("env", "post"):
        pose = wc.get_model_state(name)[0]
        assert moved(pose, spawned[name][1]) < STILL, (name, pose)
        for scoped, now, _ in wc.link_states():
            if scoped.startswith(name + "::"):
                assert moved(now, links[scoped]) < STILL, scoped
    names = [n for n, _, _ in wc.model_states()]
    assert names[-3:] == ["env", "post", "plain"]
    assert moved(wc.get_model_state("plain")[0], spawned["plain"][1]) > 0.1   # it fell
    # the gate of the static model did not swing; the plain model's did
    assert links["env::gate"][0][2] == pytest.approx(2.0)
    assert wc.get_link_state("env::gate")[0][0][2] == pytest.approx(2.0, abs=STILL)
    assert wc.get_link_state("plain::gate")[0][0][2] < 1.0


def test_they_are_listed_as_gazebo_lists_them(empty):
    _, wc = empty
    wc.spawn("env", ENV, at(3.0, 0.0), kind="urdf")
    wc.spawn("post", POST, at(-2.0, 0.0), kind="urdf")
    env = wc.model_properties("env")
    assert env.is_static is True
    assert env.body_names == ["base", "gate"] and env.joint_names == ["gate_hinge"]
    assert env.geom_names == ["base_collision", "base_fixed_joint_lump__crate_collision_1",
                              "base_fixed_joint_lump__trough_collision_2", "gate_collision"]
    post = wc.model_properties("post")
    assert post.is_static is False                 # joined to the world, not static
    assert post.body_names == ["post", "head"]      # "world" is no link; lens lumped into head
    assert post.joint_names == ["world_joint", "pan"]
    assert post.geom_names == ["post_collision", "head_collision"]
    assert wc.get_joint_properties("post::world_joint").kind == "fixed"
    assert wc.get_joint_properties("env::gate_hinge").position == [0.0]
    # the static model's links are where the file puts them in the model frame
    assert wc.get_link_state("env::gate")[0][0] == pytest.approx((3.0, 1.2, 1.0))
    assert wc.get_link_state("post::post")[0][0] == pytest.approx((-2.0, 0.0, 0.75))
    assert wc.get_link_state("post::head")[0][0] == pytest.approx((-2.0, 0.0, 1.55), abs=1e-6)
    assert wc.get_link_properties("env::gate").mass == 0.0      # static: nothing to weigh
    assert wc.get_link_properties("post::head").mass == pytest.approx(0.3, abs=1e-5)  # + lens


def test_a_static_model_collides_as_a_world_body_and_its_mesh_as_triangles(empty):
    sim, wc = empty
    wc.spawn("env", ENV, at(3.0, 0.0), kind="urdf")
    wc.spawn("plain", PLAIN_ENV, at(-3.0, 0.0), kind="urdf")
    client = sim.physics.client
    env = sim.models.get("env")
    for body in uids(env):
        assert collision_filters.colliders(client)[(body, -1)] == (
            WORLD_COLLISION_GROUP, WORLD_COLLISION_MASK)
    # down through the open trough (floor 0.5 m up, walls to 1.5 m): its floor, not its top
    ray = client.rayTest((4.5, 0.0, 3.0), (4.5, 0.0, -1.0),
                         collisionFilterMask=WORLD_COLLISION_GROUP)[0]
    assert ray[0] in uids(env) and ray[3][2] == pytest.approx(0.5, abs=0.01)
    # a movable model's trough collides as its hull: the ray stops at the walls' top
    ray = client.rayTest((-1.5, 0.0, 3.0), (-1.5, 0.0, -1.0))[0]
    assert ray[0] in uids(sim.models.get("plain")) and ray[3][2] == pytest.approx(1.5, abs=0.01)


def test_a_robot_driven_into_a_static_wall_stops_and_its_laser_sees_it(empty):
    sim, wc = empty
    wc.spawn("env", ENV, at(1.0, 0.0), kind="urdf")        # its wall at x 0.95 .. 1.05
    run(sim, 0.5)
    assert sim.robot.scan()[0] == pytest.approx(0.95 + 0.032, abs=0.02)   # base_scan x -0.032
    sim.robot.command(0.2, 0.0)
    run(sim, 8.0)                                            # 1.6 m if nothing stood there
    x = sim.robot.ground_truth()[0][0]
    assert 0.7 < x < 0.95
    assert moved(wc.get_model_state("env")[0], at(1.0, 0.0)) < STILL


def test_a_static_model_teleports_resets_and_comes_back_from_the_pool(empty):
    sim, wc = empty
    wc.spawn("env", ENV, at(3.0, 0.0), kind="urdf")
    first = uids(sim.models.get("env"))
    wc.set_model_state("env", at(3.0, 2.0, 0.5, yaw=math.pi / 2), ((0, 0, 0), (0, 0, 0)))
    run(sim, 1.0)
    assert moved(wc.get_model_state("env")[0], at(3.0, 2.0, 0.5, yaw=math.pi / 2)) < STILL
    assert wc.get_link_state("env::gate")[0][0] == pytest.approx((1.8, 2.0, 1.5))
    sim.reset_world()
    assert moved(wc.get_model_state("env")[0], at(3.0, 0.0)) < STILL
    wc.delete("env")
    wc.spawn("env2", ENV, at(-3.0, 0.0, 1.0), kind="urdf")   # the same text: the parked body
    again = sim.models.get("env2")
    assert uids(again) == first and again.static
    for body in first:
        assert collision_filters.colliders(sim.physics.client)[(body, -1)] == (
            WORLD_COLLISION_GROUP, WORLD_COLLISION_MASK)
    run(sim, 2.0)
    assert moved(wc.get_model_state("env2")[0], at(-3.0, 0.0, 1.0)) < STILL


def test_a_revolute_joint_to_the_world_turns_in_place(empty):
    sim, wc = empty
    wc.spawn("turntable", TURNTABLE, at(2.0, -2.0), kind="urdf")
    assert wc.model_properties("turntable").body_names == ["table"]
    wc.set_model_configuration("turntable", ["spindle"], [1.0])
    run(sim, 1.0)
    assert wc.get_joint_properties("turntable::spindle").position[0] == pytest.approx(1.0,
                                                                                      abs=0.01)
    assert moved(wc.get_model_state("turntable")[0], at(2.0, -2.0)) < STILL
    table = wc.get_link_state("turntable::table")[0]
    assert table[0] == pytest.approx((2.0, -2.0, 0.5), abs=1e-6)     # turned about the spindle
    assert 2 * math.atan2(table[1][2], table[1][3]) == pytest.approx(1.0, abs=0.01)


def test_a_missing_mesh_is_one_warning_and_the_rest_of_the_model_is_there(empty):
    sim, wc = empty
    warnings = wc.spawn("env", ENV, at(3.0, 0.0), kind="urdf")
    (warning,) = warnings
    assert "link 'barn' <collision> left out" in warning and "barn.dae not found" in warning
    assert "env" in sim.models and ROBOT in sim.models
    assert wc.model_properties("env").body_names == ["base", "gate"]
    client = sim.physics.client                   # the crate's mesh is there: a ray hits it
    ray = client.rayTest((3.0, -2.0, 2.0), (3.0, -2.0, -1.0))[0]
    assert ray[0] in uids(sim.models.get("env")) and ray[3][2] == pytest.approx(0.5, abs=0.01)


def test_a_pendulum_on_a_world_root_swings_under_gravity_and_comes_back_from_the_pool(empty):
    """A plain URDF is the SDF model Gazebo makes of it (urdf_to_sdf): the weight fixed to the
    bob is lumped into it with Gazebo's names, the revolute joint is simulated: the bob,
    level at first, swings down under gravity while the model stays joined to the world; a
    second spawn of the same text takes the parked bodies and swings again."""
    sim, wc = empty
    assert wc.spawn("pendulum", PENDULUM, at(1.0, 2.0), kind="urdf") == []
    props = wc.model_properties("pendulum")
    assert props.body_names == ["post", "bob"] and props.joint_names == ["world_joint", "swing"]
    assert props.geom_names == ["post_collision", "bob_collision",
                                "bob_fixed_joint_lump__weight_collision_1"]
    assert wc.get_link_properties("pendulum::bob").mass == pytest.approx(1.0)   # + weight
    bob = wc.get_link_state("pendulum::bob")[0]
    assert bob[0] == pytest.approx((1.0, 2.1, 1.0), abs=1e-6)
    run(sim, 0.3)
    angle = wc.get_joint_properties("pendulum::swing").position[0]
    assert angle > 0.3                      # about +y: the bob's end goes down
    assert wc.get_link_state("pendulum::bob")[0][0] == pytest.approx((1.0, 2.1, 1.0), abs=1e-4)
    assert moved(wc.get_model_state("pendulum")[0], at(1.0, 2.0)) < STILL
    first = uids(sim.models.get("pendulum"))
    wc.delete("pendulum")
    wc.spawn("again", PENDULUM, at(-1.0, 0.0), kind="urdf")
    assert uids(sim.models.get("again")) == first
    assert wc.get_joint_properties("again::swing").position[0] == pytest.approx(0.0, abs=1e-9)
    run(sim, 0.3)
    assert wc.get_joint_properties("again::swing").position[0] == pytest.approx(angle, abs=0.02)
