"""ROBOTIS' ROS 2 stages (learning/robotis_stages_ros2) on numbers worked out by hand from
turtlebot3_machine_learning's ROS 2 code (dqn_environment.py, dqn_gazebo.py) and
turtlebot3_gazebo's humble animations; then StageEnv(variant="ros2") on the simulator and its
registered ids. No ROS. Units: m, rad, s of sim time."""
import math
import os
import random

import numpy as np
import pytest

from tutorial_turtlebot.learning import robotis_stages as rs
from tutorial_turtlebot.learning import robotis_stages_ros2 as r2
from tutorial_turtlebot.sim.files.sdf.world_catalogue import WORLD_DIR
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world


def f32(value):
    return float(np.float32(value))


def yaw_of(quaternion):
    x, y, z, w = quaternion
    assert x == y == 0.0
    return 2 * math.atan2(z, w) % (2 * math.pi)


# --- the definitions ----------------------------------------------------------------------------

def test_the_ros2_numbers():
    assert r2.OBSERVATION_SIZE == 26 and r2.SCAN_SAMPLES == 48 and r2.ACTIONS == 5
    assert (r2.COLLISION_RANGE, r2.GOAL_RANGE, r2.OBSTACLE_NEAR) == (0.15, 0.20, 0.5)
    assert (r2.GOAL_REWARD, r2.FAIL_REWARD) == (100.0, -50.0)
    assert (r2.MAX_STEP, r2.MAX_EPISODE_STEPS) == (800, 799)
    assert r2.FIRST_GOAL == (0.5, 0.0) and r2.SPAWN == (0.0, 0.0, 0.0)
    assert len(r2.STAGE_4_GOALS) == 12 and r2.STAGE_4_GOALS[5] == (-1.5, 2.1)


def test_actions_drive_at_02_m_s_and_turn_as_in_noetic():
    assert [r2.action_command(a) for a in range(5)] == [
        (0.2, 1.5), (0.2, 0.75), (0.2, 0.0), (0.2, -0.75), (0.2, -1.5)]


def test_the_state_takes_the_front_half_of_48_rays():
    angles = r2.scan_angles()
    assert len(angles) == 48 and angles[0] == 0.0 and angles[47] == pytest.approx(6.28)
    assert angles[1] == pytest.approx(6.28 / 47)
    # 11 * 0.13362 = 1.4698 <= pi/2 < 12 * 0.13362; 35 * 0.13362 = 4.677 < 3pi/2 <= 36 * ...
    assert [i for i, a in enumerate(angles) if r2.is_front(a)] == (
        list(range(0, 12)) + list(range(36, 48)))


def test_distance_and_angle_are_unrounded():
    assert r2.goal_distance((3.0, 4.0), 0.0, 0.0) == 5.0
    assert r2.goal_distance((0.123, 0.0), 0.0, 0.0) == 0.123          # noetic: 0.12
    assert rs.goal_bearing((0.0, 1.0), 0.0, 0.0, 0.0) == math.pi / 2   # noetic: 1.57
    # facing yaw 3.0 with the goal at (-1, -0.1): atan2 = -3.0419240, less 3.0, plus 2 pi
    assert rs.goal_bearing((-1.0, -0.1), 0.0, 0.0, 3.0) == pytest.approx(0.2412613, abs=1e-7)


def test_observation_order_and_nearest():
    ranges = [1.0] * 48
    ranges[5] = math.inf       # ahead-left: 3.5
    ranges[20] = 0.3           # behind: not in the state, but the nearest
    ranges[40] = 0.6           # ahead-right: the 17th front range
    obs = r2.observation(ranges, r2.scan_angles(), 1.25, -0.5)
    assert len(obs.values) == 26 and obs.values[:2] == [1.25, -0.5]
    assert obs.values[2 + 5] == 3.5 and obs.values[2 + 12 + (40 - 36)] == 0.6
    assert 0.3 not in obs.values and obs.nearest == 0.3
    assert obs.front_angles[12] == pytest.approx(36 * 6.28 / 47)


