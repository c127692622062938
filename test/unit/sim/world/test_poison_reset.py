"""No input poisons the world for good: every entry point refuses what would (one line naming
the field), and reset_world / reset_simulation restore a good state whatever came before, even
bodies whose physics state went NaN (they are rebuilt). Real pybullet physics, no ROS master."""
import math

import numpy as np
import pytest

from tutorial_turtlebot.errors import RequestError
from tutorial_turtlebot.sim.engine.bullet import pybullet
from tutorial_turtlebot.sim.world.physics_properties import OdeConfig, PhysicsProperties
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import CUBE, ROBOT, WHEEL, at, box_sdf, run

NAN = float("nan")
REST = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
# a static wall 1 m ahead of the robot, as tall as the lidar: the scan has finite ranges
WALL = ("<sdf version='1.6'><model name='wall'><static>true</static><link name='link'>"
        "<collision name='c'><geometry><box><size>0.2 2 1</size></box></geometry></collision>"
        "</link></model></sdf>")


def poisons(wc):
    """(what is sent, the field its refusal names) through every entry point."""
    com = wc.get_link_properties("box::link").com
    inertia = wc.get_link_properties("box::link").inertia
    return [
        (lambda: wc.set_model_state(ROBOT, at(0, 0), ((1e308, 0, 0), (0, 0, 0))), "twist"),
        (lambda: wc.set_model_state(ROBOT, ((0, 0, 1e308), (0, 0, 0, 1)), REST), "position"),
        (lambda: wc.set_model_state(ROBOT, ((0, 0, 0), (NAN, 0, 0, 1)), REST), "NaN"),
        (lambda: wc.set_link_state("box::link", at(2, 2), ((0, 0, 0), (1e200, 0, 0))),
         "twist.angular.x"),
        (lambda: wc.spawn("far", CUBE, ((0, 1e308, 0), (0, 0, 0, 1))), "position.y"),
        (lambda: wc.spawn("heavy", box_sdf(mass=1e308, visual=False), at(3, 3, 0.1)), "<mass>"),
        (lambda: wc.spawn("u", WHEEL.replace('mass value="5"', 'mass value="nan"'),
                          at(3, -3, 0.1), kind="urdf"), "mass"),
        (lambda: wc.spawn("u", WHEEL.replace('ixx="0.1"', 'ixx="-1"'), at(3, -3, 0.1),
                          kind="urdf"), "ixx"),
        (lambda: wc.apply_body_wrench("box::link", "", (0, 0, 0), (0, 0, 1e300), (0, 0, 0)),
         "wrench.force.z"),
        (lambda: wc.apply_joint_effort("spin", -1e200), "effort"),
        (lambda: wc.set_link_properties("box::link", com, True, 1e308, inertia), "mass"),
        (lambda: wc.set_model_configuration("w", ["spin"], [1e300]), "joint_positions"),
        (lambda: wc.set_physics_properties(PhysicsProperties(gravity=(1e308, 0.0, -9.8))),
         "gravity.x"),
        (lambda: wc.set_physics_properties(PhysicsProperties(ode=OdeConfig(
            sor_pgs_iters=4294967295))), "sor_pgs_iters"),
    ]


def poison_the_bullet_state(sim):
    """What no request can do any more: NaN written straight into the physics of the robot,
    the spawned SDF box and the spawned URDF model."""
    cid = sim.physics.client
    for name in (ROBOT, "box", "w"):
        body = sim.models.get(name).parts[0].body.uid
        pybullet.resetBaseVelocity(body, (NAN, 0, 0), (0, 0, 0), physicsClientId=cid)
    run(sim, 0.2)
    assert not all(math.isfinite(v) for v in _state(sim, ROBOT))


def _state(sim, name):
    pose, twist, _ = WorldControl(sim).get_model_state(name)
    return pose[0] + pose[1] + twist[0] + twist[1]


def assert_good(sim, wc, spawn_z_box, spawn_z_wheel):
    run(sim, 2.5)     # long enough to fall through the floor if the body were broken
    for name in wc.models.names():
        assert all(math.isfinite(v) for v in _state(sim, name)), name
    (x, y, z), _ = wc.get_model_state(ROBOT)[0]
    assert (x, y) == pytest.approx((0.0, 0.0), abs=0.01) and abs(z) < 0.01
    assert wc.get_model_state("box")[0][0] == pytest.approx((2, 2, spawn_z_box), abs=0.01)
    assert wc.get_model_state("w")[0][0][2] == pytest.approx(spawn_z_wheel, abs=0.02)
    ranges = np.asarray(sim.robot.scan())
    assert np.isfinite(ranges).any()
    assert np.nanmin(ranges) == pytest.approx(0.9, abs=0.1)   # the wall's face, 0.9 m ahead


@pytest.mark.parametrize("reset", ["reset_world", "reset_simulation"])
def test_poison_every_entry_point_then_reset(reset):
    sim = Simulation(SimConfig(model="burger", world="empty"))
    try:
        wc = WorldControl(sim)
        wc.spawn("wall", WALL, at(1.0, 0.0, 0.5))
        wc.spawn("box", CUBE, at(2, 2, 0.075))
        wc.spawn("w", WHEEL, at(-2, 2, 0.05), kind="urdf")
        run(sim, 0.5)
        rest_wheel = wc.get_model_state("w")[0][0][2]
        for send, field in poisons(wc):
            with pytest.raises(RequestError) as err:
                send()
            assert field in str(err.value) and "\n" not in str(err.value), str(err.value)
        assert_good(sim, wc, 0.075, rest_wheel)

        poison_the_bullet_state(sim)
        wc.apply_body_wrench("box::link", "", (0, 0, 0), (0, 0, 1.0), (0, 0, 0))
        getattr(sim, reset)()
        if reset == "reset_simulation":
            assert sim.time_ns == 0
        assert_good(sim, wc, 0.075, rest_wheel)
        assert sim.forces.wrenches == []      # what acted on the old bodies went with them
        # the rebuilt models answer the world API as before
        assert wc.model_properties("w").joint_names == ["spin"]
        wc.apply_joint_effort("spin", 0.01, duration_ns=10_000_000)
        wc.set_model_state("box", at(2, 2, 0.3), REST)
        run(sim, 1.0)
        assert wc.get_model_state("box")[0][0][2] == pytest.approx(0.075, abs=0.01)
    finally:
        sim.close()


def test_a_teleport_repairs_a_poisoned_model():
    """set_model_state of a model whose state went NaN rebuilds it, then moves it (before,
    it answered success and changed nothing)."""
    sim = Simulation(SimConfig(model="burger", world="empty"))
    try:
        wc = WorldControl(sim)
        wc.spawn("box", CUBE, at(2, 2, 0.075))
        wc.spawn("w", WHEEL, at(-2, 2, 0.05), kind="urdf")
        poison_the_bullet_state(sim)
        wc.set_model_state(ROBOT, at(1, -1, 0.0), REST)
        wc.set_model_state("box", at(-1, -1, 0.3), REST)
        wc.set_link_state("w::base", at(3, 0, 0.2), REST)
        run(sim, 2.0)
        assert wc.get_model_state(ROBOT)[0][0] == pytest.approx((1, -1, 0), abs=0.02)
        assert wc.get_model_state("box")[0][0] == pytest.approx((-1, -1, 0.075), abs=0.01)
        assert wc.get_model_state("w")[0][0][:2] == pytest.approx((3, 0), abs=0.05)
        assert abs(wc.get_model_state("w")[0][0][2]) < 0.2
    finally:
        sim.close()
