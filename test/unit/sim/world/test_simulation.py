"""The ROS-free simulator (``Simulation``) with real pybullet physics. No ROS master.

Numbers from doc/turtlebot3.md sections 1, 2 and 4.2; the arena of turtlebot3_world is a hexagonal
ring with corners on the x axis, inner circumradius 2.933 m and inner flats 2.540 m from the
centre. Sim time only: nothing here depends on how fast the machine is.
"""
import math

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.sim import kinematics
from tutorial_turtlebot.sim.devices.diff_drive import SAFE_LINEAR
from tutorial_turtlebot.errors import UserError
from tutorial_turtlebot.robot_models import MODELS
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, urdf_path

from unit_helpers import run as run_counting

MODEL_NAMES = ("burger", "waffle", "waffle_pi")
TB3_SPAWN = (-2.0, -0.5)
ARENA_APOTHEM = 2.540        # centre to each inner flat of the hexagonal wall, m
ARENA_CIRCUMRADIUS = 2.933   # centre to each inner corner, m
WALL_NORMALS = [(math.cos(math.radians(a)), math.sin(math.radians(a)))
                for a in (30, 90, 150, 210, 270, 330)]
CONTACT_SLOP = 0.005         # m a body may sink into a wall (pybullet margins, soft contact)
TOTAL_MASS = {"burger": 1.00, "waffle": 1.55, "waffle_pi": 1.55}   # kg (doc/turtlebot3.md 1.2)
SCAN_X = {"burger": -0.032, "waffle": -0.064, "waffle_pi": -0.064}  # base_scan in footprint


