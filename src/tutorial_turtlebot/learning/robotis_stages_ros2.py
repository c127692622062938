"""What ROBOTIS' turtlebot3_machine_learning for ROS 2 does in its four DQN stages, as plain
functions and data: no ROS, no Gymnasium, no simulator (doc/learning.md). StageEnv uses it with
``variant="ros2"``; robotis_stages.py is the ROS 1 (noetic) version, the default.

It follows github.com/ROBOTIS-GIT/turtlebot3_machine_learning, branches ``main``, ``humble`` and
``jazzy`` (one tree; ``main`` at 3bce927fc2161b3df4568c6a170502dd45aff7e3, tag 1.0.3):
turtlebot3_dqn/turtlebot3_dqn/dqn_environment.py (state, reward, episode), dqn_gazebo.py
(goals, resets) and dqn_agent.py (26 state values). The stage worlds and their moving obstacles
are turtlebot3_gazebo's of github.com/ROBOTIS-GIT/turtlebot3_simulations, branch ``humble`` at
98d3e7a8181cdf497511a07d8271d4758c26ab2e (its worlds turtlebot3_dqn_stage1 to 4, its model
turtlebot3_dqn_world, its plugins obstacles.cpp, obstacle1.cpp and obstacle2.cpp), drawn again as
this package's worlds/turtlebot3_dqn_stage1.world to stage4. The noetic version follows branch
``noetic`` at 5df6e0a4fbf326b0d4bf9838701090522413844c.

What differs from noetic (robotis_stages):

- ``observation``: 26 values: the goal's distance and angle (unrounded), then the 24 ranges of
  the front half (0..pi/2 and 3pi/2..2pi) of a 48-sample scan (ROBOTIS' e-manual for jazzy has
  the laser at 48 samples; the code needs 24 in front). No nearest range, no rounding.
- ``collision``: any range under 0.15 m, a -inf or a NaN's 0 included (noetic: 0 < r < 0.13).
- ``reward``: ``1 - 2 |angle| / pi`` plus ``obstacle_reward`` (ranges within 0.5 m ahead); a
  goal gives 100 and ends the episode; a collision or the time limit gives -50 and ends it.
  No distance term. What the agent receives went through a float32 (turtlebot3_msgs' Dqn.srv).
- ``EpisodeBook``: 800 states to an episode, the reset's among them (799 actions); a failure
  (collision, time limit) resets the world and draws a goal; a goal only draws the next one.
- ``GoalSequence``: the first goal (0.5, 0); then, stages 1-3, any point of a 0.1 m grid over
  -2.1..2.0 m (no test against the pillars or the last goal); stage 4, one of 12 points (the
  last one may come again). Coordinates as float32 (turtlebot3_msgs' Goal.srv).
- ``action_command``: 0.2 m/s (noetic 0.15), the same five turn rates.
- ``KeyframeObstacle``: Gazebo pose animations (stage 3 turns the four pillars about (0, 0)
  once in 40 s; stage 4 moves two pillars along keyframes) instead of obstacle nodes.

Units: metres, radians (angles counter-clockwise from the robot's +x), seconds, m/s.
"""
import math
import random
from typing import List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from . import robotis_stages as rs
# shared with noetic: the stages, the five actions, the obstacles' tick; and the step,
# rs.STEP_TIME, one scan period (ROBOTIS' ROS 2 agent has none: it asks again as soon as it
# has learnt)
from .robotis_stages import ACTIONS, OBSTACLE_TICK, STAGES
REEXPORTED = (ACTIONS, STAGES)  # used as r2.ACTIONS and r2.STAGES by the tests

SCAN_SAMPLES = 48           # rays of the scan; its front half gives the state's 24 ranges
SCAN_MAX_ANGLE = 6.28       # rad: the last ray of turtlebot3_gazebo's LDS (the first at 0)
FRONT_SAMPLES = 24
OBSERVATION_SIZE = 2 + FRONT_SAMPLES
LINEAR_SPEED = 0.2          # m/s of every action
MAX_STEP = 800              # states to an episode, counting the one a reset gives
MAX_EPISODE_STEPS = MAX_STEP - 1   # actions to an episode that times out
COLLISION_RANGE = 0.15      # m
GOAL_RANGE = 0.20           # m
OBSTACLE_NEAR = 0.5         # m: ranges ahead within this weigh on obstacle_reward
GOAL_REWARD = 100.0
FAIL_REWARD = -50.0         # a collision or the time limit
FIRST_GOAL = (0.5, 0.0)     # m
GOAL_GRID = (-21, 21)       # stages 1-3: a goal coordinate is randrange(-21, 21) / 10 m
STAGE_4_GOALS = ((1.0, 0.0), (2.0, -1.5), (0.0, -2.0), (2.0, 1.5), (0.5, 2.0), (-1.5, 2.1),
                 (-2.0, 0.5), (-2.0, -0.5), (-1.5, -2.0), (-0.5, -1.0), (2.0, -0.5), (-1.0, -1.0))
