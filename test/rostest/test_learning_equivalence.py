#!/usr/bin/env python3
"""rostest node: the Gymnasium environment (learning.stage_env.StageEnv, in this process) and
ROBOTIS' stage client over ROS (robotis_stage_client.Env, a faithful equivalent of
environment_stage_N.Env with its Respawn and, in stage 3, its obstacle node, against the /gazebo
sim node of the stage launch file) agree step by step: from the same start, the same goal draws
(random.Random(SEEDS[stage]) on both sides) and the same actions, the same done flags and goal
hits, rewards within what the 0.01 rounding of the heading and the distances explains, and each
of the 24 scan values within 1 cm.

The actions are planned on StageEnv (a scripted policy steers to the goal by the heading until
two goals are reached, then drives straight into a wall; in stage 1 the episode is then reset
and steering goes on), then replayed on the ROS client. The two runs are one after the other,
so that StageEnv's physics does not delay the ROS client.

When an action acts. The diff drive reads its command at its 30 Hz control ticks, at the start
of a physics step (as gazebo_ros_diff_drive); a tick falls on every scan moment. Over ROS the
command comes after the scan, when the sim has already run that tick (its physics runs up to
20 ms of wall time ahead of its messages, and the scan is made after the step that reaches its
moment): the last action goes on for one more control period, 1/30 s (35 ms on the 2.5 ms step
grid). StageEnv does the same (its step keeps the last command for the physics step of that
tick); a StageEnv whose command acted at once was 0.05 rad of heading and 17 cm of scan off
(measured), which this test would catch.

The real-time factor (0.2). With the tick, the delay of a command does not matter as long as it
reaches the sim before the next tick: 35 ms of sim time, minus the up to 20 ms x factor the
physics runs ahead. At factor 1 that leaves the client 15 ms of wall time, goal respawns
included (delete, a model_states without the goal, spawn), which a loaded machine misses; at
0.2, 155 ms, which it does not (a miss shows as a 35 ms lag: 0.05 rad). The run takes 5 wall s
per sim s.

Laser noise. Both sides have Gazebo's gaussian noise of sigma 0.01 m (the URDF's <noise>,
sim/devices/lidar.py): two independent draws differ by more than 1 cm at a third of the rays.
The noise is off on both sides: StageEnv's robot gets its LaserConfig with noise_sigma 0; the
sim node's robot (the stage launch file's, whose URDF no launch argument changes) is replaced,
before the run, by the same URDF with the laser's stddev 0, spawned through
/gazebo/spawn_urdf_model with the same name and pose.

Rewards. reward = round(5 tr(heading), 2) * 2 ** (distance / start distance), tr piecewise
linear in the heading with slope 2/pi per rad; heading, distance and start distance are rounded
to 0.01 on both sides. For dh, dd, ds, the differences of those rounded values between the
sides, |reward difference| <= (10/pi dh + 0.01) 2**q + 5 ln 2 2**q (dd / s + d ds / s**2), q the
larger distance / start distance (``reward_bound``); dh and dd must be within HEADING_TOL and
DISTANCE_TOL. A goal's or a collision's reward must be equal. The first heading after the first
reset is not compared: ROBOTIS' comes from odometry that arrived before its first goal was set,
the heading to (0, 0).

Stage 3's obstacle. Its ground friction stops a tick's 0.5 rad/s within 60 ms, so it turns the
same 0.0149 rad at every tick and its angle counts the ticks. StageEnv ticks every 0.1 s of sim
time; ROBOTIS' node sleeps 0.1 s of wall time (5 times as many ticks per sim second at factor
0.2), so the client's obstacle thread ticks at the same sim moments as StageEnv instead
(robotis_stage_client.MovingObstacle, DIFFERENCE 5). What is left: a tick over ROS sets the pose
read from a model_states message, a moment before the sim applies it, and turns 0.0137 to
0.0151 rad instead of 0.0149 (measured); over 80 steps the phases differ by up to 0.012 rad
(1 cm at the pillars' 0.85 m). So in stage 3 the obstacle's yaw (what each tick found, at rest)
is compared within OBSTACLE_YAW_TOL, the rays that end on the obstacle (within OBSTACLE_REACH of
the centre on either side: a ray at a pillar's edge may hit it on one side only) are left out
of the 1 cm comparison and their largest difference printed, and the plan keeps the robot
0.39 m from the pillars' centres, so that the phase decides no collision.

Waits on wall time with limits."""
import dataclasses
import math
import os
import random
import sys
import time
import unittest

import numpy as np
import rospy
import rostest
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import DeleteModel, SpawnModel
from geometry_msgs.msg import Point, Pose, Quaternion, Twist

