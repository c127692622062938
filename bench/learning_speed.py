#!/usr/bin/env python3
"""Benchmark helper: the speed of the learning environments (learning/stage_env.py,
learning/vector.py), no ROS; run_bench.py's group "learning".

    learning_speed.py [SECONDS]      print every figure (about 10 x SECONDS of wall time)

Figures (env steps per wall second; each pair measured in interleaved rounds in one run, so
that a drift of the machine's speed falls on both alike):
  one env / bound   StageEnv(stage) stepped with seeded random actions (reset on a collision or
                    after 500 steps) against its physics bound: the same stage world, robot
                    and step size in bare pybullet replaying the env's very physics: its
                    wheel commands (the drive's velocities, or the brake) before the same
                    physics steps, the obstacles' ticks (stages 3, 4), one batch of the 24
                    rays per env step and the robot put back at its spawn where the env
                    reset; no Simulation, drive, observation or reward
  vector / one env  make_vector_env with one worker per core (K envs each, stepped in a batch
                    per call) against one StageEnv in this process
  coarse steps      StageEnv at time_step 0.005 and 0.01 s against 0.0025 s, and how far the
                    robot's final pose lies from the 0.0025 s one after 100 env steps of a
                    scripted policy (open field; and driving into a wall)
  render            ms per render() of a StageEnv with render_mode "rgb_array" (the top-down
                    picture; the Waffle Pi's camera) against ms per env step, a render after
                    each step (as Gymnasium's RecordVideo renders)
"""
import math
import os
import random
import sys
import time

import numpy as np
import pybullet

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, os.pardir, "src"))
sys.path.insert(0, os.path.join(HERE, os.pardir, "test"))
from process_helpers import cpu_seconds  # noqa: E402

from tutorial_turtlebot.learning import robotis_stages as rs  # noqa: E402
from tutorial_turtlebot.learning.stage_env import StageEnv  # noqa: E402

EPISODE = 500   # env steps before a reset (turtlebot3_dqn's episode)


