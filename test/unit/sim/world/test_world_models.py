"""The world as models with the real pybullet physics (sim/world_models, world_control,
world_bullet's movable bodies). No ROS master."""
import math

import pytest

from tutorial_turtlebot.errors import RequestError, UserError
from tutorial_turtlebot.sim.world import reference_frames as rf
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl
from tutorial_turtlebot.sim.world.world_models import (robot_model_name, spawn_failure,
                                                       spawn_refusal)

from unit_helpers import at, box_sdf, run


@pytest.mark.parametrize("world, model, names", [
    ("empty", "waffle", ["ground_plane", "turtlebot3_waffle"]),
    ("turtlebot3_world", "burger", ["ground_plane", "ros_symbol", "turtlebot3_burger"]),
    ("turtlebot3_house", "burger", ["ground_plane", "turtlebot3_house", "turtlebot3"]),
    ("turtlebot3_stage_1", "waffle", ["ground_plane", "turtlebot3_square", "turtlebot3_burger"]),
    ("turtlebot3_stage_2", "burger", ["ground_plane", "turtlebot3_square", "obstacle",
                                      "turtlebot3_burger"]),
    ("turtlebot3_stage_4", "burger", ["ground_plane", "turtlebot3_plaza", "obstacle_1",
                                      "obstacle_2", "turtlebot3_burger"]),
])
def test_model_order_world_then_robot(world, model, names):
    sim = Simulation(SimConfig(model=model, world=world, camera=False))
    try:
        assert sim.models.names() == names
    finally:
        sim.close()


def test_robot_name_param_overrides():
    assert robot_model_name("turtlebot3_world", "waffle_pi") == "turtlebot3_waffle_pi"
    sim = Simulation(SimConfig(world="empty", robot_name="tb3_0"))
    try:
        assert sim.models.names() == ["ground_plane", "tb3_0"]
    finally:
        sim.close()


def test_spawn_order_and_duplicate_and_delete(empty):
    sim, wc = empty
    wc.spawn("a", box_sdf(), at(1, 1, 0.075))
    wc.spawn("b", box_sdf(), at(1, -1, 0.075))
    assert sim.models.names() == ["ground_plane", "turtlebot3_burger", "a", "b"]
    with pytest.raises(RequestError, match="entity already exists"):
        wc.spawn("a", box_sdf(), at(2, 2, 0.075))
    wc.delete("a")
    assert sim.models.names() == ["ground_plane", "turtlebot3_burger", "b"]
    with pytest.raises(RequestError, match="DeleteModel: model does not exist"):
        wc.delete("a")
    wc.delete("turtlebot3_burger")           # a robot goes with its plugins' outputs
    assert sim.models.names() == ["ground_plane", "b"] and sim.robot is None
    assert sim.robots == {} and all(robot is None for robot, _ in sim.step())


def test_the_robot_pushes_a_light_box(empty):
    sim, wc = empty
    wc.spawn("box", box_sdf(), at(0.4, 0.0, 0.075))
    run(sim, 0.5)
    start = wc.get_model_state("box")[0][0]
    sim.robot.command(0.2, 0.0)
    run(sim, 4.0)
    end = wc.get_model_state("box")[0][0]
    robot = wc.get_model_state("turtlebot3_burger")[0][0]
    assert end[0] - start[0] > 0.4           # pushed along +x
    assert end[0] > robot[0]                 # still ahead of the robot, not passed through


def test_a_box_knocked_off_a_table_falls(empty):
    sim, wc = empty
    table = ("<sdf><model name='t'><static>1</static><link name='top'><pose>1 0 0.4 0 0 0</pose>"
             "<collision name='c'><geometry><box><size>0.6 0.6 0.05</size></box></geometry>"
             "</collision></link></model></sdf>")
    wc.spawn("table", table, at(0, 0))
    wc.spawn("box", box_sdf(size=0.1), at(1.0, 0.0, 0.475))
    run(sim, 1.0)
    assert wc.get_model_state("box")[0][0][2] == pytest.approx(0.475, abs=0.01)   # on the table
    wc.set_model_state("box", wc.get_model_state("box")[0], ((4.0, 0.0, 0.0), (0, 0, 0)))
    run(sim, 2.0)
    assert wc.get_model_state("box")[0][0][2] == pytest.approx(0.05, abs=0.01)    # on the floor


def test_spawned_and_world_models_go_back_to_their_spawn(empty):
    sim, wc = empty
    wc.spawn("box", box_sdf(), at(0.5, 1.0, 0.075, yaw=0.5))
    wc.set_model_state("box", at(2, 2, 0.075), ((0.5, 0, 0), (0, 0, 0)))
    wc.set_model_state("turtlebot3_burger", at(-1, -1), rf.ZERO_TWIST)
    run(sim, 0.5)
    sim.reset_world()
    pose, twist, _ = wc.get_model_state("box")
    assert pose[0] == pytest.approx((0.5, 1.0, 0.075), abs=1e-6)
    assert rf.rpy_from_quat(pose[1])[2] == pytest.approx(0.5, abs=1e-6)
    assert twist == rf.ZERO_TWIST
    assert wc.get_model_state("turtlebot3_burger")[0][0][:2] == pytest.approx((0, 0), abs=1e-6)
    wc.set_model_state("box", at(2, 2, 0.075), rf.ZERO_TWIST)
    sim.reset_simulation()
    assert sim.time == 0.0
    assert wc.get_model_state("box")[0][0] == pytest.approx((0.5, 1.0, 0.075), abs=1e-6)