def test_collision_is_any_range_under_015():
    def nearest(value):
        ranges = [2.0] * 48
        ranges[30] = value        # behind: every ray counts
        return r2.observation(ranges, r2.scan_angles(), 1.0, 0.0).nearest

    book = r2.EpisodeBook()
    assert book.record(1.0, nearest(0.149)).collided
    assert not book.record(1.0, nearest(0.15)).collided
    assert book.record(1.0, nearest(-math.inf)).collided      # closer than range_min (noetic: no)
    assert book.record(1.0, nearest(math.nan)).collided       # NaN reads 0 (noetic: no)


def test_yaw_reward_is_linear_in_the_angle():
    assert r2.yaw_reward(0.0) == 1.0
    assert r2.yaw_reward(math.pi / 4) == 0.5 and r2.yaw_reward(-math.pi / 4) == 0.5
    assert r2.yaw_reward(math.pi / 2) == 0.0 and r2.yaw_reward(-math.pi) == -1.0


def test_obstacle_reward_by_hand():
    assert r2.obstacle_reward([0.51, 3.5], [0.0, 0.3]) == 0.0          # none within 0.5 m
    # one range ahead at 0.3 m: exp(-3 * (0.3 - 0.25)) = 0.86070798; -(1 + 4 * 0.86070798)
    assert r2.obstacle_reward([0.3], [0.0]) == pytest.approx(-4.44283190, abs=1e-8)
    # under 0.26 m (and a -inf) the distance is clipped to 0.01: -(1 + 4 * 0.97044553)
    assert r2.obstacle_reward([0.2], [6.28]) == pytest.approx(-4.88178213, abs=1e-8)
    assert r2.obstacle_reward([-math.inf], [0.0]) == pytest.approx(-4.88178213, abs=1e-8)
    # ahead at 0.25 (decay 0.97044553, weight cos(0)^6 + 0.1 = 1.1) and left at 0.5
    # (decay exp(-0.75) = 0.47236655, weight 0.1): (1.06749008 + 0.04723666) / 1.2
    # = 0.92893895; -(1 + 4 * 0.92893895)
    assert (r2.obstacle_reward([0.25, 0.5], [0.0, math.pi / 2])
            == pytest.approx(-4.71575580, abs=1e-8))
    # ahead at 0.4 (decay exp(-0.45) = 0.63762815, weight 1.1) and 45 degrees right at 0.3
    # (decay 0.86070798, weight cos(pi/4)^6 + 0.1 = 0.225): (0.70139097 + 0.19365929) / 1.325
    # = 0.67550963; -(1 + 4 * 0.67550963)
    assert r2.obstacle_reward([0.4, 0.3], [0.0, 7 * math.pi / 4]) == pytest.approx(
        -3.70203853, abs=1e-8)
    # a ray at 2 pi - a weighs as one at a (its angle from ahead is -a); farther ones count not
    assert r2.obstacle_reward([0.3, 0.4], [0.0, 2 * math.pi - 0.3]) == pytest.approx(
        r2.obstacle_reward([0.3, 0.4, 0.7], [0.0, 0.3, 0.1]), abs=1e-12)


def test_reward_goal_before_failure_and_as_a_float32():
    obs = r2.observation([1.0] * 48, r2.scan_angles(), 1.0, 0.1)
    shaped = 1 - 0.2 / math.pi        # nothing within 0.5 m
    assert r2.reward(0.1, obs, False, False) == pytest.approx(shaped, abs=1e-15)
    assert r2.reward(0.1, obs, True, True) == 100.0
    assert r2.reward(0.1, obs, False, True) == -50.0
    book = r2.EpisodeBook()
    assert book.reward(0.1, obs) == f32(shaped) != shaped   # Dqn.srv's reward is a float32


def test_an_episode_is_800_states_the_resets_included():
    book = r2.EpisodeBook()
    outcomes = [book.record(1.0, 1.0) for _ in range(800)]   # a reset's state, then 799 steps
    assert not any(o.timed_out for o in outcomes[:-1])
    assert outcomes[-1] == r2.Outcome(False, False, True) and outcomes[-1].failed
    assert book.reward(0.0, None) == -50.0 and book.end_step() and not book.done
    assert book.states == 0


def test_goal_and_collision_set_the_count_back():
    book = r2.EpisodeBook()
    for _ in range(500):
        book.record(1.0, 1.0)
    outcome = book.record(0.19, 0.1)            # both at once: both tasks run, the goal pays
    assert outcome.reached and outcome.collided and not outcome.timed_out
    assert book.states == 0 and book.reward(0.0, None) == 100.0
    assert book.end_step() and not book.end_step()


