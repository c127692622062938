"""The learning stages as Gymnasium environments (learning/stage_env) on the real simulator: the
registered ids, Gymnasium's own checker, seeds, goals, collisions and the obstacles. No ROS.
Units: m, rad, s of sim time."""
import importlib
import math
import random

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")   # tools/setup.sh installs it; the error says so

importlib.import_module("tutorial_turtlebot.learning")   # registers the ids
from tutorial_turtlebot.learning import robotis_stages as rs  # noqa: E402
from tutorial_turtlebot.learning.stage_env import StageEnv  # noqa: E402


def steer_to_goal(obs):
    """A scripted policy: the action that turns toward the goal (heading is obs[24])."""
    return int(min(range(5), key=lambda a: abs(obs[24] - (2 - a) * math.pi / 8)))


@pytest.fixture(scope="module")
def stage_1():
    env = gymnasium.make("TurtleBot3Stage1-v0")
    yield env
    env.close()


def test_every_stage_is_registered_with_the_dqn_time_limit():
    for stage in rs.STAGES:
        spec = gymnasium.spec("TurtleBot3Stage%d-v0" % stage)
        assert spec.kwargs == {"stage": stage} and spec.max_episode_steps == 501


def test_gymnasiums_checker_passes():
    from gymnasium.utils.env_checker import check_env
    env = StageEnv(1)
    try:
        check_env(env, skip_render_check=True)
    finally:
        env.close()


def test_spaces_and_the_first_observation(stage_1):
    obs, info = stage_1.reset(seed=0)
    assert stage_1.observation_space.shape == (28,) and stage_1.action_space.n == 5
    assert stage_1.observation_space.contains(obs)
    # the Burger at the origin of the 4 m arena, the first goal (0.6, 0) straight ahead
    assert info["goal"] == (0.6, 0.0) and info["sim_time"] == 0.0
    assert obs[24] == pytest.approx(0.0, abs=0.011) and obs[25] == pytest.approx(0.6, abs=0.011)
    assert np.all((obs[:24] > 1.7) & (obs[:24] < 3.0))   # the walls, 2 m away (2.83 at corners)
    assert obs[26] == obs[27] == 0.0                     # stage 1


def test_a_step_is_one_scan_period_at_015_m_s(stage_1):
    stage_1.reset(seed=0)
    _, reward, terminated, truncated, info = stage_1.step(2)
    assert info["sim_time"] == pytest.approx(rs.STEP_TIME)
    x, y, _ = stage_1.unwrapped._odometry()
    assert 0.01 < x < 0.031 and abs(y) < 0.005          # at most 0.15 m/s for 0.2 s
    assert not terminated and not truncated and reward > 0


def test_the_same_seed_gives_the_same_episode(stage_1):
    def episode(seed):
        obs, _ = stage_1.reset(seed=seed)
        out = [obs]
        for _ in range(20):
            obs, reward, _, _, _ = stage_1.step(steer_to_goal(obs))
            out.append(np.append(obs, reward))
        return out
    first, again, other = episode(5), episode(5), episode(6)
    assert all(np.array_equal(a, b) for a, b in zip(first, again))
    assert not all(np.array_equal(a, b) for a, b in zip(first, other))   # the laser's noise


def test_a_goal_gives_200_and_the_next_goal_and_goes_on(stage_1):
    obs, info = stage_1.reset(seed=1)
    goals = [info["goal"]]
    for _ in range(300):
        obs, reward, terminated, _, info = stage_1.step(steer_to_goal(obs))
        if info["at_goal"]:   # info names the goal reached; the env holds the next
            assert reward == 200 and not terminated and info["goal"] == goals[-1]
            goals.append(stage_1.unwrapped.goal)
            if len(goals) == 3:
                break
        assert not terminated
    assert len(goals) == 3 and goals[0] == (0.6, 0.0)
    replay = rs.GoalSequence(1, random.Random(1))     # reset(seed=1) draws from Random(1)
    assert goals[1:] == [replay.next(), replay.next()]


def test_driving_into_the_wall_ends_the_episode_with_minus_200():
    env = StageEnv(1)
    try:
        env.reset(seed=0)
        for step in range(200):   # straight on, into the wall 2 m ahead (0.03 m a step)
            obs, reward, terminated, _, info = env.step(2)
            if terminated:
                break
        assert terminated and reward == -200 and info["collision"]
        assert 0 < min(obs[:24]) < 0.13
        goal = info["goal"]      # (the first goal, on the way, was reached: this is the next)
        # a reset puts the robot back; the goal stays, as ROBOTIS' clients keep it
        obs, info = env.reset()
        assert info["goal"] == goal and min(obs[:24]) > 1.7 and info["sim_time"] == 0.0
    finally:
        env.close()


def test_stage_3_obstacle_spins_and_stage_4_obstacles_move():
    for stage, name in ((3, "obstacle"), (4, "obstacle_1")):
        env = StageEnv(stage)
        try:
            env.reset(seed=0)
            start = env.world.get_model_state(name)[0]
            for _ in range(10):
                env.step(2)
            pose, twist, _ = env.world.get_model_state(name)
            if stage == 3:
                assert twist[1][2] == pytest.approx(0.5, abs=0.05)
            else:   # 20 ticks of its first leg: (-0.005, -0.012) m a tick
                assert pose[0][0] - start[0][0] == pytest.approx(-0.1, abs=0.01)
                assert pose[0][1] - start[0][1] == pytest.approx(-0.24, abs=0.01)
        finally:
            env.close()


def test_the_pinned_collision_fix_is_an_option():
    env = StageEnv(1, fix_pinned_collision=True)
    try:
        env.reset(seed=0)
        ranges = [1.0] * 24
        ranges[0] = -math.inf
        env.robot.scan = lambda: np.array(ranges)     # a reading closer than range_min
        assert env._observe(0.0, 0.0, 0.0).collision
        env.fix_pinned_collision = False
        assert not env._observe(0.0, 0.0, 0.0).collision
    finally:
        env.close()


def test_refusals():
    with pytest.raises(ValueError, match="stage 5"):
        StageEnv(5)
    env = StageEnv(1)
    try:
        env.reset()
        with pytest.raises(ValueError, match="action 7"):
            env.step(7)
    finally:
        env.close()
