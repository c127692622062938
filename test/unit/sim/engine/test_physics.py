"""WorldPhysics and RobotBody (engine/physics.py, engine/robot_body.py), directly: the client's
set-up and step, its parameters, ray casts, the robots' collision bits, and a robot body's
placement. What the Simulation makes of them is tested in sim/world/. No ROS master."""
import math

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.errors import UserError
from tutorial_turtlebot.sim.engine.physics import (FIRST_ROBOT_BIT, GRAVITY, MAX_ROBOTS,
                                                   ROBOT_GROUPS, WorldPhysics)
from tutorial_turtlebot.sim.engine.robot_body import SPAWN_CLEARANCE, RobotBody
from tutorial_turtlebot.sim.engine.world_bullet import (ALL_COLLISION_GROUPS,
                                                        WORLD_COLLISION_GROUP)
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, urdf_path
from tutorial_turtlebot.sim.files.sdf.world_catalogue import resolve_world
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world

STEP = 0.0025


@pytest.fixture
def physics():
    """WorldPhysics of the empty world (a ground plane, its top at z = 0)."""
    made = WorldPhysics(load_world(resolve_world("empty")[0]), STEP, solver_iterations=17)
    yield made
    made.close()


def add_box(physics, centre, half=0.5, group=WORLD_COLLISION_GROUP):
    """A static box of half side ``half`` at ``centre``, in collision group ``group``."""
    cid = physics.client
    shape = pybullet.createCollisionShape(pybullet.GEOM_BOX, halfExtents=(half,) * 3,
                                          physicsClientId=cid)
    box = pybullet.createMultiBody(0, shape, basePosition=centre, physicsClientId=cid)
    pybullet.setCollisionFilterGroupMask(box, -1, group, ALL_COLLISION_GROUPS,
                                         physicsClientId=cid)
    return box


def test_the_client_is_set_up(physics):
    params = pybullet.getPhysicsEngineParameters(physicsClientId=physics.client)
    assert params["fixedTimeStep"] == STEP and params["numSolverIterations"] == 17
    assert (params["gravityAccelerationX"], params["gravityAccelerationY"],
            params["gravityAccelerationZ"]) == (0.0, 0.0, -GRAVITY)
    assert physics.world_bodies                       # the ground plane
    assert physics.gui is False and physics.egl is False


def test_step_advances_one_time_step(physics):
    """A free ball falls g t^2 / 2 in 100 steps (semi-implicit Euler: g t^2 / 2 plus half a
    step's worth)."""
    cid = physics.client
    shape = pybullet.createCollisionShape(pybullet.GEOM_SPHERE, radius=0.05, physicsClientId=cid)
    ball = pybullet.createMultiBody(1.0, shape, basePosition=(0, 0, 10), physicsClientId=cid)
    pybullet.changeDynamics(ball, -1, linearDamping=0.0, physicsClientId=cid)
    for _ in range(100):
        physics.step()
    z = pybullet.getBasePositionAndOrientation(ball, physicsClientId=cid)[0][2]
    n = 100
    assert 10.0 - z == pytest.approx(GRAVITY * STEP ** 2 * n * (n + 1) / 2, rel=1e-4)
    vz = pybullet.getBaseVelocity(ball, physicsClientId=cid)[0][2]
    assert vz == pytest.approx(-GRAVITY * n * STEP, rel=1e-4)


def test_set_parameters(physics):
    # (not contactBreakingThreshold: Bullet keeps that one for the whole process, every client)
    physics.set_parameters(0.004, (0.5, 0.0, -3.0), {"numSolverIterations": 37})
    params = pybullet.getPhysicsEngineParameters(physicsClientId=physics.client)
    assert params["fixedTimeStep"] == 0.004 and physics.time_step == 0.004
    assert params["numSolverIterations"] == 37
    assert (params["gravityAccelerationX"], params["gravityAccelerationY"],
            params["gravityAccelerationZ"]) == (0.5, 0.0, -3.0)


