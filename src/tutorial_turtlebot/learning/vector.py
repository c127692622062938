"""The learning stages as a Gymnasium vector environment: one worker process per core, each
holding several environments that it steps in a batch per call (doc/learning.md).

    from tutorial_turtlebot.learning.vector import make_vector_env
    envs = make_vector_env("TurtleBot3Stage1-v0", num_envs=8)      # workers: one per core
    obs, infos = envs.reset(seed=0)        # env i seeded with 0 + i
    obs, rewards, terminated, truncated, infos = envs.step(envs.action_space.sample())
    envs.close()

Why not gymnasium's AsyncVectorEnv: it keeps one process per environment and waits for all of
them at every step; pybullet holds the GIL while it steps, so a process is the unit of a core,
and with more environments than cores the processes (and the main one) fight over the cores
at every step. Here a worker steps its share of the environments one after the other and
answers once per batch: the main process does little more than send the actions and
concatenate the answers, and each core runs one worker flat out.

- ``autoreset_mode``: Gymnasium 1.x's ``AutoresetMode.NEXT_STEP`` by default (as
  AsyncVectorEnv, and learning.ray_actors' only mode): the step after one that ended an
  episode (terminated or truncated) resets that environment and returns its first
  observation, reward 0, terminated and truncated False (the action given for it is
  ignored). ``AutoresetMode.SAME_STEP``: the environment is
  reset in the step that ended it; that step returns the new first observation and puts the
  last one in ``infos["final_obs"]`` and its info in ``infos["final_info"]``.
- seeds: ``reset(seed=s)`` seeds environment i with ``s + i`` (a list: one seed each; None:
  unseeded); the same seed gives the same observations in every stage.
- infos: Gymnasium's vector form (each key an array over the environments, ``"_key"`` its
  mask).
- ``close()`` ends the workers (they also end when this process dies: their pipe closes);
  they ignore SIGINT, so a Ctrl-C reaches this process only: between calls close() shuts them
  down in order; during a call (its answers half read) the workers are terminated at once and
  the KeyboardInterrupt goes on. A worker's exception is raised here as a RuntimeError with
  its traceback, and ends the workers.
"""
import importlib
import multiprocessing
import os
import signal
import traceback
from typing import Any, Dict, List, Optional, Sequence, Union

import gymnasium
import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

CLOSE_TIMEOUT = 5.0   # s a worker has to end after "close" before it is terminated


class _InfoBatch:
    """Gymnasium's VectorEnv._add_info over ``num_envs`` environments (a worker's share)."""

    _add_info = VectorEnv._add_info

    def __init__(self, num_envs: int):
        self.num_envs = num_envs


def _worker(conn, parent_conn, env_id: str, count: int, env_kwargs: dict, same_step: bool):
    """A worker process: ``count`` environments of ``env_id``, driven over ``conn``."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)   # Ctrl-C is the main process's to handle
    if parent_conn is not None:
        parent_conn.close()
    envs: List[gymnasium.Env] = []
    try:
        # importing the package registers the stages (in a spawned process too)
        importlib.import_module("tutorial_turtlebot.learning")
        envs = [gymnasium.make(env_id, **env_kwargs) for _ in range(count)]
        conn.send(("ok", (envs[0].observation_space, envs[0].action_space)))
        done = np.zeros(count, dtype=bool)
        while True:
            try:
                command, data = conn.recv()
            except EOFError:   # the main process is gone
                break
            if command == "step":
                conn.send(("ok", _step(envs, data, done, same_step)))
            elif command == "reset":
                seeds, options = data
                infos, obs = _InfoBatch(count), []
                out: Dict[str, Any] = {}
                for i, (env, seed) in enumerate(zip(envs, seeds)):
                    o, info = env.reset(seed=seed, options=options)
                    obs.append(o)
                    out = infos._add_info(out, info, i)
                done[:] = False
                conn.send(("ok", (np.stack(obs), out)))
            elif command == "call":
                name, args, kwargs = data
                values = []
                for env in envs:
                    attr = getattr(env.unwrapped if name != "spec" else env, name)
                    values.append(attr(*args, **kwargs) if callable(attr) else attr)
                conn.send(("ok", values))
            elif command == "close":
                conn.send(("ok", None))
                break
            else:
                raise ValueError("unknown command %r" % (command,))
    except (KeyboardInterrupt, BrokenPipeError):
        pass
    except Exception:   # noqa: BLE001 - told to the main process, which raises it
        try:
            conn.send(("error", traceback.format_exc()))
        except (BrokenPipeError, OSError):
            pass
    finally:
        for env in envs:
            env.close()
        conn.close()


def _step(envs, actions, done, same_step: bool):
    """One batch step of a worker's environments, with the autoreset of its mode."""
    count = len(envs)
    obs = []
    rewards = np.zeros(count, dtype=np.float64)
    terminated = np.zeros(count, dtype=bool)
    truncated = np.zeros(count, dtype=bool)
    batch, infos = _InfoBatch(count), {}
    for i, env in enumerate(envs):
        if done[i]:   # NEXT_STEP: this step is the reset
            o, info = env.reset()
        else:
            o, rewards[i], terminated[i], truncated[i], info = env.step(actions[i])
            if same_step and (terminated[i] or truncated[i]):
                infos = batch._add_info(infos, {"final_obs": o, "final_info": info}, i)
                o, info = env.reset()
        obs.append(o)
        infos = batch._add_info(infos, info, i)
    if not same_step:
        done[:] = terminated | truncated
    return np.stack(obs), rewards, terminated, truncated, infos