def test_a_goal_met_by_a_resets_state_ends_the_next_step():
    book = r2.EpisodeBook()
    assert book.record(0.1, 1.0).reached        # the reset's state: no step clears the flags
    assert not book.record(1.0, 1.0).reached    # the next step finds nothing new ...
    assert book.reward(0.0, None) == 100.0 and book.end_step()   # ... and still ends
    assert book.states == 1                     # (nothing set the count back)


def test_goals_are_drawn_as_dqn_gazebo_draws_them():
    goals = r2.GoalSequence(1, random.Random(7))
    assert goals.first() == (0.5, 0.0)
    drawn = [goals.next() for _ in range(300)]
    rng = random.Random(7)                      # x then y, each randrange(-21, 21) / 10
    expected = []
    for _ in range(300):
        x = rng.randrange(-21, 21) / 10
        expected.append((f32(x), f32(rng.randrange(-21, 21) / 10)))
    assert drawn == expected
    xs = {x for x, _ in drawn}
    assert min(xs) == f32(-2.1) and max(xs) == f32(2.0) and len(xs) == 42
    # no test against the pillars at (+-1, +-1), r 0.15 m: some goals lie in one
    drawn += [goals.next() for _ in range(1000)]
    assert any(math.hypot(abs(x) - 1, abs(y) - 1) < 0.15 for x, y in drawn)
    stage_4 = r2.GoalSequence(4, random.Random(7))
    assert stage_4.first() == (0.5, 0.0)
    drawn = [stage_4.next() for _ in range(200)]
    rng = random.Random(7)
    assert drawn == [tuple(map(f32, r2.STAGE_4_GOALS[rng.randint(0, 11)])) for _ in range(200)]
    assert any(a == b for a, b in zip(drawn, drawn[1:]))   # the same goal may come again


def test_stage_3_turns_once_in_40_s_as_gazebo_squads():
    (pillars,) = r2.obstacles(3)
    assert pillars.name == "turtlebot3_dqn_obstacles"
    assert pillars.pose_at(0.0) == ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
    assert yaw_of(pillars.pose_at(20.0)[1]) == pytest.approx(math.pi, abs=1e-12)
    assert yaw_of(pillars.pose_at(40.0)[1]) == pytest.approx(0.0, abs=1e-12)
    # squad with Shoemake's tangents (the ends open): yaw(u) = pi u - pi u (1 - u)^2 / 2 over
    # 0..20 s, pi + pi u + pi u^2 (1 - u) / 2 over 20..40 s; at u = 0.5: 7 pi / 16, 25 pi / 16
    assert yaw_of(pillars.pose_at(10.0)[1]) == pytest.approx(7 * math.pi / 16, abs=1e-12)
    assert yaw_of(pillars.pose_at(30.0)[1]) == pytest.approx(25 * math.pi / 16, abs=1e-12)
    assert yaw_of(pillars.pose_at(55.0)[1]) == pytest.approx(
        math.pi * 0.75 - math.pi * 0.75 * 0.25 ** 2 / 2, abs=1e-12)   # 15 s into the loop
    for _ in range(100):                        # 100 ticks of 0.1 s
        pose, twist = pillars.tick(None)
    assert pose == pillars.pose_at(10.0) and twist == ((0.0,) * 3, (0.0,) * 3)