SPAWN = (0.0, 0.0, 0.0)     # (x m, y m, yaw rad) of the robot in every stage
ARENA_DIAGONAL = 5.0 * math.sqrt(2)   # m: the 5 m square's, more than any goal distance in it


def world_file(stage: int) -> str:
    """The file in worlds/ of ``stage``'s world."""
    return "turtlebot3_dqn_stage%d.world" % stage


def float32(value: float) -> float:
    """``value`` as a float32 of a ROS message carries it."""
    return float(np.float32(value))


def action_command(action: int) -> Tuple[float, float]:
    """(linear m/s, angular rad/s) of discrete ``action`` 0..4 (0 turns left fastest)."""
    return LINEAR_SPEED, rs.action_command(action)[1]


def scan_angles(samples: int = SCAN_SAMPLES, angle_min: float = 0.0,
                angle_max: float = SCAN_MAX_ANGLE) -> List[float]:
    """The rays' angles (rad, counter-clockwise from ahead), spread as Gazebo spreads them."""
    step = (angle_max - angle_min) / (samples - 1)
    return [angle_min + i * step for i in range(samples)]


def is_front(angle: float) -> bool:
    """Whether a ray at ``angle`` (rad, 0..2pi) is one of the state's: within 90 degrees of
    ahead."""
    return 0 <= angle <= math.pi / 2 or 3 * math.pi / 2 <= angle <= 2 * math.pi


def goal_distance(goal: Sequence[float], x: float, y: float) -> float:
    """The distance (m, unrounded) from the robot at (x, y) to the goal."""
    return math.sqrt((goal[0] - x) ** 2 + (goal[1] - y) ** 2)


class Observation(NamedTuple):
    values: List[float]          # the 26 values: distance, angle, the front ranges
    front_ranges: List[float]    # m
    front_angles: List[float]    # rad, 0..2pi, of front_ranges
    nearest: float               # m: the smallest of all ranges


def observation(ranges: Sequence[float], angles: Sequence[float], distance: float,
                angle: float) -> Observation:
    """calculate_state's state for a scan's ``ranges`` at ``angles`` and the goal's distance
    and angle."""
    scan = rs.scan_values(ranges)
    front = [(r, a) for r, a in zip(scan, angles) if is_front(a)]
    front_ranges = [r for r, _ in front]
    return Observation([distance, angle] + front_ranges, front_ranges, [a for _, a in front],
                       min(scan))


def yaw_reward(angle: float) -> float:
    """1 with the goal straight ahead, 0 at 90 degrees, -1 behind (``angle`` in rad)."""
    return 1 - (2 * abs(angle) / math.pi)


def obstacle_reward(front_ranges: Sequence[float], front_angles: Sequence[float]) -> float:
    """The penalty for the front ranges within OBSTACLE_NEAR: ``-(1 + 4 * d)``, d the mean of
    ``exp(-3 * clip(r - 0.25, 0.01, 3.5))`` weighted by ``cos(angle)**6 + 0.1`` (angle from
    ahead, -pi..pi: the nearer ahead, the heavier); 0 with none."""
    near = [(r, a) for r, a in zip(front_ranges, front_angles) if r <= OBSTACLE_NEAR]
    if not near:
        return 0.0
    # ROBOTIS scales the weights so that the largest is 10, then normalises: only the ratios stay
    weights = [math.cos(a - 2 * math.pi if a > math.pi else a) ** 6 + 0.1 for _, a in near]
    decays = [math.exp(-3.0 * min(max(r - 0.25, 1e-2), 3.5)) for r, _ in near]
    weighted = sum(w * d for w, d in zip(weights, decays)) / sum(weights)
    return -(1.0 + 4.0 * weighted)


def reward(angle: float, obs: Observation, succeeded: bool, failed: bool) -> float:
    """calculate_reward: the goal's reward, else a failure's, else the yaw reward of the goal's
    ``angle`` (rad) plus the obstacle reward of ``obs``."""
    if succeeded:
        return GOAL_REWARD
    if failed:
        return FAIL_REWARD
    return yaw_reward(angle) + obstacle_reward(obs.front_ranges, obs.front_angles)


class Outcome(NamedTuple):
    """What calculate_state's tests found in one state."""
    reached: bool      # the goal is closer than GOAL_RANGE: a new goal is drawn
    collided: bool     # a range is under COLLISION_RANGE
    timed_out: bool    # the state was the MAX_STEP-th of its episode

    @property
    def failed(self) -> bool:
        """A collision or the time limit: the world is reset and a goal drawn."""
        return self.collided or self.timed_out