from robotis_stage_client import Env, MovingObstacle, yaw_of
from sim_test_support import wait_for

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, os.pardir, os.pardir)
sys.path.insert(0, os.path.join(ROOT, "src"))
from tutorial_turtlebot.learning.stage_env import StageEnv  # noqa: E402
from tutorial_turtlebot.sim.kinematics import yaw_from_quat  # noqa: E402

# the goals' seed of each stage: one whose plan reaches goals and then a collision
SEEDS = {1: 5, 2: 5, 3: 38, 4: 5}
ROBOT = "turtlebot3_burger"
SCAN_TOL = 0.01          # m
HEADING_TOL = 0.03       # rad: rounding (0.01) and what the command delay turns (see above)
DISTANCE_TOL = 0.02      # m: rounding (0.01) and the command delay's 0.15 m/s x 5 ms
OBSTACLE_YAW_TOL = 0.03  # rad (module docstring)
GOALS_FIRST = 2          # the policy steers until this many goals are reached ...
STEER_STEPS = 60         # ... or for this many steps, then drives straight into a wall
STRAIGHT_STEPS = 60
AFTER_RESET_STEPS = 15   # stage 1: steering after the collision's reset


def steer(heading: float) -> int:
    """The action that turns toward a goal at ``heading`` (rad, left positive)."""
    return int(np.clip(2 - round(heading / 0.35), 0, 4))


def reward_bound(a, b) -> float:
    """The most the rewards of two states ``a`` and ``b`` (dicts: heading, distance, start) can
    differ by for their differences of the rounded heading and distances (module docstring)."""
    dh = abs(a["heading"] - b["heading"])
    dd = abs(a["distance"] - b["distance"])
    ds = abs(a["start"] - b["start"])
    s = min(a["start"], b["start"])
    d = max(a["distance"], b["distance"])
    q = 2 ** (max(a["distance"] / a["start"], b["distance"] / b["start"]))
    return (10 / math.pi * dh + 0.01) * q + 5 * math.log(2) * q * (dd / s + d * ds / s ** 2) + 1e-9


SCAN_OFFSET = -0.032   # m: base_scan ahead of base_footprint (the burger URDF)
OBSTACLE_REACH = 1.3   # m: stage 3's pillars turn within 1.0 m of the centre, its walls are
# 1.925 m from it


def obstacle_rays(pose, ranges) -> np.ndarray:
    """Which of the 24 rays of a scan taken at ``pose`` (x, y, yaw) end within OBSTACLE_REACH
    of the centre: on stage 3's turning obstacle, not on a wall."""
    x, y, yaw = pose
    ox, oy = x + SCAN_OFFSET * math.cos(yaw), y + SCAN_OFFSET * math.sin(yaw)
    angles = yaw + np.arange(24) * (6.28319 / 23)
    ex = ox + np.asarray(ranges) * np.cos(angles)
    ey = oy + np.asarray(ranges) * np.sin(angles)
    return np.hypot(ex, ey) < OBSTACLE_REACH


def noise_free_urdf() -> str:
    with open(os.path.join(ROOT, "urdf", "turtlebot3_burger.urdf")) as f:
        text = f.read()
    laser_noise = "<mean>0.0</mean>\n          <stddev>0.01</stddev>"
    assert text.count(laser_noise) == 1, "the burger URDF's laser noise moved"
    return text.replace(laser_noise, "<mean>0.0</mean>\n          <stddev>0.0</stddev>")


def plan_and_run_env(stage: int, plan=None):
    """Run StageEnv with the scripted policy, or the given ``plan``; the plan (None = reset, else
    an action) and rows."""
    env = StageEnv(stage)
    env.robot.laser = dataclasses.replace(env.robot.laser, noise_sigma=0.0)
    stepper = env
    rows = []
    if plan is not None:
        for entry in plan:
            if entry is None:
                obs, _ = stepper.reset(seed=SEEDS[stage]) if not rows else stepper.reset()
                rows.append(dict(entry=None, state=[float(v) for v in obs], reward=0.0,
                                 done=False, goal=False, pose=(0, 0, 0), obstacle=0.0,
                                 start=env._start_distance))
            else:
                obs, reward, done, _, info = stepper.step(entry)
                rows.append(dict(entry=entry, state=[float(v) for v in obs], reward=reward,
                                 done=done, goal=info["at_goal"], pose=(0, 0, 0), obstacle=0.0,
                                 start=env._start_distance))
        env.close()
        return plan, rows
    plan = []

    def obstacle_yaw():
        if stage != 3:
            return 0.0
        pose, _, _ = env.world.get_model_state("obstacle")
        return yaw_from_quat(pose[1])

    def pose():
        odom = env.robot.odom()
        return odom.position[0], odom.position[1], yaw_from_quat(odom.orientation)

    def record(entry, obs, reward, done, goal):
        rows.append(dict(entry=entry, state=[float(v) for v in obs], reward=reward, done=done,
                         goal=goal, pose=pose(), obstacle=obstacle_yaw(),
                         start=env._start_distance))

    obs, info = stepper.reset(seed=SEEDS[stage])
    plan.append(None)
    record(None, obs, 0.0, False, False)
    phases = [("steer", STEER_STEPS), ("straight", STRAIGHT_STEPS)]
    if stage == 1:
        phases.append(("steer", AFTER_RESET_STEPS))
    for phase, steps in phases:
        goals = 0
        for _ in range(steps):
            action = steer(obs[-4]) if phase == "steer" else 2
            obs, reward, done, _, info = stepper.step(action)
            plan.append(action)
            record(action, obs, reward, done, info["at_goal"])
            goals += info["at_goal"]
            if done or (phase == "steer" and goals >= GOALS_FIRST):
                break
        if done:
            if phase == "straight" and stage == 1:
                obs, info = stepper.reset()
                plan.append(None)
                record(None, obs, 0.0, False, False)
            else:
                break
    env.close()
    return plan, rows


