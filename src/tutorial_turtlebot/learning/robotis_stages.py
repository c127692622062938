"""What ROBOTIS' turtlebot3_machine_learning (ROS 1, noetic) does in its four DQN stages, as plain
functions and data: no ROS, no Gymnasium, no simulator (doc/learning.md).

- ``observation``: the 28 values of ``environment_stage_N.getState``: the scan (+inf as 3.5,
  NaN as 0), the heading to the goal and its distance (both rounded to 0.01), then ``0, 0``
  in stage 1 or the nearest range (rounded) and its index in stages 2 to 4; and whether that
  scan is a collision (0 < nearest < 0.13 m: a -inf below the laser's range_min is none).
- ``reward``: ``setReward``'s yaw-and-distance reward, the stage's collision and goal values.
- ``GoalSequence``: ``respawnGoal.getPosition``: the goals, from a ``random.Random``.
- ``SpinningObstacle``, ``WaypointObstacle``: what ``moving_obstacle.py`` (stage 3) and
  ``combination_obstacle_1/2.py`` (stage 4) do to the obstacles at each of their ticks.

It follows github.com/ROBOTIS-GIT/turtlebot3_machine_learning, branch ``noetic`` at commit
5df6e0a4fbf326b0d4bf9838701090522413844c (turtlebot3_dqn/src/turtlebot3_dqn/ and nodes/). The
ROS 2 stages (branches ``main``, ``humble`` and ``jazzy``, one tree, at
3bce927fc2161b3df4568c6a170502dd45aff7e3) are in robotis_stages_ros2.py.

Units: metres, radians (heading counter-clockwise from the robot's +x to the goal), m/s.
"""
import math
import random
from typing import List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

STAGES = (1, 2, 3, 4)
SCAN_SAMPLES = 24           # the LDS-01's samples in ROBOTIS' learning set-up
OBSERVATION_SIZE = SCAN_SAMPLES + 4
ACTIONS = 5
LINEAR_SPEED = 0.15         # m/s of every action
MAX_ANGULAR = 1.5           # rad/s: action a turns at ((ACTIONS - 1) / 2 - a) * MAX_ANGULAR / 2
STEP_TIME = 0.2             # s of sim time an environment step lasts: the next scan (5 Hz)
MAX_EPISODE_STEPS = 501     # turtlebot3_dqn ends an episode once its step index reaches 500
NO_RETURN = 3.5             # what a +inf range reads as
COLLISION_RANGE = 0.13      # m
GOAL_RANGE = 0.2            # m
OBSTACLE_NEAR = 0.5         # m: stage 4's obstacle penalty below this
# (collision reward, goal reward) per stage
END_REWARDS = {1: (-200.0, 200.0), 2: (-150.0, 200.0), 3: (-150.0, 200.0), 4: (-500.0, 1000.0)}
FIRST_GOAL = (0.6, 0.0)     # m: the goal of the first episode in every stage
# stages 1-3: a new goal is not within 0.4 m (on x and y) of these, nor within 1 m of the last
PILLARS = ((0.6, 0.6), (0.6, -0.6), (-0.6, 0.6), (-0.6, -0.6), (0.0, 0.0))
# stage 4: the goals it draws from
STAGE_4_GOALS = ((0.6, 0.0), (1.9, -0.5), (0.5, -1.9), (0.2, 1.5), (-0.8, -0.9), (-1.0, 1.0),
                 (-1.9, 1.1), (0.5, -1.5), (2.0, 1.5), (0.5, 1.8), (0.0, -1.0), (-0.1, 1.6),
                 (-2.0, -0.8))
OBSTACLE_TICK = 0.1         # s between two moves of an obstacle node (it sleeps 0.1 s)


def action_command(action: int) -> Tuple[float, float]:
    """(linear m/s, angular rad/s) of discrete ``action`` 0..4 (0 turns left fastest)."""
    return LINEAR_SPEED, ((ACTIONS - 1) / 2 - action) * MAX_ANGULAR * 0.5