def test_ray_distances_to_a_box(physics):
    """A box whose near face is 2.5 m ahead: that distance within 1 mm; inf where nothing is
    within range (the floor too far below, or behind)."""
    add_box(physics, (3.0, 0.0, 1.0))
    origin = np.array([0.0, 0.0, 1.0])
    directions = np.array([[1.0, 0.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, -1.0],
                           [0.0, 1.0, 0.0], [math.cos(0.1), math.sin(0.1), 0.0]])
    distances = physics.ray_distances(origin, directions, 3.5)
    assert distances.shape == (5,)
    assert distances[0] == pytest.approx(2.5, abs=1e-3)
    assert distances[1] == math.inf and distances[3] == math.inf
    assert distances[2] == pytest.approx(1.0, abs=1e-3)             # the ground plane's top
    assert distances[4] == pytest.approx(2.5 / math.cos(0.1), abs=1e-3)
    # Beyond max_range: nothing.
    assert np.all(np.isinf(physics.ray_distances(origin, directions[:1], 2.0)))


def test_ray_distances_see_only_the_mask(physics):
    add_box(physics, (3.0, 0.0, 1.0), group=1 << FIRST_ROBOT_BIT)     # a "robot"
    origin, ahead = np.array([0.0, 0.0, 1.0]), np.array([[1.0, 0.0, 0.0]])
    assert physics.ray_distances(origin, ahead, 3.5)[0] == math.inf   # the world only
    assert physics.ray_distances(origin, ahead, 3.5, mask=ROBOT_GROUPS)[0] == pytest.approx(
        2.5, abs=1e-3)


def test_robot_bits_run_out_after_max_robots(physics):
    bits = [physics.take_robot_bit() for _ in range(MAX_ROBOTS)]
    assert bits[0] == 1 << FIRST_ROBOT_BIT
    assert len(set(bits)) == MAX_ROBOTS
    assert all(bin(b).count("1") == 1 and b & ROBOT_GROUPS == b for b in bits)
    assert not any(b & WORLD_COLLISION_GROUP for b in bits)
    assert max(bits) <= ALL_COLLISION_GROUPS
    with pytest.raises(UserError, match="at most %d robots" % MAX_ROBOTS):
        physics.take_robot_bit()
    physics.give_back_robot_bit(bits[7])
    physics.give_back_robot_bit(bits[3])
    assert physics.take_robot_bit() == bits[3]          # the lowest free bit first
    assert physics.take_robot_bit() == bits[7]
    with pytest.raises(UserError):
        physics.take_robot_bit()


def test_close_disconnects_once(physics):
    cid = physics.client
    physics.close()
    assert physics.client is None
    assert pybullet.getConnectionInfo(physicsClientId=cid)["isConnected"] == 0
    physics.close()                                       # again: nothing to do


def test_a_robot_body_stands_at_its_spawn_pose_with_its_bit(physics):
    description = read_urdf(urdf_path("burger"))
    yaw = 0.3
    pose = ((1.0, -0.5, 0.0), (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)))
    robot = RobotBody(physics, description, pose, ("wheel_left_joint", "wheel_right_joint"),
                      0.1)
    assert robot.collision_bit == 1 << FIRST_ROBOT_BIT
    assert not robot.ray_mask & robot.collision_bit       # its rays never meet itself
    assert robot.ray_mask & WORLD_COLLISION_GROUP
    (x, y, z), orn = robot.footprint_pose()
    assert (x, y, z) == pytest.approx((1.0, -0.5, SPAWN_CLEARANCE), abs=1e-6)
    assert orn == pytest.approx(pose[1], abs=1e-6)
    assert robot.wheel_states() == ((0.0, 0.0), (0.0, 0.0))
    # A ray from 1 m ahead back at the chassis meets it, unless it is one of the robot's own.
    ahead = np.array([math.cos(yaw), math.sin(yaw), 0.0])
    origin = np.array([1.0, -0.5, 0.1]) + ahead
    back = -ahead[None, :]
    assert 0.85 < physics.ray_distances(origin, back, 1.0, ALL_COLLISION_GROUPS)[0] < 1.0
    assert physics.ray_distances(origin, back, 1.0, robot.collision_bit)[0] < 1.0
    assert physics.ray_distances(origin, back, 1.0, robot.ray_mask)[0] == math.inf
    robot.remove()
    assert physics.take_robot_bit() == 1 << FIRST_ROBOT_BIT   # given back