class EpisodeBook:
    """dqn_environment's bookkeeping from call to call: its count of states (a reset's and a
    step's), which a goal, a collision or the time limit sets back to 0; and its succeed and
    fail flags, which a state's tests set and only a step that reports done clears (so a goal
    or a collision found by a reset's state ends the next step)."""

    def __init__(self):
        self.states = 0
        self.succeeded = False
        self.failed = False

    def record(self, distance: float, nearest: float) -> Outcome:
        """Count one state and test it: the goal at ``distance`` (m), the nearest range (m)."""
        self.states += 1
        reached = distance < GOAL_RANGE
        collided = nearest < COLLISION_RANGE
        if reached:
            self.succeeded = True
            self.states = 0
        if collided:
            self.failed = True
            self.states = 0
        timed_out = self.states == MAX_STEP
        if timed_out:
            self.failed = True
            self.states = 0
        return Outcome(reached, collided, timed_out)

    @property
    def done(self) -> bool:
        return self.succeeded or self.failed

    def reward(self, angle: float, obs: Observation) -> float:
        """The step's reward (as the agent receives it: a float32)."""
        return float32(reward(angle, obs, self.succeeded, self.failed))

    def end_step(self) -> bool:
        """Whether the step ends the episode; the flags are cleared if so."""
        done = self.done
        if done:
            self.succeeded = self.failed = False
        return done


class GoalSequence:
    """dqn_gazebo's goals: FIRST_GOAL, then each new one drawn from ``rng`` as
    generate_goal_pose draws it (random.randrange, random.randint), as float32s."""

    def __init__(self, stage: int, rng: Optional[random.Random] = None):
        self.stage = stage
        self.rng = rng if rng is not None else random.Random()

    def first(self) -> Tuple[float, float]:
        return float32(FIRST_GOAL[0]), float32(FIRST_GOAL[1])

    def next(self) -> Tuple[float, float]:
        """The next goal (m, world frame)."""
        if self.stage != 4:
            x = self.rng.randrange(*GOAL_GRID) / 10
            y = self.rng.randrange(*GOAL_GRID) / 10
        else:
            x, y = STAGE_4_GOALS[self.rng.randint(0, len(STAGE_4_GOALS) - 1)]
        return float32(x), float32(y)


# --- the moving obstacles: Gazebo's pose animations -------------------------------------------
# A rotation about z is kept as (w, z) of its quaternion; the functions below do what Gazebo's
# ignition::math does with whole quaternions, restricted to such rotations.

def _quat(yaw: float) -> Tuple[float, float]:
    return math.cos(yaw / 2), math.sin(yaw / 2)


def _mul(p, q):
    return p[0] * q[0] - p[1] * q[1], p[0] * q[1] + p[1] * q[0]


def _log(q) -> float:
    """The z of the pure quaternion log(q)."""
    if abs(q[0]) < 1.0:
        angle = math.acos(q[0])
        sine = math.sin(angle)
        if abs(sine) >= 1e-3:
            return angle / sine * q[1]
    return q[1]


def _exp(z: float):
    angle = abs(z)
    sine = math.sin(angle)
    return math.cos(angle), (sine / angle * z if abs(sine) >= 1e-3 else z)


def _slerp(t: float, p, q, shortest: bool = False):
    cos = p[0] * q[0] + p[1] * q[1]
    if cos < 0.0 and shortest:
        cos, q = -cos, (-q[0], -q[1])
    if abs(cos) < 1 - 1e-3:
        sine = math.sqrt(1 - cos * cos)
        angle = math.atan2(sine, cos)
        c0, c1 = math.sin((1 - t) * angle) / sine, math.sin(t * angle) / sine
        return p[0] * c0 + q[0] * c1, p[1] * c0 + q[1] * c1
    w, z = p[0] * (1 - t) + q[0] * t, p[1] * (1 - t) + q[1] * t
    norm = math.hypot(w, z)
    return w / norm, z / norm


def _same_rotation(p, q) -> bool:
    return abs(p[0] - q[0]) <= 1e-3 and abs(p[1] - q[1]) <= 1e-3


def _rotation_tangents(points) -> list:
    """Shoemake's tangents of a rotation spline (ignition's RotationSpline)."""
    n, closed = len(points), _same_rotation(points[0], points[-1])
    tangents = []
    for i, p in enumerate(points):
        inverse = (p[0], -p[1])
        after = points[i + 1] if i < n - 1 else (points[1] if closed else p)
        before = points[i - 1] if i > 0 else (points[n - 2] if closed else p)
        z = -0.25 * (_log(_mul(inverse, after)) + _log(_mul(inverse, before)))
        tangents.append(_mul(p, _exp(z)))
    return tangents