def test_teleport_with_a_frame_and_zero_twist_stops(empty):
    sim, wc = empty
    wc.spawn("box", box_sdf(), at(1.0, 0.0, 0.075, yaw=math.pi / 2))
    wc.spawn("other", box_sdf(), at(3.0, 3.0, 0.075))
    wc.set_model_state("other", at(1.0, 0.0, 0.0), ((1.0, 0, 0), (0, 0, 0)), reference="box")
    pose, twist, _ = wc.get_model_state("other")
    assert pose[0] == pytest.approx((1.0, 1.0, 0.075), abs=1e-6)     # box's +x is world +y
    assert twist[0] == pytest.approx((0.0, 1.0, 0.0), abs=1e-6)       # twist rotated too
    rel, _, _ = wc.get_model_state("other", "box")
    assert rel[0] == pytest.approx((1.0, 0.0, 0.0), abs=1e-6)
    wc.set_model_state("other", at(2.0, 0.0, 0.075), rf.ZERO_TWIST)
    run(sim, 0.2)
    assert wc.get_model_state("other")[1][0] == pytest.approx((0, 0, 0), abs=1e-3)


def test_failure_answers(empty):
    sim, wc = empty
    cases = [
        (lambda: wc.get_model_state("nope"), "GetModelState: model does not exist"),
        (lambda: wc.get_model_state("turtlebot3_burger", "nope"), "did you forget to scope"),
        (lambda: wc.set_model_state("nope", at(0, 0), rf.ZERO_TWIST),
         "SetModelState: model does not exist"),
        (lambda: wc.set_model_state("turtlebot3_burger", ((math.nan, 0, 0), (0, 0, 0, 1)),
                                    rf.ZERO_TWIST), "NaN"),
        (lambda: wc.get_link_state("turtlebot3_burger::nope"), "does not exist"),
        (lambda: wc.model_properties("nope"), "GetModelProperties: model does not exist"),
        (lambda: wc.spawn("b", box_sdf(), at(0, 0), reference="nope"), "reference_frame"),
    ]
    for call, words in cases:
        with pytest.raises(RequestError, match=words):
            call()


def test_link_states_and_properties(empty):
    sim, wc = empty
    names = [name for name, _, _ in wc.link_states()]
    assert names == ["ground_plane::link", "turtlebot3_burger::base_footprint",
                     "turtlebot3_burger::wheel_left_link", "turtlebot3_burger::wheel_right_link"]
    pose, _ = wc.get_link_state("turtlebot3_burger::base_footprint")
    assert pose[0] == pytest.approx(wc.get_model_state("turtlebot3_burger")[0][0], abs=1e-9)
    props = wc.model_properties("turtlebot3_burger")
    assert props.body_names[0] == "base_footprint" and not props.is_static
    assert props.joint_names == ["wheel_left_joint", "wheel_right_joint"]
    assert wc.model_properties("ground_plane").is_static


def test_physics_properties_change_the_step(empty):
    sim, wc = empty
    props = wc.physics_properties()
    assert props.time_step == 0.0025 and props.real_time_factor == pytest.approx(1.0)
    from dataclasses import replace
    wc.set_physics_properties(replace(props, time_step=0.001, max_update_rate=0.0))
    start = sim.time
    sim.step()
    assert sim.time - start == pytest.approx(0.001)
    with pytest.raises(RequestError, match="time_step"):
        wc.set_physics_properties(replace(props, time_step=1.0))


def test_lidar_samples():
    sim = Simulation(SimConfig(world="turtlebot3_stage_1", lidar_samples=24))
    try:
        ranges = sim.robot.scan()
        assert len(ranges) == 24
        assert sim.robot.laser.angle_increment == pytest.approx(6.28319 / 23)
        # the square's inner faces are 1.925 m away ahead, left, behind (index 6 = 1.64 rad)
        assert ranges[0] == pytest.approx(1.925, abs=0.05)
    finally:
        sim.close()


def test_stage_3_obstacle_spins_when_given_a_twist():
    sim = Simulation(SimConfig(world="turtlebot3_stage_3"))
    wc = WorldControl(sim)
    try:
        run(sim, 0.5)
        for _ in range(10):        # as moving_obstacle.py: same pose, angular z 0.5, again
            pose = wc.get_model_state("obstacle")[0]
            wc.set_model_state("obstacle", pose, ((0, 0, 0), (0, 0, 0.5)))
            run(sim, 0.1)
        yaw = rf.rpy_from_quat(wc.get_model_state("obstacle")[0][1])[2]
        assert yaw > 0.1
        centre = wc.get_model_state("obstacle")[0][0]
        assert math.hypot(centre[0], centre[1]) < 0.01    # about its own centre
    finally:
        sim.close()


def test_a_spawn_refusal_prefixes_a_user_error_once():
    """spawn_refusal: a UserError becomes the spawn's refusal; a RequestError (a UserError
    too) already is one and goes on unchanged."""
    with pytest.raises(RequestError) as err:
        with spawn_refusal():
            raise UserError("model_xml: no <model>")
    assert str(err.value) == "SpawnModel: Failure - model_xml: no <model>"
    with pytest.raises(RequestError) as err:
        with spawn_refusal():
            raise spawn_failure("mesh triangles: 12, more than the 11")
    assert str(err.value) == "SpawnModel: Failure - mesh triangles: 12, more than the 11"