def collision_points(description, ring=16):
    """Points (n x 3, in base_footprint) on the hull of every collision shape of the URDF:
    box corners, the rims of cylinders (wheels, LDS) and the poles of spheres."""
    root = description.root_link
    points = []
    for name, link in description.links.items():
        for collision in link.collisions:
            shape, size = collision.geometry.shape, collision.geometry.size
            if shape == "box":
                local = [(sx * size[0] / 2, sy * size[1] / 2, sz * size[2] / 2)
                         for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
            elif shape == "cylinder":
                radius, length = size
                local = [(radius * math.cos(a), radius * math.sin(a), sz * length / 2)
                         for a in np.linspace(0, 2 * math.pi, ring, endpoint=False)
                         for sz in (-1, 1)]
            elif shape == "sphere":
                local = [tuple(size[0] * np.eye(3)[i] * sign) for i in range(3)
                         for sign in (-1, 1)]
            else:
                raise AssertionError("unexpected collision shape %s in %s" % (shape, name))
            pose = description.transform(root, name) @ collision.origin.matrix()
            homogeneous = np.hstack([np.array(local), np.ones((len(local), 1))])
            points.extend((pose @ homogeneous.T).T[:, :3])
    return np.array(points)


def world_outline(sim):
    """(x, y) of the robot's collision points in the world, tilt included, where it is now."""
    pos, orn = sim.robot.ground_truth()
    world = collision_points(sim.robot.description) @ kinematics.rotation_matrix(orn).T + pos
    return [tuple(p[:2]) for p in world]


def deepest(points, normal):
    """How far the points reach along a wall's outward normal, from the arena centre (m)."""
    return max(px * normal[0] + py * normal[1] for px, py in points)


def run(sim, seconds):
    """Step ``seconds`` of sim time; return how often each output was due (all robots)."""
    return run_counting(sim, seconds, per_robot=False)


def rpy(sim):
    return pybullet.getEulerFromQuaternion(sim.robot.ground_truth()[1])


def heading(sim):
    return kinematics.yaw_from_quat(sim.robot.ground_truth()[1])


@pytest.fixture
def make_sim():
    """Factory of Simulations, all closed at the end of the test."""
    sims = []

    def make(**kwargs):
        sim = Simulation(SimConfig(**kwargs))
        sims.append(sim)
        return sim

    yield make
    for sim in sims:
        sim.close()


@pytest.fixture(scope="module", params=MODEL_NAMES)
def resting(request):
    """Each model spawned in the empty world at (0.4, -0.3, yaw 0.7), left alone for 1 s."""
    sim = Simulation(SimConfig(model=request.param, world="empty", x=0.4, y=-0.3, yaw=0.7))
    run(sim, 1.0)
    yield sim
    sim.close()


# --- configuration -----------------------------------------------------------------------------

def test_default_config_is_valid():
    """The defaults (burger in turtlebot3_world) pass validation."""
    SimConfig().validate()


def test_bad_odom_source():
    """odom_source other than world/encoders: UserError naming it and the valid ones."""
    with pytest.raises(UserError, match="odom_source") as err:
        SimConfig(odom_source="gps").validate()
    assert "world" in str(err.value) and "encoders" in str(err.value)


@pytest.mark.parametrize("step", [0.0, -0.001, 0.00005, 0.02, math.nan, math.inf])
def test_bad_step_size(step):
    """A physics step outside 0.1..10 ms: UserError naming max_step_size (the node's param)."""
    with pytest.raises(UserError, match="max_step_size"):
        SimConfig(time_step=step).validate()


@pytest.mark.parametrize("name", ["clock_rate"])
@pytest.mark.parametrize("rate", [0.0, -1.0, math.nan, math.inf, 401.0, "fast"])
def test_bad_rates(name, rate):
    """A rate <= 0, non-finite, not a number or above the 400 Hz physics rate: UserError."""
    with pytest.raises(UserError, match=name):
        SimConfig(**{name: rate}).validate()


def test_rate_up_to_the_physics_rate_is_fine():
    """Every step (400 Hz at 2.5 ms) is the fastest allowed rate."""
    SimConfig(clock_rate=400.0).validate()


@pytest.mark.parametrize("name", ["x", "y", "z", "yaw"])
@pytest.mark.parametrize("value", [math.nan, math.inf, -math.inf, "1.0"])
def test_bad_spawn(name, value):
    """A spawn coordinate that is not a finite number: UserError naming it."""
    with pytest.raises(UserError, match=r"spawn %s\b" % name):
        SimConfig(**{name: value}).validate()


def test_bad_solver_iterations():
    """solver_iterations must be a positive integer."""
    with pytest.raises(UserError, match="solver_iterations"):
        SimConfig(solver_iterations=0).validate()


def test_simulation_validates_its_config():
    """Simulation() refuses a bad config before building anything."""
    with pytest.raises(UserError, match="odom_source"):
        Simulation(SimConfig(world="empty", odom_source="gps"))


@pytest.mark.parametrize("field, value, valid", [
    ("model", "burgers", ("burger", "waffle", "waffle_pi")),
    ("world", "turtlebot3_moon", ("empty", "turtlebot3_world")),
    ("lidar_model", "lds02", ("gazebo", "lds01")),
])
def test_unknown_names_list_the_valid_ones(field, value, valid):
    """Unknown model, world or lidar_model: UserError with the bad name and the valid ones."""
    with pytest.raises(UserError) as err:
        Simulation(SimConfig(**{field: value}))
    message = str(err.value)
    assert value in message
    assert all(name in message for name in valid)


# --- the robot at rest -------------------------------------------------------------------------

def test_rests_on_its_wheels_at_the_spawn(resting):
    """After 1 s alone: base_footprint on the floor at the spawn pose, level, still."""
    (x, y, z), _ = resting.robot.ground_truth()
    assert (x, y) == pytest.approx((0.4, -0.3), abs=0.003)
    assert abs(z) < 0.003
    roll, pitch, _ = rpy(resting)
    assert abs(roll) < 0.03 and abs(pitch) < 0.03
    assert heading(resting) == pytest.approx(0.7, abs=0.01)
    lin, ang = resting.robot.body.velocity()
    assert np.linalg.norm(lin) < 0.01 and np.linalg.norm(ang) < 0.05


def test_total_mass_matches_the_urdf(resting):
    """The masses pybullet simulates add up to the URDF's: ~1.00 kg burger, ~1.55 kg waffles."""
    phys = resting.robot.body
    links = range(-1, pybullet.getNumJoints(phys.robot, physicsClientId=phys.client))
    total = sum(pybullet.getDynamicsInfo(phys.robot, link, physicsClientId=phys.client)[0]
                for link in links)
    assert total == pytest.approx(resting.robot.description.mass, abs=1e-4)
    assert total == pytest.approx(TOTAL_MASS[resting.config.model], abs=0.01)


def test_imu_at_rest(resting):
    """At rest the IMU reads gravity (+9.8 up, as a real IMU), no rotation, the spawn yaw."""
    imu = resting.robot.imu()
    ax, ay, az = imu.linear_acceleration
    assert az == pytest.approx(9.8, abs=0.05)
    assert math.hypot(ax, ay) < 0.3          # only the slight tilt onto the caster
    assert np.linalg.norm(imu.angular_velocity) < 0.02
    assert kinematics.yaw_from_quat(imu.orientation) == pytest.approx(0.7, abs=0.01)


# --- following commands ------------------------------------------------------------------------

@pytest.mark.parametrize("model", MODEL_NAMES)
def test_drives_straight(make_sim, model):
    """Facing yaw 2.0, 0.2 m/s for 5 s: about 1 m ahead (5 %), < 2 cm sideways, heading kept
    within 0.03 rad; odom twist in the body frame; both wheels turning forward."""
    sim = make_sim(model=model, world="empty", yaw=2.0)
    run(sim, 0.5)
    (x0, y0, _), _ = sim.robot.ground_truth()
    yaw0 = heading(sim)
    sim.robot.command(0.2, 0.0)
    run(sim, 5.0)
    (x, y, _), _ = sim.robot.ground_truth()
    ahead = (x - x0) * math.cos(yaw0) + (y - y0) * math.sin(yaw0)
    aside = -(x - x0) * math.sin(yaw0) + (y - y0) * math.cos(yaw0)
    assert ahead == pytest.approx(1.0, rel=0.05)
    assert abs(aside) < 0.02
    assert abs(kinematics.wrap_angle(heading(sim) - yaw0)) < 0.03
    odom = sim.robot.odom()
    assert odom.linear[0] == pytest.approx(0.2, rel=0.05)
    assert abs(odom.linear[1]) < 0.02
    (left, right), (v_left, v_right) = sim.robot.joint_states()
    assert left > 25 and right > 25           # 1 m / 0.033 m = 30 rad, both positive
    assert v_left == pytest.approx(0.2 / 0.033, rel=0.05)
    assert v_right == pytest.approx(0.2 / 0.033, rel=0.05)


@pytest.mark.parametrize("model", ["burger", "waffle"])
def test_accelerates_at_the_plugin_ramp(make_sim, model):
    """0 -> 0.22 m/s at 1 m/s^2 (Gazebo's wheelAcceleration), without wheel slip: about
    0.1 m/s after 0.1 s, and 0.5*0.22*0.22 + 0.22*0.18 = 0.064 m covered after 0.4 s."""
    sim = make_sim(model=model, world="empty")
    run(sim, 0.5)
    (x0, _, _), _ = sim.robot.ground_truth()
    sim.robot.command(0.22, 0.0)
    run(sim, 0.1)
    assert 0.07 < sim.robot.odom().linear[0] < 0.13
    run(sim, 0.3)
    assert sim.robot.ground_truth()[0][0] - x0 == pytest.approx(0.064, rel=0.1)


@pytest.mark.parametrize("model", MODEL_NAMES)
def test_turns_in_place(make_sim, model):
    """0.5 rad/s for 4 s: about 2 rad (5 %), base_footprint moves < 2 cm."""
    sim = make_sim(model=model, world="empty")
    run(sim, 0.5)
    (x0, y0, _), _ = sim.robot.ground_truth()
    yaw0 = heading(sim)
    sim.robot.command(0.0, 0.5)
    run(sim, 4.0)
    (x, y, _), _ = sim.robot.ground_truth()
    assert kinematics.wrap_angle(heading(sim) - yaw0) == pytest.approx(2.0, rel=0.05)
    assert math.hypot(x - x0, y - y0) < 0.02
    assert sim.robot.odom().angular[2] == pytest.approx(0.5, rel=0.05)


@pytest.mark.parametrize("model", MODEL_NAMES)
def test_commands_are_clamped_to_the_model_limits(make_sim, model):
    """By default 1 m/s and 10 rad/s become the model's top speeds (0.22 / 0.26 m/s ...)."""
    spec = MODELS[model]
    sim = make_sim(model=model, world="empty")
    problems = sim.robot.command(1.0, 0.0)
    assert len(problems) == 1 and "linear.x" in problems[0]
    run(sim, 2.0)
    assert sim.robot.odom().linear[0] == pytest.approx(spec.max_linear, rel=0.05)
    problems = sim.robot.command(0.0, -10.0)
    assert len(problems) == 1 and "angular.z" in problems[0]
    run(sim, 2.0)
    assert sim.robot.odom().angular[2] == pytest.approx(-spec.max_angular, rel=0.05)


def test_no_clamp_when_switched_off(make_sim):
    """clamp_cmd_vel False: 0.5 m/s is driven as it is; 5 m/s is held to SAFE_LINEAR."""
    sim = make_sim(model="burger", world="empty", clamp_cmd_vel=False)
    assert sim.robot.command(0.5, 0.0) == []
    run(sim, 2.0)
    assert sim.robot.odom().linear[0] == pytest.approx(0.5, rel=0.05)
    problems = sim.robot.command(5.0, 0.0)
    assert len(problems) == 1 and "linear.x" in problems[0]
    run(sim, 3.0)
    speed = sim.robot.odom().linear[0]
    assert 1.5 < speed <= SAFE_LINEAR * 1.05
    roll, pitch, _ = rpy(sim)
    assert abs(roll) < 0.2 and abs(pitch) < 0.2


@pytest.mark.parametrize("bad", [(math.nan, 0.0), (0.0, math.inf), (-math.inf, math.nan)])
def test_nan_command_raises_and_is_ignored(make_sim, bad):
    """NaN/inf: ValueError, and the previous command stays in effect."""
    sim = make_sim(model="burger", world="empty")
    sim.robot.command(0.1, 0.0)
    run(sim, 0.5)
    with pytest.raises(ValueError):
        sim.robot.command(*bad)
    (x0, _, _), _ = sim.robot.ground_truth()
    run(sim, 1.0)
    assert sim.robot.ground_truth()[0][0] - x0 == pytest.approx(0.1, rel=0.05)
    assert all(math.isfinite(v) for v in sim.robot.ground_truth()[0])


# --- walls -------------------------------------------------------------------------------------

def assert_inside_arena(sim, upright=True):
    """No part of the robot beyond any inner wall of the hexagon (CONTACT_SLOP allowed); with
    ``upright``, also level on the floor."""
    (x, y, z), _ = sim.robot.ground_truth()
    assert math.hypot(x, y) < ARENA_CIRCUMRADIUS
    points = world_outline(sim)
    for normal in WALL_NORMALS:
        assert deepest(points, normal) <= ARENA_APOTHEM + CONTACT_SLOP, normal
    if upright:
        roll, pitch, _ = rpy(sim)
        assert abs(roll) < 0.2 and abs(pitch) < 0.2
        assert abs(z) < 0.02                  # on the floor, not climbing the wall


@pytest.fixture(scope="module")
def collision_hulls():
    """Collision hull points of the burger and waffle URDFs, in base_footprint."""
    return {m: collision_points(read_urdf(urdf_path(m))) for m in ("burger", "waffle")}


@pytest.mark.parametrize("model, front, rear, half_width", [
    ("burger", 0.038, -0.102, 0.089), ("waffle", 0.073, -0.197, 0.153)])
def test_collision_outline_matches_reference(collision_hulls, model, front, rear, half_width):
    """The hull the wall tests use spans what doc/turtlebot3.md 1.1 gives (wheels: the widest)."""
    points = collision_hulls[model]
    assert points[:, 0].max() == pytest.approx(front, abs=0.002)
    assert points[:, 0].min() == pytest.approx(rear, abs=0.002)
    assert np.abs(points[:, 1]).max() == pytest.approx(half_width, abs=0.002)
    assert points[:, 2].min() == pytest.approx(0.0, abs=0.001)      # wheels touch the floor


@pytest.mark.parametrize("model", ["burger", "waffle"])
def test_stopped_by_the_wall_behind_the_spawn(make_sim, model):
    """Facing -x at full speed for 10 s: ends touching the west-south-west wall, not beyond."""
    sim = make_sim(model=model, world="turtlebot3_world", yaw=math.pi)
    sim.robot.command(1.0, 0.0)                     # clamped to the model's top speed
    run(sim, 10.0)
    assert_inside_arena(sim)
    (x, _, _), _ = sim.robot.ground_truth()
    front = 0.038 if model == "burger" else 0.069
    assert x > -2.644 + front - CONTACT_SLOP
    wall = WALL_NORMALS[3]                    # the flat facing 210 degrees
    assert deepest(world_outline(sim), wall) > ARENA_APOTHEM - 0.01   # touching it


@pytest.mark.parametrize("model", ["burger", "waffle"])
def test_never_through_the_corner(make_sim, model):
    """Top speed for 20 s diagonally into the arena's -x corner: always inside and upright."""
    corner = (-ARENA_CIRCUMRADIUS, 0.0)
    yaw = math.atan2(corner[1] - TB3_SPAWN[1], corner[0] - TB3_SPAWN[0])
    sim = make_sim(model=model, world="turtlebot3_world", yaw=yaw)
    sim.robot.command(1.0, 0.0)                     # clamped to the model's top speed
    farthest = 0.0
    for _ in range(400):
        run(sim, 0.05)
        assert_inside_arena(sim)
        farthest = max(farthest, math.hypot(*sim.robot.ground_truth()[0][:2]))
    assert farthest > ARENA_APOTHEM + 0.2     # it did get into the corner


@pytest.mark.parametrize("model", ["burger", "waffle"])
def test_never_through_the_corner_at_safe_linear(make_sim, model):
    """Unclamped, at SAFE_LINEAR (2 m/s, 9x a burger's top speed), for 20 s into the same
    corner: it may bounce and tumble, but never leaves the arena and never explodes."""
    corner = (-ARENA_CIRCUMRADIUS, 0.0)
    yaw = math.atan2(corner[1] - TB3_SPAWN[1], corner[0] - TB3_SPAWN[0])
    sim = make_sim(model=model, world="turtlebot3_world", yaw=yaw, clamp_cmd_vel=False)
    sim.robot.command(SAFE_LINEAR, 0.0)
    for _ in range(400):
        run(sim, 0.05)
        assert_inside_arena(sim, upright=False)
        assert all(math.isfinite(v) for v in sim.robot.ground_truth()[0])


# --- the laser ---------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def spawn_scans():
    """(gazebo ranges, lds01 ranges) of a burger at the turtlebot3_world spawn."""
    scans = []
    for lidar in ("gazebo", "lds01"):
        sim = Simulation(SimConfig(model="burger", world="turtlebot3_world", lidar_model=lidar))
        try:
            run(sim, 0.2)
            scans.append(sim.robot.scan())
        finally:
            sim.close()
    return tuple(scans)


def test_scan_shape(spawn_scans):
    """360 float32 ranges; nothing too close at the spawn (the robot never sees itself)."""
    gazebo, _ = spawn_scans
    assert gazebo.shape == (360,) and gazebo.dtype == np.float32
    assert not np.any(gazebo == -np.inf)
    valid = gazebo[np.isfinite(gazebo)]
    assert valid.size > 200 and valid.min() > 0.3


def test_wall_behind_the_spawn(spawn_scans):
    """Index 180 (behind) sees the west wall about 0.61 m away."""
    gazebo, _ = spawn_scans
    assert gazebo[180] == pytest.approx(0.612, abs=0.03)


def test_pillar_ahead_left_of_the_spawn(spawn_scans):
    """The pillar at (-1.1, 0), radius 0.15: nearest reading about 0.91 m at about 28 degrees."""
    gazebo, _ = spawn_scans
    scan_x, scan_y = TB3_SPAWN[0] + SCAN_X["burger"], TB3_SPAWN[1]
    dx, dy = -1.1 - scan_x, 0.0 - scan_y
    expected = math.hypot(dx, dy) - 0.15
    bearing = math.degrees(math.atan2(dy, dx))
    sector = gazebo[15:45]
    index = 15 + int(np.argmin(sector))
    assert sector.min() == pytest.approx(expected, abs=0.03)
    assert index * 6.28319 / 359 == pytest.approx(math.radians(bearing), abs=math.radians(3))


def test_no_return_is_inf_in_gazebo_mode_and_zero_in_lds01(spawn_scans):
    """Where Gazebo publishes +inf (nothing within 3.5 m) the LDS-01 mode publishes 0.0."""
    gazebo, lds01 = spawn_scans
    assert np.any(gazebo == np.inf) and not np.any(gazebo == 0.0)
    assert np.all(np.isfinite(lds01)) and np.all(lds01 >= 0.0)
    no_return = np.flatnonzero(gazebo == np.inf)
    zero = np.flatnonzero(lds01 == 0.0)
    assert len(zero) > 0
    # The two modes step 1 degree and 1.0028 degrees: the gaps agree but for their edges.
    assert len(np.setxor1d(no_return, zero)) <= 4
    hit = np.isfinite(gazebo) & (lds01 > 0)
    assert np.median(np.abs(gazebo[hit] - lds01[hit])) < 0.05


# --- odometry ----------------------------------------------------------------------------------

def test_world_odom_starts_at_the_spawn(make_sim):
    """odom_source world (Gazebo's): the odom pose is the world pose, from the spawn."""
    sim = make_sim(model="burger", world="turtlebot3_world", yaw=0.3)
    odom = sim.robot.odom()
    assert odom.position[:2] == pytest.approx(TB3_SPAWN, abs=1e-6)
    assert kinematics.yaw_from_quat(odom.orientation) == pytest.approx(0.3, abs=1e-6)
    run(sim, 0.5)
    odom = sim.robot.odom()
    assert odom.position[:2] == pytest.approx(TB3_SPAWN, abs=0.003)
    assert odom.position == pytest.approx(sim.robot.ground_truth()[0])


def test_encoder_odom_starts_at_zero_and_measures_the_drive(make_sim):
    """odom_source encoders: (0, 0, 0) at the spawn; after driving 1 m it reads about 1 m."""
    sim = make_sim(model="burger", world="turtlebot3_world", odom_source="encoders")
    odom = sim.robot.odom()
    assert odom.position == (0.0, 0.0, 0.0)
    assert kinematics.yaw_from_quat(odom.orientation) == 0.0
    run(sim, 0.5)
    assert sim.robot.odom().position[:2] == pytest.approx((0.0, 0.0), abs=0.003)
    (x0, y0, _), _ = sim.robot.ground_truth()
    sim.robot.command(0.2, 0.0)
    run(sim, 5.0)
    (x1, y1, _), _ = sim.robot.ground_truth()
    odom = sim.robot.odom()
    travelled = math.hypot(x1 - x0, y1 - y0)
    assert odom.position[0] == pytest.approx(1.0, rel=0.05)
    assert odom.position[0] == pytest.approx(travelled, rel=0.05)
    assert abs(odom.position[1]) < 0.02
    assert odom.linear[0] == pytest.approx(0.2, rel=0.05)
    assert x1 < -0.9                          # the world pose is elsewhere: (-1.0, -0.5)


# --- the IMU while moving ----------------------------------------------------------------------

def test_imu_while_turning(make_sim):
    """Turning at 0.5 rad/s, the IMU's angular_velocity z reads about 0.5 rad/s."""
    sim = make_sim(model="burger", world="empty")
    sim.robot.command(0.0, 0.5)
    run(sim, 1.0)
    readings = []
    for _ in range(400):
        if (sim.robot, "imu") in sim.step():
            readings.append(sim.robot.imu().angular_velocity[2])
    assert len(readings) == 200
    assert np.mean(readings) == pytest.approx(0.5, abs=0.05)
    assert min(readings) > 0.3


# --- resets ------------------------------------------------------------------------------------

@pytest.mark.parametrize("odom_source", ["world", "encoders"])
def test_reset_world(make_sim, odom_source):
    """reset_world: robot back at the spawn, stopped, odom as at the start; time runs on."""
    sim = make_sim(model="burger", world="turtlebot3_world", odom_source=odom_source)
    start_odom = sim.robot.odom().position
    sim.robot.command(0.2, 0.5)
    run(sim, 2.0)
    assert math.dist(sim.robot.ground_truth()[0][:2], TB3_SPAWN) > 0.2
    before = sim.time_ns
    sim.reset_world()
    assert sim.time_ns == before
    assert sim.robot.ground_truth()[0][:2] == pytest.approx(TB3_SPAWN, abs=1e-6)
    assert heading(sim) == pytest.approx(0.0, abs=1e-6)
    assert sim.robot.odom().position[:2] == pytest.approx(start_odom[:2], abs=1e-6)
    run(sim, 1.0)                             # the old command is gone, time goes on
    assert sim.time_ns == before + 1_000_000_000
    assert sim.robot.ground_truth()[0][:2] == pytest.approx(TB3_SPAWN, abs=0.005)


def test_reset_simulation(make_sim):
    """reset_simulation: time back to 0, robot at the spawn, every output due again."""
    sim = make_sim(model="burger", world="turtlebot3_world")
    sim.robot.command(0.2, 0.0)
    run(sim, 2.0)
    sim.reset_simulation()
    assert sim.time_ns == 0 and sim.time == 0.0
    assert sim.robot.ground_truth()[0][:2] == pytest.approx(TB3_SPAWN, abs=1e-6)
    assert [name for _, name in sim.step()] == ["clock", "odom", "joint_states", "scan", "imu"]
    assert sim.time_ns == sim.step_ns


# --- what step() reports -----------------------------------------------------------------------

def test_step_reports_outputs_at_their_rates(make_sim):
    """Over 1 s: scan 5, odom and joint_states 30, imu 200, clock 100; 2.5 ms per step."""
    sim = make_sim(model="burger", world="empty")
    assert [name for _, name in sim.step()] == ["clock", "odom", "joint_states", "scan", "imu"]
    assert sim.time_ns == 2_500_000
    counts = run(sim, 1.0)
    assert counts == {"scan": 5, "odom": 30, "joint_states": 30, "imu": 200, "clock": 100}
    assert sim.time_ns == 1_002_500_000
    assert run(sim, 9.0) == {"scan": 45, "odom": 270, "joint_states": 270, "imu": 1800,
                             "clock": 900}


def test_custom_rates(make_sim, tmp_path):
    """Rates from an edited URDF: the diff drive's updateRate 50 Hz (odom), the laser's
    update_rate 10 Hz, with a 5 ms step."""
    text = open(urdf_path("burger")).read()
    assert "<updateRate>30</updateRate>" in text and "<update_rate>5</update_rate>" in text
    edited = tmp_path / "burger.urdf"
    edited.write_text(text.replace("<updateRate>30</updateRate>", "<updateRate>50</updateRate>")
                      .replace("<update_rate>5</update_rate>", "<update_rate>10</update_rate>"))
    sim = make_sim(model="burger", world="empty", time_step=0.005, urdf=str(edited))
    sim.step()
    counts = run(sim, 1.0)
    assert counts["odom"] == 50 and counts["scan"] == 10 and counts["imu"] == 200
    assert sim.time_ns == 1_005_000_000


# --- advance -----------------------------------------------------------------------------------

@pytest.mark.parametrize("time_step", [0.0025, 0.004])
def test_advance_is_step_bit_for_bit(make_sim, time_step):
    """Simulation.advance(n) (no outputs; the learning environments' stepping) gives the same
    physics as n step() calls, bit for bit: the same commands (driving, turning, pushing on a
    wall, braking) in chunks that fall across the drive's 30 Hz ticks give the same pose,
    velocities, wheel states and clock."""
    stepped, advanced = (make_sim(model="burger", world="turtlebot3_stage_1",
                                  time_step=time_step) for _ in range(2))
    plan = [((0.15, 0.0), [1, 7, 80, 13]), ((0.15, 1.5), [40, 3]), ((0.22, 0.0), [4000]),
            ((0.0, 0.0), [5, 120]), ((0.1, 2.0), [2, 2, 61])]
    for (linear, angular), chunks in plan:
        for sim in (stepped, advanced):
            sim.robot.command(linear, angular)
        for n in chunks:
            for _ in range(n):
                stepped.step()
            advanced.advance(n)
            assert advanced.time_ns == stepped.time_ns
            assert advanced.robot.ground_truth() == stepped.robot.ground_truth()
            assert advanced.robot.body.velocity() == stepped.robot.body.velocity()
            assert advanced.robot.joint_states() == stepped.robot.joint_states()
            if n == 4000:   # it drove into the arena's wall and stopped there
                (x, y, _), _ = advanced.robot.ground_truth()
                assert min(advanced.robot.scan()) < 0.13 and math.hypot(x, y) > 1.5