def test_stage_4_pillars_follow_gazebos_hermite_spline():
    first, second = r2.obstacles(4)
    assert (first.name, second.name) == ("turtlebot3_dqn_obstacle1", "turtlebot3_dqn_obstacle2")
    assert first.pose_at(10.0)[0] == (-0.5, -1.0, 0.0)
    assert first.pose_at(70.0)[0] == (-3.7, -3.0, 0.0)
    assert first.pose_at(160.0)[0] == (0.0, 0.0, 0.0)     # the loop starts over
    assert first.pose_at(55.0)[1] == (0.0, 0.0, 0.0, 1.0)   # no turning
    # 0..10 s, s = 0.5: the ends (0, 0), (-0.5, -1); tangents (closed loop, Catmull-Rom)
    # 0.5 * ((-0.5, -1) - (0, 0)) and 0.5 * ((-3.5, -1) - (0, 0)):
    # 0.5 p0 + 0.5 p1 + 0.125 t0 - 0.125 t1 = (-0.0625, -0.5)
    assert first.pose_at(5.0)[0] == pytest.approx((-0.0625, -0.5, 0.0), abs=1e-12)
    # 140..160 s, both ends (0, 0): tangents (0.25, 0.5) and the first one's (-0.25, -0.5)
    assert first.pose_at(150.0)[0] == pytest.approx((0.0625, 0.125, 0.0), abs=1e-12)
    # the second: 0..10 s to (0.7, 0.2), tangents (0.35, 0.1) and 0.5 * (2.5, 3.5)
    assert second.pose_at(5.0)[0] == pytest.approx((0.2375, -0.10625, 0.0), abs=1e-12)
    assert second.pose_at(140.0 + 85.0)[0] == pytest.approx((3.5, 1.8, 0.0), abs=1e-12)
    assert r2.obstacles(1) == [] and r2.obstacles(2) == []


@pytest.mark.parametrize("stage", r2.STAGES)
def test_worlds_have_robotis_ros2_geometry(stage):
    world = load_world(os.path.join(WORLD_DIR, r2.world_file(stage)))
    walls = [s for s in world.collisions if s.name.startswith("turtlebot3_dqn_world::")]
    assert sorted((round(abs(s.pose[0]), 3), round(abs(s.pose[1]), 3)) for s in walls) == [
        (0.0, 2.425), (0.0, 2.425), (2.425, 0.0), (2.425, 0.0)]
    assert all(s.kind == "box" and s.size == (5.0, 0.15, 0.5) for s in walls)
    pillars = [s for s in world.collisions if s.kind == "cylinder"]
    if stage in (2, 3):
        assert sorted((s.pose[0], s.pose[1]) for s in pillars) == [
            (-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0)]
        assert all(s.size == (0.15, 0.5) and s.pose[2] == 0.25 for s in pillars)
    elif stage == 4:
        assert sorted(s.pose[:3] for s in pillars) == [(-2.0, -2.0, 0.0), (2.0, 2.0, 0.0)]
        assert all(s.size == (0.12, 0.25) for s in pillars)   # under the laser (0.18 m up)
        inner = [s for s in world.collisions if s.name.startswith("inner_walls::")]
        assert len(inner) == 7 and all(s.size == (1.0, 0.15, 0.5) for s in inner)
    else:
        assert pillars == []
    movers = {m.name for m in r2.obstacles(stage)}
    assert movers <= set(world.models)


# --- the environment ----------------------------------------------------------------------------

gymnasium = pytest.importorskip("gymnasium")


def make_env(stage=1):
    from tutorial_turtlebot.learning.stage_env import StageEnv
    return StageEnv(stage, variant="ros2")


@pytest.fixture(scope="module")
def stage_1():
    env = make_env(1)
    yield env
    env.close()


def test_every_stage_is_registered_with_799_steps():
    import tutorial_turtlebot.learning as learning
    assert learning.ROS2_ENV_IDS == tuple("TurtleBot3Stage%dRos2-v0" % s for s in r2.STAGES)
    for stage, env_id in zip(r2.STAGES, learning.ROS2_ENV_IDS):
        assert gymnasium.spec(env_id).kwargs == {"stage": stage, "variant": "ros2"}
        env = gymnasium.make(env_id)
        try:
            assert env.spec.max_episode_steps == 799 and env.unwrapped.variant == "ros2"
            assert env.observation_space.shape == (26,) and env.unwrapped.stage == stage
        finally:
            env.close()
    assert gymnasium.spec("TurtleBot3Stage1-v0").max_episode_steps == 501   # noetic as it was


@pytest.mark.parametrize("stage", r2.STAGES)
def test_gymnasiums_checker_passes(stage):
    from gymnasium.utils.env_checker import check_env
    env = make_env(stage)
    try:
        check_env(env.unwrapped, skip_render_check=True)
    finally:
        env.close()


