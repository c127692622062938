"""ROBOTIS' stage semantics (learning/robotis_stages) on hand-made numbers: the observation, the
reward, the goal draws and the obstacle nodes. No simulator, no ROS. Units: m, rad."""
import math
import random

import pytest

from tutorial_turtlebot.learning import robotis_stages as rs


def test_actions_turn_from_left_to_right_at_015_m_s():
    assert [rs.action_command(a) for a in range(5)] == [
        (0.15, 1.5), (0.15, 0.75), (0.15, 0.0), (0.15, -0.75), (0.15, -1.5)]


def test_heading_wraps_and_rounds():
    assert rs.heading_to((1.0, 0.0), 0.0, 0.0, 0.0) == 0.0
    assert rs.heading_to((0.0, 1.0), 0.0, 0.0, 0.0) == 1.57
    # goal behind on the left while facing -170 degrees: the angle wraps into -pi..pi
    heading = rs.heading_to((-1.0, 0.1), 0.0, 0.0, math.radians(-170))
    assert -math.pi <= heading <= math.pi and heading == round(heading, 2)
    assert rs.goal_distance((3.0, 4.0), 0.0, 0.0) == 5.0
    assert rs.goal_distance((0.123, 0.0), 0.0, 0.0) == 0.12


def test_observation_maps_inf_and_nan_and_keeps_minus_inf():
    ranges = [1.0] * 24
    ranges[3], ranges[5], ranges[7] = math.inf, math.nan, 0.5
    obs = rs.observation(2, ranges, 0.3, 1.2)
    assert obs.values[3] == 3.5 and obs.values[5] == 0.0
    assert obs.values[24:] == [0.3, 1.2, 0.0, 5.0]    # the NaN's 0 is the nearest, at 5
    assert not obs.collision                          # 0 is not > 0
    stage_1 = rs.observation(1, ranges, 0.3, 1.2)
    assert stage_1.values[24:] == [0.3, 1.2, 0.0, 0.0] and len(stage_1.values) == 28
    ranges[7] = 0.1
    ranges[5] = 1.0
    assert rs.observation(1, ranges, 0.0, 1.0).collision      # 0 < 0.1 < 0.13
    ranges[7] = -math.inf                                    # closer than range_min
    assert not rs.observation(1, ranges, 0.0, 1.0).collision  # ROBOTIS' test misses it
    assert rs.observation(1, [1.0] * 24, 0.0, 0.19).at_goal
    assert not rs.observation(1, [1.0] * 24, 0.0, 0.2).at_goal


def test_yaw_reward_is_1_towards_the_goal():
    # heading 0: the middle action (straight on) scores 1, the hardest turns score less
    rewards = [rs.yaw_reward(0.0, a) for a in range(5)]
    assert rewards[2] == pytest.approx(1.0)
    assert rewards[0] == pytest.approx(rewards[4]) and rewards[0] < rewards[1] < 1.0
    # the goal pi/8 to the left: turning left (action 1) scores best; pi/4: the hardest left
    assert max(range(5), key=lambda a: rs.yaw_reward(math.pi / 8, a)) == 1
    assert max(range(5), key=lambda a: rs.yaw_reward(math.pi / 4, a)) == 0


def test_reward_scales_with_distance_and_ends():
    values = [1.0] * 24 + [0.0, 1.0, 1.0, 0.0]
    base = round(rs.yaw_reward(0.0, 2) * 5, 2)
    assert rs.reward(1, values, 2, 1.0, False, False) == pytest.approx(base * 2.0)
    assert rs.reward(1, values, 2, 2.0, False, False) == pytest.approx(base * 2 ** 0.5)
    assert rs.reward(1, values, 2, 1.0, True, False) == -200
    assert rs.reward(3, values, 2, 1.0, True, False) == -150
    assert rs.reward(4, values, 2, 1.0, True, True) == 1000     # the goal wins
    near = values[:-2] + [0.4, 3.0]
    assert rs.reward(4, near, 2, 1.0, False, False) == pytest.approx(base * 2.0 - 5)
    assert rs.reward(2, near, 2, 1.0, False, False) == pytest.approx(base * 2.0)


def test_goals_are_drawn_as_respawngoal_draws_them():
    goals = rs.GoalSequence(1, random.Random(7))
    assert goals.first() == (0.6, 0.0)
    drawn = [goals.next() for _ in range(50)]
    last = (0.6, 0.0)
    for x, y in drawn:
        assert -1.2 <= x <= 1.2 and -1.2 <= y <= 1.2
        assert x == round(x, 1) and y == round(y, 1)
        assert not any(abs(x - px) <= 0.4 and abs(y - py) <= 0.4 for px, py in rs.PILLARS)
        assert not (abs(x - last[0]) < 1 and abs(y - last[1]) < 1)
        last = (x, y)
    # the same seed, the same goals; the draws are random.randrange's
    again = rs.GoalSequence(1, random.Random(7))
    assert [again.next() for _ in range(50)] == drawn
    stage_4 = rs.GoalSequence(4, random.Random(3))
    picks = [stage_4.next() for _ in range(30)]
    assert all(p in rs.STAGE_4_GOALS for p in picks)
    assert all(a != b for a, b in zip(picks, picks[1:]))


def test_obstacle_nodes():
    pose = ((0.1, 0.2, 0.25), (0.0, 0.0, 0.0, 1.0))
    assert rs.SpinningObstacle().tick(pose) == (pose, ((0, 0, 0), (0, 0, 0.5)))
    mover = rs.WaypointObstacle("obstacle_1")
    at = ((2.0, 2.0, 0.25), (0.0, 0.0, 0.0, 1.0))
    visited = {0}
    for _ in range(5000):
        at, twist = mover.tick(at)
        visited.add(mover.leg)
        assert twist == ((0, 0, 0), (0, 0, 0))
        assert -2.5 < at[0][0] < 2.5 and -2.5 < at[0][1] < 2.5   # it stays in the plaza
    assert visited == set(range(len(rs.WAYPOINTS["obstacle_1"][1])))   # every leg, in a loop
    assert [type(m).__name__ for m in rs.obstacles(3)] == ["SpinningObstacle"]
    assert [m.name for m in rs.obstacles(4)] == ["obstacle_1", "obstacle_2"]
    assert rs.obstacles(1) == rs.obstacles(2) == []
