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
  stopped; how much sim time that is depends on the sim's speed, so there is no pause here.
  Registered with a TimeLimit of 501 steps, where turtlebot3_dqn ends an episode.
- ``fix_pinned_collision``: ROBOTIS' collision test misses the -inf the laser reads below
  0.12 m, so a robot pressed against a wall is never flagged; True counts it (off by default).
- ``time_step``: the physics step (s; 0.0025 by default, as the sim node's); coarser steps run
  faster at a cost in accuracy measured in doc/learning.md.
- ``variant``: "noetic" (the above, ROBOTIS' ROS 1 clients) or "ros2": ROBOTIS' ROS 2 nodes
  (learning.robotis_stages_ros2) in their worlds (worlds/turtlebot3_dqn_stage1.world to 4),
  the laser at 48 samples. A step's state is the one of the moment its action arrives, before the
  action acts (dqn_environment reads the last scan and odometry then), and the action is then
  held for 0.2 s; a goal, a collision or the 799th step ends the episode; a failure resets the
  world at once, a goal draws the next one with the robot where it is. fix_pinned_collision
  changes nothing there (its collision test counts a -inf).
- ``render_mode``: None, "rgb_array" or "human" (a window; without a display it fails at
  construction); the picture is learning.stage_render's, or with ``render_camera`` the
  robot's camera image (waffle, waffle_pi).

Units: metres, radians, seconds; the world frame of the stage world.
"""
import math
import os
import random
from typing import Optional

import gymnasium
import numpy as np
from gymnasium import spaces

from ..sim.files.sdf.world_catalogue import WORLD_DIR
from ..sim.kinematics import yaw_from_quat
from ..sim.world.simulation import SimConfig, Simulation
from ..sim.world.world_control import WorldControl
from . import robotis_stages as rs
from . import robotis_stages_ros2 as r2
from .stage_render import RENDER_MODES, StageRender

MAX_GOAL_DISTANCE = 6.0    # m: farther than any two points of a stage's arena
VARIANTS = ("noetic", "ros2")   # ROBOTIS' ROS 1 clients, ROBOTIS' ROS 2 nodes


class StageEnv(gymnasium.Env):
    """One TurtleBot3 in learning stage ``stage`` (1 to 4)."""

    # one env step is rs.STEP_TIME (0.2 s) of sim time: 5 frames a sim second
    metadata = {"render_modes": list(RENDER_MODES), "render_fps": 5}

    def __init__(self, stage: int = 1, model: str = "burger", time_step: float = 0.0025,
                 fix_pinned_collision: bool = False, render_mode: Optional[str] = None,
                 render_camera: bool = False, variant: str = "noetic"):
        if stage not in rs.STAGES:
            raise ValueError("stage %r: the learning stages are %s" % (stage, rs.STAGES))
        if variant not in VARIANTS:
            raise ValueError("variant %r: the variants are %s" % (variant, ", ".join(VARIANTS)))
        self.variant = variant
        self.render_mode = render_mode   # (checked before the sim is built: no display fails)
        self._render = StageRender(render_mode, render_camera, model, self.metadata["render_fps"],
                                   "TurtleBot3 stage %d" % stage)
        self.last_ranges = None          # the last observation's scan (m), as the laser gave it
        self.stage = stage
        self.fix_pinned_collision = fix_pinned_collision
        if variant == "ros2":   # ROBOTIS' ROS 2 world; the robot is spawned as "burger" there
            config = SimConfig(model=model, world=os.path.join(WORLD_DIR, r2.world_file(stage)),
                               x=r2.SPAWN[0], y=r2.SPAWN[1], yaw=r2.SPAWN[2], robot_name=model,
                               lidar_samples=r2.SCAN_SAMPLES, time_step=time_step)
        else:
            config = SimConfig(model=model, world="turtlebot3_stage_%d" % stage,
                               lidar_samples=rs.SCAN_SAMPLES, time_step=time_step)
        self.sim = Simulation(config)
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
        if variant == "ros2":
            self._init_ros2(far)

    # --- Gymnasium ---------------------------------------------------------------------------

    def reset(self, *, seed: Optional[int] = None, options: Optional[dict] = None):
        super().reset(seed=seed)
        if self.variant == "ros2":
            return self._reset_ros2(seed)
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
        if self.render_mode == "human":
            self.render()
        return self._array(obs.values), self._info(obs)

    def step(self, action):
        action = int(action)
        if not 0 <= action < rs.ACTIONS:
            raise ValueError("action %r: the actions are 0 to %d" % (action, rs.ACTIONS - 1))
        if self.variant == "ros2":
            return self._step_ros2(action)
        self._hold(*rs.action_command(action))
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
        if self.render_mode == "human":
            self.render()
        return self._array(obs.values), value, obs.collision, False, info

    def render(self):
        """The stage seen from above now (learning.stage_render; with render_camera the
        robot's camera image): an HxWx3 uint8 array for "rgb_array"; shown in a window, and
        None, for "human" (which reset and step also show)."""
        return self._render.frame(self.sim, self.robot, self.goal, self.last_ranges)

    def close(self):
        self._render.close()
        if self.sim is not None:
            self.sim.close()
            self.sim = None

    # --- the parts -----------------------------------------------------------------------------

    def _odometry(self):
        """(x, y, yaw) of base_footprint in odom (as ROBOTIS reads /odom)."""
        odom = self.robot.odom()
        return odom.position[0], odom.position[1], yaw_from_quat(odom.orientation)

    def _observe(self, x: float, y: float, yaw: float) -> rs.Observation:
        ranges = self.last_ranges = self.robot.scan()
        obs = rs.observation(self.stage, ranges,
                             rs.heading_to(self.goal, x, y, yaw), rs.goal_distance(self.goal, x, y))
        if self.fix_pinned_collision and not obs.collision and np.any(np.isneginf(ranges)):
            obs = obs._replace(collision=True)
        return obs

    def _hold(self, linear: float, angular: float) -> None:
        """Command (linear m/s, angular rad/s) and run one step (STEP_TIME) of sim time."""
        # Over ROS the command comes after the scan, when the diff drive's control tick of that
        # moment (30 Hz: one falls on every scan) has read the last one: the last action goes on
        # for one physics step, and the new one acts from the next tick, 1/30 s later.
        self.sim.advance(1)
        self.robot.command(linear, angular)
        steps = self._tick_steps - 1
        for _ in range(self._ticks):
            self.sim.advance(steps)
            self._move_obstacles()
            steps = self._tick_steps

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

    # --- the ROS 2 variant (learning.robotis_stages_ros2) --------------------------------------

    def _init_ros2(self, far: float) -> None:
        """The ROS 2 variant's space (26 values), goal, obstacles and bookkeeping."""
        # The rays' angles of ROS 2's laser (0..6.28 rad), which pick the state's rays and weigh
        # obstacle_reward: this laser's sweep is the noetic URDF's, 0..6.28319 rad, whose last
        # ray (0.0032 rad further) lies past 2 pi and would drop out.
        self._angles = r2.scan_angles()
        low = np.zeros(r2.OBSERVATION_SIZE)
        low[1] = -math.pi
        high = np.array([r2.ARENA_DIAGONAL, math.pi] + [far] * r2.FRONT_SAMPLES)
        self.observation_space = spaces.Box(low.astype(np.float32), high.astype(np.float32),
                                            dtype=np.float32)
        self._goals = None
        self.goal = r2.GoalSequence(self.stage).first()
        self._movers = r2.obstacles(self.stage)
        self._book = r2.EpisodeBook()
        self._episode_open = False     # a reset gave a state and no step has ended its episode
        self._scan = None              # (sim time ns, ranges) of the last scan read

    def _reset_ros2(self, seed: Optional[int]):
        """The first reset and a seeded one are make_environment (the world reset, the first
        goal); after an episode that ended (a failure reset the world already) only the state
        is read; an episode cut short ends as the time limit ends one (the world reset, a new
        goal). Then reset_environment's state, which counts and is tested as a step's."""
        if self._goals is None or seed is not None:
            self._goals = r2.GoalSequence(self.stage, random.Random(seed))
            self.goal = self._goals.first()
            if seed is not None:
                self.robot.reseed(seed)
            self._book = r2.EpisodeBook()
            self._reset_world()
        elif self._episode_open:
            self._book = r2.EpisodeBook()
            self._reset_world()
            self.goal = self._goals.next()
        self._episode_open = True
        obs, outcome, goal, time = self._state_ros2()
        if self.render_mode == "human":
            self.render()
        return self._array(obs.values), self._info_ros2(outcome, goal, time)

    def _step_ros2(self, action: int):
        """rl_agent_interface: the state of now, its reward and done; then, unless done, the
        action held for STEP_TIME (done: the robot is stopped)."""
        obs, outcome, goal, time = self._state_ros2()
        value = self._book.reward(obs.values[1], obs)
        done = self._book.end_step()
        if done:
            self._episode_open = False
            self.robot.command(0.0, 0.0)
        else:
            self._hold(*r2.action_command(action))
        if self.render_mode == "human":
            self.render()
        return self._array(obs.values), value, done, False, self._info_ros2(outcome, goal, time)

    def _state_ros2(self):
        """calculate_state: (the state of now, its tests, its goal, its sim time s); a goal
        reached draws the next goal, a failure resets the world and draws one (dqn_gazebo)."""
        x, y, yaw = self._odometry()
        goal, time = self.goal, self.sim.time
        obs = r2.observation(self._latest_scan(), self._angles, r2.goal_distance(goal, x, y),
                             rs.goal_bearing(goal, x, y, yaw))
        outcome = self._book.record(obs.values[0], obs.nearest)
        if outcome.reached:
            self.goal = self._goals.next()
        if outcome.failed:
            self._reset_world()
            self.goal = self._goals.next()
        return obs, outcome, goal, time

    def _latest_scan(self):
        """The last scan: read again at the same sim time, the same ranges (the same message)."""
        if self._scan is None or self._scan[0] != self.sim.time_ns:
            self._scan = (self.sim.time_ns, self.robot.scan())
        self.last_ranges = self._scan[1]
        return self._scan[1]

    def _reset_world(self) -> None:
        """Gazebo's reset_simulation (dqn_gazebo's on humble): the world, the robot and the
        obstacles' animations back to their start."""
        self.sim.reset_simulation()
        self._movers = r2.obstacles(self.stage)
        self._scan = None

    def _info_ros2(self, outcome: r2.Outcome, goal, time: float) -> dict:
        return {"goal": goal, "at_goal": outcome.reached, "collision": outcome.collided,
                "timeout": outcome.timed_out, "sim_time": time}