def test_space_and_the_first_state(stage_1):
    space = stage_1.observation_space
    assert space.shape == (26,) and space.low[1] == np.float32(-math.pi)
    assert space.high[0] == np.float32(5 * math.sqrt(2)) and space.high[2] == np.float32(3.5)
    obs, info = stage_1.reset(seed=0)
    assert space.contains(obs) and info["goal"] == (0.5, 0.0) and info["sim_time"] == 0.0
    assert obs[0] == pytest.approx(0.5, abs=1e-3) and obs[1] == pytest.approx(0.0, abs=1e-3)
    assert np.all((obs[2:] > 2.2) & (obs[2:] < 3.4))   # the walls, 2.35 m from the centre


def test_a_step_gives_the_state_its_action_found_then_holds_it_02_s(stage_1):
    first, _ = stage_1.reset(seed=0)
    obs, reward, terminated, truncated, info = stage_1.step(2)
    assert np.array_equal(obs, first) and info["sim_time"] == 0.0   # read before it acts
    assert reward == pytest.approx(1 - 2 * abs(float(first[1])) / math.pi, abs=1e-7)
    assert not terminated
    obs, _, _, _, info = stage_1.step(2)
    assert info["sim_time"] == pytest.approx(0.2)
    assert 0.5 - 0.04 < obs[0] < 0.5 - 0.01               # at most 0.2 m/s for 0.2 s


def test_a_goal_ends_the_episode_with_100_and_the_robot_stays(stage_1):
    stage_1.reset(seed=0)
    for _ in range(40):
        obs, reward, terminated, _, info = stage_1.step(2)
        if terminated:
            break
    assert terminated and reward == 100.0 and info["at_goal"] and obs[0] < 0.2
    x, _, _ = stage_1.unwrapped._odometry()
    obs, info = stage_1.reset()
    rng = random.Random(0)
    goal = tuple(f32(rng.randrange(-21, 21) / 10) for _ in range(2))
    assert info["goal"] == goal and info["sim_time"] > 1.0        # no world reset
    assert stage_1.unwrapped._odometry()[0] == x > 0.3
    assert obs[0] == pytest.approx(math.hypot(goal[0] - x, goal[1]), abs=0.02)


def test_a_collision_ends_with_minus_50_and_resets_the_world(stage_1):
    stage_1.reset(seed=0)
    stage_1.unwrapped.goal = (-2.0, 0.0)        # behind the robot, out of its way
    for _ in range(100):                        # straight into the wall 2.35 m ahead
        _, reward, terminated, _, info = stage_1.step(2)
        if terminated:
            break
    assert terminated and reward == -50.0 and info["collision"] and info["sim_time"] > 9.0
    obs, info = stage_1.reset()
    assert info["sim_time"] == 0.0
    assert stage_1.unwrapped._odometry()[:2] == pytest.approx((0.0, 0.0), abs=1e-6)
    goal = info["goal"]
    assert obs[0] == pytest.approx(math.hypot(*goal), abs=1e-3)


def test_the_time_limit_is_the_799th_step_minus_50():
    env = gymnasium.make("TurtleBot3Stage1Ros2-v0")
    try:
        env.reset(seed=0)
        for step in range(1, 800):   # a tight circle (radius 0.13 m) that meets nothing
            _, reward, terminated, truncated, info = env.step(0)
            if terminated or truncated:
                break
        assert step == 799 and reward == -50.0 and info["timeout"]
        assert terminated and truncated          # ROBOTIS ends it; the TimeLimit agrees
        _, info = env.reset()
        assert info["sim_time"] == 0.0           # a failure: the world was reset
    finally:
        env.close()


def test_stage_3_and_4_obstacles_follow_their_animations():
    for stage in (3, 4):
        env = make_env(stage)
        try:
            env.reset(seed=1)
            for _ in range(10):
                env.step(1)
            time = env.sim.time
            assert time == pytest.approx(2.0)
            for mover in r2.obstacles(stage):
                pose, _, _ = env.world.get_model_state(mover.name)
                expected = mover.pose_at(round(time / 0.1) * 0.1)
                assert pose[0] == pytest.approx(expected[0], abs=1e-9)
                assert pose[1] == pytest.approx(expected[1], abs=1e-9)
                assert expected != mover.pose_at(0.0)      # they moved
        finally:
            env.close()


def test_refusals():
    from tutorial_turtlebot.learning.stage_env import StageEnv
    with pytest.raises(ValueError, match="variant 'ros1'"):
        StageEnv(1, variant="ros1")