def goal_bearing(goal: Sequence[float], x: float, y: float, yaw: float) -> float:
    """The angle (rad, -pi..pi, unrounded) from the robot's heading (``yaw``) to the goal:
    the bearing less the yaw, wrapped once (both ROBOTIS versions wrap it so)."""
    heading = math.atan2(goal[1] - y, goal[0] - x) - yaw
    if heading > math.pi:
        heading -= 2 * math.pi
    elif heading < -math.pi:
        heading += 2 * math.pi
    return heading


def heading_to(goal: Sequence[float], x: float, y: float, yaw: float) -> float:
    """The angle (rad, -pi..pi, rounded to 0.01) from the robot's heading to the goal."""
    return round(goal_bearing(goal, x, y, yaw), 2)


def goal_distance(goal: Sequence[float], x: float, y: float) -> float:
    """The distance (m, rounded to 0.01) from the robot to the goal."""
    return round(math.hypot(goal[0] - x, goal[1] - y), 2)


class Observation(NamedTuple):
    values: List[float]      # the 28 values
    collision: bool
    at_goal: bool


def scan_values(ranges: Sequence[float]) -> List[float]:
    """A scan's ranges (m) as both ROBOTIS versions read them: +inf as 3.5, NaN as 0, a -inf
    (closer than range_min) kept."""
    return [NO_RETURN if r == math.inf else 0.0 if math.isnan(r) else float(r) for r in ranges]


def observation(stage: int, ranges: Sequence[float], heading: float,
                distance: float) -> Observation:
    """getState of ``stage`` for a scan's ``ranges`` and the rounded heading and distance."""
    scan = scan_values(ranges)
    nearest = min(scan)
    collision = COLLISION_RANGE > nearest > 0
    if stage == 1:
        tail = [0.0, 0.0]
    else:
        tail = [round(nearest, 2), float(int(np.argmin(scan)))]
    return Observation(scan + [heading, distance] + tail, collision, distance < GOAL_RANGE)


def yaw_reward(heading: float, action: int) -> float:
    """setReward's reward for turning ``action`` with the goal at ``heading`` (1 straight at
    it, falling to -1 away from it)."""
    angle = -math.pi / 4 + heading + (math.pi / 8 * action) + math.pi / 2
    return 1 - 4 * math.fabs(0.5 - math.modf(0.25 + 0.5 * angle % (2 * math.pi) / math.pi)[0])


def reward(stage: int, values: Sequence[float], action: int, start_distance: float,
           collision: bool, at_goal: bool) -> float:
    """setReward of ``stage``: the yaw reward scaled by 2^(distance / the goal's distance at
    its start), minus 5 in stage 4 near an obstacle; a collision's or a goal's value instead
    (the goal's when both)."""
    heading, distance = values[-4], values[-3]
    value = round(yaw_reward(heading, action) * 5, 2) * 2 ** (distance / start_distance)
    if stage == 4 and values[-2] < OBSTACLE_NEAR:
        value += -5
    if collision:
        value = END_REWARDS[stage][0]
    if at_goal:
        value = END_REWARDS[stage][1]
    return value


class GoalSequence:
    """The goals of respawnGoal.getPosition: FIRST_GOAL, then each new one drawn from ``rng``
    exactly as it draws them (random.randrange), so that the same seed gives the same goals."""

    def __init__(self, stage: int, rng: Optional[random.Random] = None):
        self.stage = stage
        self.rng = rng if rng is not None else random.Random()
        self.last = FIRST_GOAL
        self.last_index = 0

    def first(self) -> Tuple[float, float]:
        return FIRST_GOAL

    def next(self) -> Tuple[float, float]:
        """The next goal (m, world frame) after one was reached."""
        if self.stage != 4:
            while True:
                x = self.rng.randrange(-12, 13) / 10.0
                y = self.rng.randrange(-12, 13) / 10.0
                near_pillar = any(abs(x - px) <= 0.4 and abs(y - py) <= 0.4 for px, py in PILLARS)
                near_last = abs(x - self.last[0]) < 1 and abs(y - self.last[1]) < 1
                if not near_pillar and not near_last:
                    break
            goal = (x, y)
        else:
            while True:
                index = self.rng.randrange(0, len(STAGE_4_GOALS))
                if index != self.last_index:
                    self.last_index = index
                    break
            goal = STAGE_4_GOALS[index]
        self.last = goal
        return goal