class LearningEquivalence(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("test_learning_equivalence")
        cls.stage = int(rospy.get_param("~stage", 1))
        cls.rtf = float(rospy.get_param("~real_time_factor", 0.2))
        with open(os.path.join(ROOT, "models", "goal_box", "model.sdf")) as f:
            cls.goal_xml = f.read()
        cls.obstacle_yaw = 0.0
        cls.states_sub = rospy.Subscriber("/gazebo/model_states", ModelStates, cls._on_states)

    @classmethod
    def _on_states(cls, msg):
        if "obstacle" in msg.name:
            cls.obstacle_yaw = yaw_of(msg.pose[msg.name.index("obstacle")].orientation)

    def replace_robot_without_noise(self):
        rospy.wait_for_service("/gazebo/delete_model", 60)
        self.assertTrue(rospy.ServiceProxy("/gazebo/delete_model", DeleteModel)(ROBOT).success)
        resp = rospy.ServiceProxy("/gazebo/spawn_urdf_model", SpawnModel)(
            ROBOT, noise_free_urdf(), "", Pose(Point(0, 0, 0), Quaternion(0, 0, 0, 1)), "world")
        self.assertTrue(resp.success, resp.status_message)

    def run_ros(self, plan):
        env = Env(self.stage, 5, random.Random(SEEDS[self.stage]), self.goal_xml)
        rows = []
        obstacle = None

        def record(entry, state, reward, done, goal):
            odom = env.state_odom
            p = odom.pose.pose
            rows.append(dict(entry=entry, state=[float(v) for v in state], reward=reward,
                             done=done, goal=goal,
                             pose=(p.position.x, p.position.y, yaw_of(p.orientation)),
                             obstacle=self.obstacle_yaw, start=env.goal_distance,
                             stamp=env.last_scan.header.stamp.to_sec()))

        # the test's set-up, not the client's: a first command sent before the sim's subscriber
        # is connected is lost (ROBOTIS' agent starts long after its publisher)
        self.assertTrue(wait_for(lambda: env.pub_cmd_vel.get_num_connections() > 0, 30))
        try:
            for entry in plan:
                if entry is None:
                    state = env.reset()
                    record(None, state, 0.0, False, False)
                    if self.stage == 3 and obstacle is None:
                        obstacle = MovingObstacle(env.last_scan.header.stamp)
                        obstacle.start()
                else:
                    state, reward, done = env.step(entry)
                    record(entry, state, reward, done, env.last_goal_hit)
        finally:
            if obstacle is not None:
                obstacle.stop()
                # the obstacle's yaw at each scan: what the tick at that moment found
                for row in rows:
                    found = [yaw for due, yaw in obstacle.ticks
                             if abs(due - row["stamp"]) < 0.01]
                    row["obstacle"] = found[0] if found else math.nan
            env.pub_cmd_vel.publish(Twist())
        return rows

    def test_equivalence(self):
        wall0 = time.monotonic()
        plan, env_rows = plan_and_run_env(self.stage)
        env_wall = time.monotonic() - wall0
        self.replace_robot_without_noise()
        wall1 = time.monotonic()
        ros_rows = self.run_ros(plan)
        ros_wall = time.monotonic() - wall1
        self.report(plan, env_rows, ros_rows, env_wall, ros_wall)

    def report(self, plan, env_rows, ros_rows, env_wall, ros_wall):
        self.assertEqual(len(env_rows), len(ros_rows))
        goals = sum(r["goal"] for r in env_rows)
        collisions = sum(r["done"] for r in env_rows)
        worst = dict(scan=0.0, heading=0.0, distance=0.0, reward=0.0, pos=0.0, yaw=0.0,
                     obstacle=0.0, bound_margin=math.inf, obstacle_rays=0.0)
        failures = []
        for i, (e, r) in enumerate(zip(env_rows, ros_rows)):
            es, rs = np.array(e["state"]), np.array(r["state"])
            diffs = np.abs(es[:24] - rs[:24])
            if self.stage == 3:   # the obstacle's rays have their own bound (docstring)
                near = obstacle_rays(e["pose"], es[:24]) | obstacle_rays(r["pose"], rs[:24])
                if near.any():
                    worst["obstacle_rays"] = max(worst["obstacle_rays"],
                                                 float(np.max(diffs[near])))
                diffs = diffs[~near]
            scan_diff = float(np.max(diffs)) if diffs.size else 0.0
            dpos = math.hypot(e["pose"][0] - r["pose"][0], e["pose"][1] - r["pose"][1])
            dyaw = abs(math.remainder(e["pose"][2] - r["pose"][2], 2 * math.pi))
            # a reset's row has no tick (nan): its obstacle is at its start on both sides
            dobst = (abs(math.remainder(e["obstacle"] - r["obstacle"], 2 * math.pi))
                     if e["entry"] is not None else 0.0)
            worst["scan"] = max(worst["scan"], scan_diff)
            worst["pos"] = max(worst["pos"], dpos)
            worst["yaw"] = max(worst["yaw"], dyaw)
            worst["obstacle"] = max(worst["obstacle"], dobst)
            line = ("%3d %-5s scan %.4f heading %+.2f/%+.2f dist %.2f/%.2f reward %8.3f/%8.3f "
                    "done %d/%d goal %d/%d pos %.4f yaw %.4f obst %.4f"
                    % (i, e["entry"], scan_diff, es[24], rs[24], es[25], rs[25], e["reward"],
                       r["reward"], e["done"], r["done"], e["goal"], r["goal"], dpos, dyaw,
                       dobst))
            rospy.loginfo(line)
            print(line)
            if scan_diff > SCAN_TOL:
                failures.append("%d: scan differs by %.4f m" % (i, scan_diff))
            if e["done"] != r["done"] or e["goal"] != r["goal"]:
                failures.append("%d: done %s/%s goal %s/%s" % (i, e["done"], r["done"],
                                                               e["goal"], r["goal"]))
            if self.stage == 3 and e["entry"] is not None and not dobst <= OBSTACLE_YAW_TOL:
                failures.append("%d: obstacle yaw differs by %.4f rad" % (i, dobst))
            if e["entry"] is None:
                continue   # a reset's state: ROBOTIS' first heading is to the goal (0, 0)
            dh, dd = abs(es[24] - rs[24]), abs(es[25] - rs[25])
            worst["heading"] = max(worst["heading"], dh)
            worst["distance"] = max(worst["distance"], dd)
            dr = abs(e["reward"] - r["reward"])
            worst["reward"] = max(worst["reward"], dr)
            if dh > HEADING_TOL or dd > DISTANCE_TOL:
                failures.append("%d: heading %.2f/%.2f distance %.2f/%.2f"
                                % (i, es[24], rs[24], es[25], rs[25]))
            if e["done"] or e["goal"]:
                if e["reward"] != r["reward"]:
                    failures.append("%d: reward %s/%s" % (i, e["reward"], r["reward"]))
                continue
            a = dict(heading=es[24], distance=es[25], start=e["start"])
            b = dict(heading=rs[24], distance=rs[25], start=r["start"])
            bound = reward_bound(a, b)
            worst["bound_margin"] = min(worst["bound_margin"], bound - dr)
            if dr > bound:
                failures.append("%d: reward %.3f/%.3f differs by more than %.3f"
                                % (i, e["reward"], r["reward"], bound))
        summary = ("stage %d, factor %g: %d entries (%d steps), %d goals, %d collisions; max scan "
                   "difference %.4f m, heading %.2f, distance %.2f, reward %.3f (least margin to "
                   "its bound %.3f), pose %.4f m / %.4f rad, obstacle %.4f rad (its rays %.4f m); "
                   "StageEnv %.1f s, "
                   "ROS %.1f s wall"
                   % (self.stage, self.rtf, len(plan), sum(p is not None for p in plan), goals,
                      collisions, worst["scan"], worst["heading"], worst["distance"],
                      worst["reward"], worst["bound_margin"], worst["pos"], worst["yaw"],
                      worst["obstacle"], worst["obstacle_rays"], env_wall, ros_wall))
        rospy.loginfo(summary)
        print(summary)
        self.assertGreaterEqual(goals, 1)
        self.assertGreaterEqual(collisions, 1)
        self.assertFalse(failures, "\n".join(failures[:20]))


if __name__ == "__main__":
    rostest.rosrun("tutorial_turtlebot", "learning_equivalence", LearningEquivalence)