class EnvRunner:
    """StageEnv stepped with seeded random actions, reset at a collision or after EPISODE."""

    def __init__(self, stage=1, time_step=0.0025, seed=0):
        self.env = StageEnv(stage, time_step=time_step)
        self.env.reset(seed=seed)
        self.rng = random.Random(seed)
        self.t = 0
        self._record_wheels()

    def _record_wheels(self):
        """Note each wheel command of the drive's ticks (velocities, or the brake) with the
        physics step it came before, for the bound to replay: the same physics."""
        robot = self.env.robot
        body = robot.body
        self._events, self._now = None, 0
        before_step, set_wheels, brake = (robot.before_step, body.set_wheel_velocities,
                                          body.brake)

        def noting_before_step(now_ns):
            self._now = now_ns
            before_step(now_ns)

        def noting_set_wheels(left, right):
            if self._events is not None:
                self._events.append((self._now, left, right))
            set_wheels(left, right)

        def noting_brake():
            if self._events is not None:
                self._events.append((self._now, None, None))
            brake()

        robot.before_step = noting_before_step
        body.set_wheel_velocities, body.brake = noting_set_wheels, noting_brake

    def run(self, steps):
        """``steps`` env steps; returns their log: per step (its wheel commands as (physics
        step within the env step, left, right; None, None for the brake), reset after it)."""
        env, rng, log = self.env, self.rng, []
        step_ns = env.sim.step_ns
        for _ in range(steps):
            action = rng.randrange(rs.ACTIONS)
            start, self._events = env.sim.time_ns, []
            _, _, terminated, _, _ = env.step(action)
            events = [((now - start) // step_ns, left, right)
                      for now, left, right in self._events]
            self._events = None
            self.t += 1
            reset = terminated or self.t >= EPISODE
            if reset:
                env.reset()
                self.t = 0
            log.append((events, reset))
        return log

    def close(self):
        self.env.close()


class BoundRunner:
    """The physics bound of an env step: bare pybullet on a StageEnv's world and robot."""

    def __init__(self, stage=1, time_step=0.0025, seed=0):
        self.env = StageEnv(stage, time_step=time_step)
        self.env.reset(seed=seed)
        robot = self.env.robot
        self.cid = robot.body.client
        self.body = robot.body
        self.uid = robot.body.robot
        self.wheels = robot.body.wheels
        self.ticks, self.tick_steps = self.env._ticks, self.env._tick_steps
        self.stage = stage
        self.movers = rs.obstacles(stage)
        self.models = [self.env.sim.models.get(m.name) for m in self.movers]
        self.rays = robot._rays
        self.laser_offset = robot._laser_pose[:3, 3]
        self.range_max = robot.laser.range_max
        self.range_min = robot.laser.range_min
        self.mask = robot.body.ray_mask
        self.nearest = math.inf

    def replay(self, log):
        """The env steps of ``log`` (EnvRunner.run's): the same wheel commands before the
        same physics steps, and a reset where the env reset."""
        cid, uid, body = self.cid, self.uid, self.body
        step, n = pybullet.stepSimulation, self.tick_steps
        movers = list(zip(self.movers, self.models))
        for events, reset in log:
            done, k, count = 0, 0, len(events)
            for tick in range(self.ticks):
                end = (tick + 1) * n
                while done < end:
                    while k < count and events[k][0] == done:
                        _, left, right = events[k]
                        if left is None:
                            body.brake()
                        else:
                            body.set_wheel_velocities(left, right)
                        k += 1
                        # (the drive's velocities, as RobotBody sets them)
                    until = min(events[k][0], end) if k < count else end
                    for _ in range(until - done):
                        step(physicsClientId=cid)
                    done = until
                for mover, model in movers:   # the obstacle nodes' ticks, as the env's
                    model.set_state(*mover.tick(model.pose()))
            pos, orn = pybullet.getBasePositionAndOrientation(uid, physicsClientId=cid)
            rot = np.array(pybullet.getMatrixFromQuaternion(orn)).reshape(3, 3)
            origin = np.array(pos) + rot @ self.laser_offset
            ends = origin + (self.rays @ rot.T) * self.range_max
            hits = pybullet.rayTestBatch([origin.tolist()] * len(ends), ends.tolist(),
                                         collisionFilterMask=self.mask, physicsClientId=cid)
            self.nearest = min(h[2] for h in hits) * self.range_max
            if reset:
                if movers:
                    self.env.sim.models.reset()
                    self.movers = rs.obstacles(self.stage)
                    movers = list(zip(self.movers, self.models))
                self.body.reset_robot()

    def close(self):
        self.env.close()


def interleaved(runners, seconds, rounds=4, chunk=20):
    """Steps per wall second of each runner (run(steps) methods), in ``rounds`` rounds of
    turns over ``seconds`` in all."""
    steps, wall = [0] * len(runners), [0.0] * len(runners)
    slot = seconds / (rounds * len(runners))
    for runner in runners:
        runner.run(chunk)   # warm
    for _ in range(rounds):
        for k, runner in enumerate(runners):
            t0 = time.perf_counter()
            while time.perf_counter() - t0 < slot:
                runner.run(chunk)
                steps[k] += chunk
            wall[k] += time.perf_counter() - t0
    return [s / w for s, w in zip(steps, wall)]


def env_and_bound(env, bound, seconds, rounds=6):
    """(steps/s of ``env`` (an EnvRunner), of ``bound`` (a BoundRunner) replaying the env's
    very steps): in each round the env runs for a slot, then the bound replays its log."""
    steps, wall = [0, 0], [0.0, 0.0]
    bound.replay(env.run(20))   # warm
    slot = seconds / (2 * rounds)
    for _ in range(rounds):
        t0, log = time.perf_counter(), []
        while time.perf_counter() - t0 < slot:
            log += env.run(10)
        wall[0] += time.perf_counter() - t0
        t0 = time.perf_counter()
        bound.replay(log)
        wall[1] += time.perf_counter() - t0
        steps[0] += len(log)
        steps[1] += len(log)
    return steps[0] / wall[0], steps[1] / wall[1]


def one_env_and_bound(stage=1, seconds=12.0, time_step=0.0025):
    """(env steps/s of one StageEnv, of its physics bound), interleaved."""
    env, bound = EnvRunner(stage, time_step), BoundRunner(stage, time_step)
    try:
        return env_and_bound(env, bound, seconds)
    finally:
        env.close()
        bound.close()


class VectorRunner:
    """A vector env stepped with seeded random actions; run(steps) counts env steps.
    ``workers`` 0: Gymnasium's AsyncVectorEnv (one process per env, in lockstep)."""

    def __init__(self, num_envs, workers=None, stage=1):
        import gymnasium
        from tutorial_turtlebot.learning.vector import make_vector_env
        env_id = "TurtleBot3Stage%d-v0" % stage
        if workers == 0:
            self.venv = gymnasium.vector.AsyncVectorEnv(
                [lambda: gymnasium.make(env_id)] * num_envs)
        else:
            self.venv = make_vector_env(env_id, num_envs, workers=workers)
        self.venv.reset(seed=0)
        self.n = num_envs
        self.rng = np.random.default_rng(0)

    def run(self, steps):
        for _ in range(max(1, steps // self.n)):
            self.venv.step(self.rng.integers(0, rs.ACTIONS, self.n))

    def close(self):
        self.venv.close()


def vector_and_one(num_envs=None, workers=None, seconds=12.0):
    """Env steps/s of the vector env with ``workers`` (default: one per core) and
    ``num_envs`` (default 4 per worker), and of one StageEnv in this process, interleaved; and
    env steps per CPU second of the workers and of the one env: how much of the gap to
    ``workers`` x is the machine's other load rather than the vector env's own cost: a dict
    {vector, one, async (Gymnasium's AsyncVectorEnv, one env per core): steps/s;
    vector_per_cpu, one_per_cpu: steps per CPU s; worker_cores: the workers' CPU s per wall s
    while they ran}."""
    workers = workers or os.cpu_count()
    num_envs = num_envs or 4 * workers
    vec, one, lockstep = (VectorRunner(num_envs, workers), EnvRunner(1),
                          VectorRunner(workers, workers=0))
    pids = vec.venv.pids
    runners = ((vec, num_envs), (one, 20), (lockstep, workers))

    def cpu(k):
        return sum(cpu_seconds(pid) for pid in pids) if k == 0 else cpu_seconds()

    try:
        steps, wall, used = [0, 0, 0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
        for runner, chunk in runners:
            runner.run(chunk)
        slot = seconds / 12
        for _ in range(4):
            for k, (runner, chunk) in enumerate(runners):
                t0, c0 = time.perf_counter(), cpu(k)
                while time.perf_counter() - t0 < slot:
                    runner.run(chunk)
                    steps[k] += chunk
                wall[k] += time.perf_counter() - t0
                used[k] += cpu(k) - c0
        return {"vector": steps[0] / wall[0], "one": steps[1] / wall[1],
                "async": steps[2] / wall[2],
                "vector_per_cpu": steps[0] / used[0], "one_per_cpu": steps[1] / used[1],
                "worker_cores": used[0] / wall[0]}
    finally:
        for runner, _ in runners:
            runner.close()


def coarse_speeds(time_steps=(0.0025, 0.005, 0.01), seconds=12.0):
    """{time_step: env steps/s} of stage 1, interleaved."""
    runners = [EnvRunner(1, ts) for ts in time_steps]
    try:
        return dict(zip(time_steps, interleaved(runners, seconds)))
    finally:
        for runner in runners:
            runner.close()


# scripted policies of 100 env steps from stage 1's spawn (facing +x)
OPEN_FIELD = [1] * 42 + [3] * 42 + [2] * 16   # a figure of eight, then straight: no contact
INTO_WALL = [2] * 100            # straight ahead: the wall after ~12 s, then pushing on it


def final_pose(time_step, actions):
    """(x, y, yaw) of base_footprint after ``actions``, and whether any step collided."""
    env = StageEnv(1, time_step=time_step)
    try:
        env.reset(seed=0)
        collided = False
        for action in actions:
            collided |= bool(env.step(action)[2])
        (x, y, _), orn = env.robot.ground_truth()
        return (x, y, pybullet.getEulerFromQuaternion(orn)[2]), collided
    finally:
        env.close()


def pose_differences(time_steps=(0.005, 0.01), reference=0.0025):
    """{policy name: {time_step: (position difference m, |yaw difference| rad)}} against
    ``reference``, with {policy name: collided at the reference step}."""
    out, contact = {}, {}
    for name, actions in (("open field", OPEN_FIELD), ("into a wall", INTO_WALL)):
        (rx, ry, ryaw), contact[name] = final_pose(reference, actions)
        out[name] = {}
        for ts in time_steps:
            (x, y, yaw), _ = final_pose(ts, actions)
            dyaw = abs(math.atan2(math.sin(yaw - ryaw), math.cos(yaw - ryaw)))
            out[name][ts] = (math.hypot(x - rx, y - ry), dyaw)
    return out, contact


def render_cost(stage=1, seconds=5.0, model="burger", camera=False, seed=0):
    """(ms per render() of StageEnv(stage, render_mode="rgb_array"), ms per env step): seeded
    random actions (reset at a collision or after EPISODE), a render after each step as
    Gymnasium's RecordVideo does, each timed alone; ``camera``: render_camera (the robot's
    camera image) instead of the top-down picture."""
    env = StageEnv(stage, model=model, render_mode="rgb_array", render_camera=camera)
    rng, clock = random.Random(seed), time.perf_counter
    try:
        env.reset(seed=seed)
        env.render()   # (the first frame draws the background)
        step_s = render_s = 0.0
        count = t = 0
        start = clock()
        while clock() - start < seconds:
            t0 = clock()
            terminated = env.step(rng.randrange(rs.ACTIONS))[2]
            t1 = clock()
            env.render()
            render_s += clock() - t1
            step_s += t1 - t0
            count, t = count + 1, t + 1
            if terminated or t >= EPISODE:
                env.reset()
                t = 0
        return 1000 * render_s / count, 1000 * step_s / count
    finally:
        env.close()


def main():
    seconds = float(sys.argv[1]) if len(sys.argv) > 1 else 12.0
    env, bound = one_env_and_bound(1, seconds)
    print("stage 1: one env %.1f steps/s, bound %.1f steps/s, ratio %.3f"
          % (env, bound, env / bound), flush=True)
    env, bound = one_env_and_bound(3, seconds)
    print("stage 3: one env %.1f steps/s, bound %.1f steps/s, ratio %.3f"
          % (env, bound, env / bound), flush=True)
    v = vector_and_one(seconds=seconds)
    print("vector (%d workers): %.1f steps/s, one env %.1f, ratio %.2f; per CPU s %.1f vs %.1f;"
          " the workers got %.2f cores; AsyncVectorEnv %.1f steps/s (%.2f)"
          % (os.cpu_count(), v["vector"], v["one"], v["vector"] / v["one"], v["vector_per_cpu"],
             v["one_per_cpu"], v["worker_cores"], v["async"], v["async"] / v["one"]), flush=True)
    speeds = coarse_speeds(seconds=seconds)
    print("time steps: " + ", ".join("%g s %.1f steps/s (%.2fx)" % (ts, v, v / speeds[0.0025])
                                     for ts, v in speeds.items()), flush=True)
    diffs, contact = pose_differences()
    for name, by_step in diffs.items():
        print("%s (contact at 0.0025: %s): " % (name, contact[name]) + ", ".join(
            "%g s: %.1f mm, %.2f mrad" % (ts, d * 1000, a * 1000)
            for ts, (d, a) in by_step.items()), flush=True)
    for label, model, camera in (("top-down", "burger", False),
                                 ("camera, waffle_pi", "waffle_pi", True)):
        render_ms, step_ms = render_cost(1, seconds / 2, model, camera)
        print("render() rgb_array (%s): %.2f ms, an env step %.2f ms (%.2f)"
              % (label, render_ms, step_ms, render_ms / step_ms), flush=True)


if __name__ == "__main__":
    main()
