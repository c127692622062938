"""ROBOTIS' learning stages as a Gymnasium environment on the simulator, without ROS.

``StageEnv(stage)`` is turtlebot3_machine_learning's ``environment_stage_N.Env`` with its goal
respawner and obstacle nodes (learning.robotis_stages), stepped in this process at the cost of
the physics: an action is a command held for one scan period (0.2 s of sim time), after which
the observation is that scan and the odometry at that moment. The robot is spawned where
turtlebot3_gazebo's stage launch spawns it, with its laser at the 24 samples of ROBOTIS' set-up.

- ``reset(seed=...)``: the simulation back to its start (Gazebo's reset_simulation); the first
  reset, and any with a seed, also starts the goal sequence (its first goal is (0.6, 0)) and
  the laser's noise from that seed. Later resets keep the goal, as ROBOTIS' clients do.
- ``step(action)``: (observation, reward, terminated = a collision, truncated = False, info);
  a goal reached gives its reward and the next goal, and the episode goes on. The command acts
  as it does over ROS: from the diff drive's first control tick after the scan (1/30 s later).
  ROBOTIS' respawner sleeps 0.5 s of wall time before it spawns the next goal, the robot
  stopped; how much sim time that is depends on the sim's speed, so there is no pause here. Registered with a
  TimeLimit of 501 steps, where turtlebot3_dqn ends an episode.
- ``fix_pinned_collision``: ROBOTIS' collision test misses the -inf the laser reads below
  0.12 m, so a robot pressed against a wall is never flagged; True counts it (off by default).
- ``time_step``: the physics step (s; 0.0025 by default, as the sim node's); coarser steps run
  faster at a cost in accuracy measured in doc/learning.md.

Units: metres, radians, seconds; the world frame of the stage world.
"""
import math
import random
from typing import Optional

import gymnasium
import numpy as np
from gymnasium import spaces

from ..sim.kinematics import yaw_from_quat
from ..sim.world.simulation import SimConfig, Simulation
from ..sim.world.world_control import WorldControl
from . import robotis_stages as rs

MAX_GOAL_DISTANCE = 6.0    # m: farther than any two points of a stage's arena


class StageEnv(gymnasium.Env):
    """One TurtleBot3 in learning stage ``stage`` (1 to 4)."""

    metadata = {"render_modes": []}

    def __init__(self, stage: int = 1, model: str = "burger", time_step: float = 0.0025,
                 fix_pinned_collision: bool = False):
        if stage not in rs.STAGES:
            raise ValueError("stage %r: the learning stages are %s" % (stage, rs.STAGES))
        self.stage = stage
        self.fix_pinned_collision = fix_pinned_collision
        self.sim = Simulation(SimConfig(model=model, world="turtlebot3_stage_%d" % stage,
                                        lidar_samples=rs.SCAN_SAMPLES, time_step=time_step))
        self.robot = self.sim.robot
        self.world = WorldControl(self.sim)
        steps = rs.OBSTACLE_TICK / time_step
        if abs(steps - round(steps)) > 1e-6:
            raise ValueError("time_step %g s must divide %g s" % (time_step, rs.OBSTACLE_TICK))
        self._tick_steps = int(round(steps))                  # physics steps per obstacle tick
        self._ticks = int(round(rs.STEP_TIME / rs.OBSTACLE_TICK))
        # finite bounds: a -inf range (closer than range_min), which ROBOTIS passes on, is 0 here
        far = max(self.robot.laser.range_max, rs.NO_RETURN)
        low = np.zeros(rs.OBSERVATION_SIZE)
        low[-4] = -math.pi
        high = np.array([far] * rs.SCAN_SAMPLES + [math.pi, MAX_GOAL_DISTANCE, far,
                                                   rs.SCAN_SAMPLES - 1])
        self.observation_space = spaces.Box(low.astype(np.float32), high.astype(np.float32),
                                            dtype=np.float32)
        self.action_space = spaces.Discrete(rs.ACTIONS)
        self._goals: Optional[rs.GoalSequence] = None
        self.goal = rs.FIRST_GOAL
        self._start_distance = 1.0
        self._movers = rs.obstacles(stage)

    # --- Gymnasium ---------------------------------------------------------------------------

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        if self._goals is None or seed is not None:
            self._goals = rs.GoalSequence(self.stage, random.Random(seed))
            self.goal = self._goals.first()
            if seed is not None:
                self.robot.reseed(seed)
        self.sim.reset_simulation()
        self._movers = rs.obstacles(self.stage)
        x, y, yaw = self._odometry()
        self._start_distance = rs.goal_distance(self.goal, x, y)
        obs = self._observe(x, y, yaw)
        return self._array(obs.values), self._info(obs)

    def step(self, action):
        action = int(action)
        if not 0 <= action < rs.ACTIONS:
            raise ValueError("action %r: the actions are 0 to %d" % (action, rs.ACTIONS - 1))
        # Over ROS the command comes after the scan, when the diff drive's control tick of that
        # moment (30 Hz: one falls on every scan) has read the last one: the last action goes on
        # for one physics step, and the new one acts from the next tick, 1/30 s later.
        self.sim.advance(1)
        self.robot.command(*rs.action_command(action))
        steps = self._tick_steps - 1
        for _ in range(self._ticks):
            self.sim.advance(steps)
            self._move_obstacles()
            steps = self._tick_steps
        x, y, yaw = self._odometry()
        obs = self._observe(x, y, yaw)
        value = rs.reward(self.stage, obs.values, action, self._start_distance, obs.collision,
                          obs.at_goal)
        info = self._info(obs)
        # (ROBOTIS' client sends a stop at a goal or a collision, then the next command at once:
        # the stop never reaches a tick; a collision ends the episode and reset stops the robot)
        if obs.at_goal:
            self.goal = self._goals.next()
            self._start_distance = rs.goal_distance(self.goal, x, y)
        return self._array(obs.values), value, obs.collision, False, info

    def close(self):
        if self.sim is not None:
            self.sim.close()
            self.sim = None

    # --- the parts -----------------------------------------------------------------------------

    def _odometry(self):
        """(x, y, yaw) of base_footprint in odom (as ROBOTIS reads /odom)."""
        odom = self.robot.odom()
        return odom.position[0], odom.position[1], yaw_from_quat(odom.orientation)

    def _observe(self, x: float, y: float, yaw: float) -> rs.Observation:
        ranges = self.robot.scan()
        obs = rs.observation(self.stage, ranges,
                             rs.heading_to(self.goal, x, y, yaw), rs.goal_distance(self.goal, x, y))
        if self.fix_pinned_collision and not obs.collision and np.any(np.isneginf(ranges)):
            obs = obs._replace(collision=True)
        return obs

    def _move_obstacles(self) -> None:
        """One tick of the stage's obstacle nodes (set_model_state of each obstacle)."""
        for mover in self._movers:
            pose, twist, _ = self.world.get_model_state(mover.name)
            new_pose, new_twist = mover.tick(pose)
            self.world.set_model_state(mover.name, new_pose, new_twist)

    def _info(self, obs: rs.Observation) -> dict:
        return {"goal": self.goal, "at_goal": obs.at_goal, "collision": obs.collision,
                "sim_time": self.sim.time}

    @staticmethod
    def _array(values) -> np.ndarray:
        out = np.asarray(values, dtype=np.float32)
        if not np.isfinite(out).all():   # (the check alone is the cheaper when all are)
            np.nan_to_num(out, copy=False, neginf=0.0)
        return out