def _position_tangents(points) -> list:
    """Catmull-Rom tangents (tension 0) of a position spline (ignition's Spline)."""
    n = len(points)
    closed = all(abs(a - b) <= 1e-6 for a, b in zip(points[0], points[-1]))
    tangents = []
    for i in range(n):
        if i == 0:
            before = points[n - 2] if closed else points[0]
            after = points[1]
        elif i == n - 1:
            if closed:
                tangents.append(tangents[0])
                continue
            before, after = points[i - 1], points[i]
        else:
            before, after = points[i - 1], points[i + 1]
        tangents.append(tuple(0.5 * (a - b) for a, b in zip(after, before)))
    return tangents


def _hermite(p0, p1, t0, t1, s: float):
    h00, h01 = 2 * s ** 3 - 3 * s ** 2 + 1, -2 * s ** 3 + 3 * s ** 2
    h10, h11 = s ** 3 - 2 * s ** 2 + s, s ** 3 - s ** 2
    return tuple(h00 * a + h01 * b + h10 * c + h11 * d for a, b, c, d in zip(p0, p1, t0, t1))


class Key(NamedTuple):
    time: float     # s into the animation
    x: float        # m
    y: float        # m
    yaw: float      # rad


class KeyframeObstacle:
    """A model that a looping Gazebo pose animation moves (turtlebot3_gazebo's obstacles,
    obstacle1 and obstacle2 plugins): its pose at animation time t is the keyframes' joined by
    Gazebo's splines (positions: cubic Hermite with Catmull-Rom tangents; yaw: squad), and t
    runs with the sim time from the world's reset. ``tick`` moves it every OBSTACLE_TICK
    (Gazebo moves it at every physics step)."""

    def __init__(self, name: str, period: float, keys: Sequence[Key]):
        self.name = name
        self.period = period
        self.keys = tuple(keys)
        self._points = [(float(k.x), float(k.y)) for k in self.keys]
        self._point_tangents = _position_tangents(self._points)
        self._turns = [_quat(k.yaw) for k in self.keys]
        self._turn_tangents = _rotation_tangents(self._turns)
        self.ticks = 0

    def pose_at(self, time: float):
        """((x, y, 0), quaternion (x, y, z, w)) of the model frame ``time`` s into the
        animation."""
        time = math.fmod(time, self.period)
        index = max(i for i, k in enumerate(self.keys) if k.time <= time)
        key = self.keys[index]
        if index == len(self.keys) - 1 or time == key.time:
            (x, y), (w, z) = self._points[index], self._turns[index]
        else:
            s = (time - key.time) / (self.keys[index + 1].time - key.time)
            x, y = _hermite(self._points[index], self._points[index + 1],
                            self._point_tangents[index], self._point_tangents[index + 1], s)
            p, q = self._turns[index], self._turns[index + 1]
            a, b = self._turn_tangents[index], self._turn_tangents[index + 1]
            w, z = _slerp(2 * s * (1 - s), _slerp(s, p, q, shortest=True), _slerp(s, a, b))
        return (x, y, 0.0), (0.0, 0.0, z, w)

    def tick(self, pose):
        """(pose, twist) to set for the model one tick later (``pose``, where it is, is not
        needed: the animation knows)."""
        self.ticks += 1
        return self.pose_at(self.ticks * OBSTACLE_TICK), ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


# the animations of turtlebot3_gazebo's plugins: (model, period s, keyframes)
ANIMATIONS = {
    3: (("turtlebot3_dqn_obstacles", 40.0, (
        Key(0, 0, 0, 0), Key(20, 0, 0, math.pi), Key(40, 0, 0, 2 * math.pi))),),
    4: (("turtlebot3_dqn_obstacle1", 160.0, (
        Key(0, 0, 0, 0), Key(10, -0.5, -1, 0), Key(50, -3.5, -1, 0), Key(70, -3.7, -3, 0),
        Key(90, -3.5, -1, 0), Key(130, -0.5, -1, 0), Key(140, 0, 0, 0), Key(160, 0, 0, 0))),
        ("turtlebot3_dqn_obstacle2", 140.0, (
            Key(0, 0, 0, 0), Key(10, 0.7, 0.2, 0), Key(40, 2.5, 3.5, 0), Key(55, 0.3, 3.5, 0),
            Key(85, 3.5, 1.8, 0), Key(100, 3.5, 0, 0), Key(110, 2.0, 0.5, 0),
            Key(115, 1.5, 1.0, 0), Key(120, 1.0, 0.5, 0), Key(125, 0.5, 0.1, 0),
            Key(130, 0, 0, 0), Key(140, 0, 0, 0)))),
}


def obstacles(stage: int) -> list:
    """The obstacle movers of ``stage``, fresh (their animations at 0: the world's reset)."""
    return [KeyframeObstacle(*animation) for animation in ANIMATIONS.get(stage, ())]