class SpinningObstacle:
    """Stage 3's moving_obstacle.py: at each tick, model ``obstacle`` keeps its pose and gets a
    twist of 0.5 rad/s about z."""

    name = "obstacle"
    angular = 0.5   # rad/s

    def tick(self, pose):
        """(pose, (linear, angular) twist) to set for the model now at ``pose``."""
        return pose, ((0.0, 0.0, 0.0), (0.0, 0.0, self.angular))


class Leg(NamedTuple):
    step: Tuple[float, float]     # m added to x and y at each tick
    until: Tuple[float, float]    # the next leg starts within 0.05 m (on x and y) of this


# combination_obstacle_1.py and _2.py: each obstacle's legs, and where it starts over (leg 0)
WAYPOINTS = {
    "obstacle_1": ((2.0, 2.0), (
        Leg((-0.005, -0.012), (1.5, 0.8)), Leg((-0.01, 0.007), (0.5, 1.5)),
        Leg((-0.008, -0.002), (-0.3, 1.3)), Leg((-0.007, -0.005), (-1.0, 0.8)),
        Leg((-0.01, 0.007), (-2.0, 1.5)), Leg((-0.002, -0.007), (-2.2, 0.8)),
        Leg((0.004, -0.011), (-1.8, -0.3)), Leg((0.003, -0.007), (-1.5, -1.0)),
        Leg((0.009, 0.007), (-0.6, -0.3)), Leg((0.011, -0.011), (0.5, -1.4)),
        Leg((0.006, -0.006), (1.1, -2.0)), Leg((0.009, 0.01), (2.0, -1.0)),
        Leg((-0.008, 0.01), (1.2, 0.0)), Leg((-0.007, 0.005), (0.5, 0.5)),
        Leg((0.017, 0.008), (2.2, 1.3)), Leg((-0.002, 0.007), (2.0, 2.0)))),
    "obstacle_2": ((-2.0, -2.0), (
        Leg((0.007, -0.001), (-1.3, -2.1)), Leg((0.009, 0.009), (-0.4, -1.2)),
        Leg((-0.006, 0.006), (-1.0, -0.6)), Leg((0.008, -0.001), (-0.2, -0.7)),
        Leg((0.013, -0.013), (1.1, -2.0)), Leg((0.009, 0.01), (2.0, -1.0)),
        Leg((-0.008, 0.01), (1.2, 0.0)), Leg((-0.007, 0.02), (0.5, 2.0)),
        Leg((-0.013, -0.001), (-2.1, 1.8)), Leg((0.008, -0.008), (-0.5, 0.2)),
        Leg((-0.002, -0.0115), (-0.9, -2.1)), Leg((-0.011, 0.001), (-2.0, -2.0)))),
}


class WaypointObstacle:
    """One of stage 4's combination_obstacle nodes: at each tick the model moves one step of
    its leg, and takes the next leg near the leg's end (the first near its start point)."""

    def __init__(self, name: str):
        self.name = name
        self.start, self.legs = WAYPOINTS[name]
        self.leg = 0

    def tick(self, pose):
        (x, y, z), orientation = pose
        if abs(x - self.start[0]) < 0.05 and abs(y - self.start[1]) < 0.05:
            self.leg = 0
        leg = self.legs[self.leg]
        x, y = x + leg.step[0], y + leg.step[1]
        if abs(x - leg.until[0]) < 0.05 and abs(y - leg.until[1]) < 0.05:
            self.leg = (self.leg + 1) % len(self.legs)
        return ((x, y, z), orientation), ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


def obstacles(stage: int) -> list:
    """The obstacle movers of ``stage`` (its obstacle nodes), fresh."""
    if stage == 3:
        return [SpinningObstacle()]
    if stage == 4:
        return [WaypointObstacle("obstacle_1"), WaypointObstacle("obstacle_2")]
    return []