def _merge_infos(parts: Sequence[Dict[str, Any]], sizes: Sequence[int]) -> Dict[str, Any]:
    """The workers' info batches as one over every environment (Gymnasium's vector form)."""
    keys: List[str] = []
    for part in parts:
        keys.extend(k for k in part if k not in keys)
    out: Dict[str, Any] = {}
    for key in keys:
        if key.startswith("_") and key[1:] in keys:
            continue   # a mask: made with its key
        present = [part for part in parts if key in part]
        if isinstance(present[0][key], dict):
            out[key] = _merge_infos([part.get(key, {}) for part in parts], sizes)
        else:
            template = present[0][key]
            arrays = [part[key] if key in part
                      else np.zeros((size,) + template.shape[1:], dtype=template.dtype)
                      if template.dtype != object else np.full(size, None, dtype=object)
                      for part, size in zip(parts, sizes)]
            out[key] = np.concatenate(arrays)
        mask = "_" + key
        out[mask] = np.concatenate([part[mask] if mask in part else np.zeros(size, dtype=bool)
                                    for part, size in zip(parts, sizes)])
    return out


class StageVectorEnv(VectorEnv):
    """``num_envs`` environments of ``env_id`` in ``workers`` processes (default: one per core,
    at most one per environment), each stepping its share in one batch per call."""

    def __init__(self, env_id: str, num_envs: int, workers: Optional[int] = None,
                 autoreset_mode: Union[AutoresetMode, str] = AutoresetMode.NEXT_STEP,
                 context: Optional[str] = None, **env_kwargs):
        if num_envs < 1:
            raise ValueError("num_envs must be at least 1, got %r" % (num_envs,))
        mode = AutoresetMode(autoreset_mode)
        if mode not in (AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP):
            raise ValueError("autoreset_mode %s: NEXT_STEP and SAME_STEP are supported" % mode)
        workers = min(workers or os.cpu_count() or 1, num_envs)
        if workers < 1:
            raise ValueError("workers must be at least 1, got %r" % (workers,))
        self.closed = True   # until the workers run: close() has nothing to do
        self.env_id, self.num_envs = env_id, num_envs
        self.autoreset_mode = mode
        self.metadata = {"autoreset_mode": mode, "render_modes": []}
        self.render_mode = None
        self.spec = gymnasium.spec(env_id) if env_id in gymnasium.registry else None
        self.sizes = [num_envs // workers + (1 if k < num_envs % workers else 0)
                      for k in range(workers)]
        self.starts = np.cumsum([0] + self.sizes[:-1]).tolist()
        ctx = multiprocessing.get_context(context)
        self._conns, self._processes = [], []
        self.closed = False
        try:
            for size in self.sizes:
                parent, child = ctx.Pipe()
                process = ctx.Process(
                    target=_worker, name="StageVectorEnv worker", daemon=True,
                    args=(child, parent, env_id, size, env_kwargs,
                          mode is AutoresetMode.SAME_STEP))
                process.start()
                child.close()
                self._conns.append(parent)
                self._processes.append(process)
            spaces = self._receive_all()
        except BaseException:
            self.close(terminate=True)
            raise
        self.single_observation_space, self.single_action_space = spaces[0]
        self.observation_space = batch_space(self.single_observation_space, num_envs)
        self.action_space = batch_space(self.single_action_space, num_envs)

    @property
    def workers(self) -> int:
        return len(self._processes)

    @property
    def pids(self) -> List[int]:
        """The workers' process ids."""
        return [p.pid for p in self._processes]

    # --- Gymnasium ---------------------------------------------------------------------------

    def reset(self, *, seed: Optional[Union[int, Sequence[Optional[int]]]] = None,
              options: Optional[dict] = None):
        if seed is None:
            seeds = [None] * self.num_envs
        elif isinstance(seed, (int, np.integer)):
            seeds = [int(seed) + i for i in range(self.num_envs)]
        else:
            seeds = list(seed)
            if len(seeds) != self.num_envs:
                raise ValueError("%d seeds for %d environments" % (len(seeds), self.num_envs))
        if seed is not None:
            self._np_random, self._np_random_seed = gymnasium.utils.seeding.np_random(seeds[0])
        for conn, start, size in zip(self._conns, self.starts, self.sizes):
            conn.send(("reset", (seeds[start:start + size], options)))
        answers = self._receive_all()
        obs = np.concatenate([a[0] for a in answers])
        return obs, _merge_infos([a[1] for a in answers], self.sizes)

    def step(self, actions):
        actions = np.asarray(actions)
        if len(actions) != self.num_envs:
            raise ValueError("%d actions for %d environments" % (len(actions), self.num_envs))
        for conn, start, size in zip(self._conns, self.starts, self.sizes):
            conn.send(("step", actions[start:start + size]))
        answers = self._receive_all()
        return (np.concatenate([a[0] for a in answers]), np.concatenate([a[1] for a in answers]),
                np.concatenate([a[2] for a in answers]), np.concatenate([a[3] for a in answers]),
                _merge_infos([a[4] for a in answers], self.sizes))

    def call(self, name: str, *args, **kwargs) -> tuple:
        """Each environment's ``name`` (of its unwrapped env): called with the arguments if it
        is a method, else its value."""
        for conn in self._conns:
            conn.send(("call", (name, args, kwargs)))
        return tuple(v for values in self._receive_all() for v in values)

    def get_attr(self, name: str) -> tuple:
        return self.call(name)

    def close_extras(self, terminate: bool = False, **kwargs) -> None:
        """End the workers: asked to, then terminated (and killed) if they do not in time."""
        for conn in self._conns:
            if not terminate:
                try:
                    conn.send(("close", None))
                except (BrokenPipeError, OSError):
                    pass
        for process in self._processes:
            process.join(0.0 if terminate else CLOSE_TIMEOUT)
            if process.is_alive():
                process.terminate()
                process.join(CLOSE_TIMEOUT)
            if process.is_alive():
                process.kill()
                process.join()
        for conn in self._conns:
            conn.close()
        self._conns, self._processes = [], []

    def close(self, **kwargs) -> None:
        if getattr(self, "closed", True):
            return
        self.close_extras(**kwargs)
        self.closed = True

    def __del__(self):
        try:
            self.close(terminate=True)
        except Exception:   # noqa: BLE001 - at interpreter exit, anything may be gone
            pass

    # --- the workers -------------------------------------------------------------------------

    def _receive_all(self) -> list:
        """Each worker's answer, in order; RuntimeError with a worker's traceback if it
        failed (the workers are then closed), or if one died. A Ctrl-C while waiting ends the
        workers (their answers are half read) and goes on up."""
        answers, error = [], None
        try:
            for conn, process in zip(self._conns, self._processes):
                try:
                    status, value = conn.recv()
                except (EOFError, ConnectionResetError):
                    status, value = "error", "worker %d ended (exit code %s)" % (
                        process.pid, process.exitcode)
                if status == "error":
                    error = error or value
                answers.append(value)
        except KeyboardInterrupt:   # answers half read: the workers cannot be trusted now
            self.close(terminate=True)
            raise
        if error is not None:
            self.close(terminate=True)
            raise RuntimeError("a StageVectorEnv worker failed:\n%s" % error)
        return answers


def make_vector_env(env_id: str = "TurtleBot3Stage1-v0", num_envs: int = 8,
                    workers: Optional[int] = None,
                    autoreset_mode: Union[AutoresetMode, str] = AutoresetMode.NEXT_STEP,
                    context: Optional[str] = None, **env_kwargs) -> StageVectorEnv:
    """A StageVectorEnv: ``num_envs`` environments made by gymnasium.make(env_id,
    **env_kwargs), ``workers`` processes (default: one per core), ``context`` a
    multiprocessing start method (default: the platform's)."""
    return StageVectorEnv(env_id, num_envs, workers, autoreset_mode, context, **env_kwargs)
