"""ROBOTIS' learning stages on Ray actors, on one machine or a cluster (doc/learning.md).

Each actor holds ``envs_per_actor`` StageEnvs (learning.stage_env, through gymnasium.make so
that the 501-step limit applies) and steps them in batches: one remote call runs K envs for
M steps, since one call per env step costs more than the step.

Autoreset: Gymnasium 1.x's ``AutoresetMode.NEXT_STEP``, the default of its vector envs and of
learning.vector's: the step after one that ended an env's episode (terminated or truncated)
resets that env instead of stepping it, and returns the next episode's first observation with
reward 0 and terminated, truncated and at_goal False; the action given for it is ignored. This
holds across calls (an episode ended by a batch's last step is reset by the next batch's first)
and in step_batch and rollout alike (NextStepAutoreset).

    from tutorial_turtlebot.learning.ray_actors import RayStageRunner
    with RayStageRunner("TurtleBot3Stage1-v0", actors=2, envs_per_actor=4,
                        address="auto") as runner:          # or None: a Ray on this machine
        first = runner.reset(seed=0)                        # (8, 28) observations
        batch = runner.step_batch(np.random.randint(0, 5, size=(50, 8)))
        batch = runner.rollout(lambda obs: np.full(len(obs), 2), steps=50)
        batch.node_ids                                      # the Ray node of each env

``address`` is passed to ``ray.init``: None starts Ray in this process' machine (or joins
the cluster that RAY_ADDRESS names), "auto" joins the cluster that ``ray start`` made here,
"ray://HOST:10001" a remote one. Every node needs this package importable by its workers
(source the catkin workspace before ``ray start``) and the same Python and Ray versions.

Ray is an optional extra, imported only when a runner is made: ``bash tools/install_extra.sh
ray`` installs it. Units: an environment step is 0.2 s of sim time; observations are metres
and radians as StageEnv's; times in the batches are wall-clock seconds.
"""
import collections
import importlib
import time
from typing import Callable, Dict, List, Optional, Sequence

import numpy as np

INSTALL_HINT = "Ray is not installed: run 'bash tools/install_extra.sh ray' (the ray extra)"
AUTORESET_MODE = "NextStep"   # the value of gymnasium.vector.AutoresetMode.NEXT_STEP: the only one

Batch = collections.namedtuple("Batch", [
    "observations",   # (M, N, 28) float32: each env's observation after each step (NEXT_STEP:
                      #   the step after an episode's end gives the next episode's first)
    "rewards",        # (M, N) float64: ROBOTIS' reward of each step (0 at a reset step)
    "terminated",     # (M, N) bool: a collision ended the episode (the env's next step resets it)
    "truncated",      # (M, N) bool: the 501-step limit ended it (the env's next step resets it)
    "at_goal",        # (M, N) bool: the step reached the goal (the next goal follows)
    "node_ids",       # N str: the Ray node id of the actor that holds each env
    "actor_ids",      # N int: the actor (0 .. actors-1) that holds each env
    "wall_s",         # actors floats: wall-clock seconds each actor spent stepping
])


def import_ray():
    """The ray module, or ImportError with one line saying how to install it. (Imported by
    name: Ray is an extra, not one of package.xml's dependencies.)"""
    try:
        return importlib.import_module("ray")
    except ImportError:
        raise ImportError(INSTALL_HINT) from None


class NextStepAutoreset:
    """K environments stepped together with Gymnasium 1.x's NEXT_STEP autoreset (as
    learning.vector's StageVectorEnv by default): an env whose last step ended its episode
    (terminated or truncated) is reset at its next step, which returns that reset's observation,
    reward 0, terminated, truncated and at_goal False, and ignores the action. Plain Python: the
    Ray actor (StageActorBody) holds one."""

    def __init__(self, envs: Sequence):
        self.envs = list(envs)
        self.observations: Optional[np.ndarray] = None    # (K, 28): each env's latest one
        self.ended = np.zeros(len(self.envs), dtype=bool)  # its last step ended its episode

    def reset(self, seeds: Optional[Sequence[Optional[int]]] = None) -> np.ndarray:
        """Reset every env (seed i to env i; None keeps its goal sequence): (K, 28)."""
        seeds = list(seeds) if seeds is not None else [None] * len(self.envs)
        if len(seeds) != len(self.envs):
            raise ValueError("%d seeds for %d environments" % (len(seeds), len(self.envs)))
        self.observations = np.stack([env.reset(seed=seed)[0]
                                      for env, seed in zip(self.envs, seeds)])
        self.ended[:] = False
        return self.observations.copy()

    def step(self, actions: Sequence[int]):
        """One step of every env (K actions): (observations (K, 28), rewards (K,), terminated,
        truncated, at_goal (K,) bools), an ended env reset instead of stepped."""
        if self.observations is None:
            self.reset()
        count = len(self.envs)
        rewards = np.zeros(count)
        terminated = np.zeros(count, dtype=bool)
        truncated = np.zeros(count, dtype=bool)
        at_goal = np.zeros(count, dtype=bool)
        for k, env in enumerate(self.envs):
            if self.ended[k]:
                obs, _ = env.reset()
            else:
                obs, rewards[k], terminated[k], truncated[k], info = env.step(int(actions[k]))
                at_goal[k] = bool(info.get("at_goal"))
            self.observations[k] = obs
        self.ended = terminated | truncated
        return self.observations.copy(), rewards, terminated, truncated, at_goal


class StageActorBody:
    """What one Ray actor holds: ``count`` environments of ``env_id`` in one process.

    Made remote by RayStageRunner (``ray.remote(StageActorBody)``); usable directly too."""

    def __init__(self, env_id: str, count: int, env_kwargs: Optional[dict] = None):
        import gymnasium
        importlib.import_module("tutorial_turtlebot.learning")  # registers the stage ids

        self.envs = [gymnasium.make(env_id, **(env_kwargs or {})) for _ in range(count)]
        self.stepper = NextStepAutoreset(self.envs)

    def node_id(self) -> str:
        """The id of the Ray node this actor runs on."""
        return import_ray().get_runtime_context().get_node_id()

    def reset(self, seeds: Optional[Sequence[Optional[int]]] = None) -> np.ndarray:
        """Reset every env (seed i to env i; None keeps its goal sequence): (K, 28)."""
        return self.stepper.reset(seeds)

    def step(self, actions) -> Dict[str, np.ndarray]:
        """Step each env with ``actions`` (M, K): M steps of the K envs, in one call."""
        actions = np.asarray(actions, dtype=np.int64)
        return self._run(actions.shape[0], lambda index, obs: actions[index])

    def rollout(self, policy: Callable[[np.ndarray], Sequence[int]], steps: int):
        """``steps`` steps, the actions from ``policy`` (K, 28) -> (K,) at each step, given the
        observations the last step returned (an ended episode's last: its reset comes next)."""
        return self._run(steps, lambda index, obs: policy(obs))

    def _run(self, steps: int, choose) -> Dict[str, np.ndarray]:
        """``steps`` steps of the K envs, the actions from ``choose(index, observations)``."""
        if self.stepper.observations is None:
            self.stepper.reset()
        started = time.monotonic()
        count = len(self.envs)
        shape = (steps, count)
        out = {"observations": np.zeros(shape + self.stepper.observations.shape[1:],
                                        dtype=np.float32),
               "rewards": np.zeros(shape), "terminated": np.zeros(shape, dtype=bool),
               "truncated": np.zeros(shape, dtype=bool), "at_goal": np.zeros(shape, dtype=bool)}
        observations = self.stepper.observations.copy()
        for index in range(steps):
            actions = np.asarray(choose(index, observations)).reshape(count)
            step = self.stepper.step(actions)
            for key, value in zip(("observations", "rewards", "terminated", "truncated",
                                   "at_goal"), step):
                out[key][index] = value
            observations = step[0]
        out["wall_s"] = time.monotonic() - started
        return out

    def close(self) -> None:
        for env in self.envs:
            env.close()
        self.envs = []


class RayStageRunner:
    """``actors`` Ray actors with ``envs_per_actor`` environments each, stepped in batches.

    ``address``: where ray.init connects (None: start or find Ray here; "auto"; "ray://...").
    ``cpus_per_actor``: the CPUs Ray reserves for each actor (one simulator is one core).
    ``spread``: place the actors on as many nodes as Ray can (its SPREAD strategy).
    ``init_kwargs``: more ray.init arguments, used only when this runner starts Ray here.
    Envs are numbered actor by actor: env ``a * envs_per_actor + k`` is env k of actor a.
    """

    def __init__(self, env_id: str = "TurtleBot3Stage1-v0", actors: int = 2,
                 envs_per_actor: int = 4, address: Optional[str] = None,
                 env_kwargs: Optional[dict] = None, cpus_per_actor: float = 1.0,
                 spread: bool = True, init_kwargs: Optional[dict] = None):
        if actors < 1 or envs_per_actor < 1:
            raise ValueError("actors %r, envs_per_actor %r: both must be at least 1"
                             % (actors, envs_per_actor))
        ray = import_ray()
        self._ray = ray
        self._started_ray = False
        if not ray.is_initialized():
            kwargs = {"address": address, "ignore_reinit_error": True,
                      "log_to_driver": False}
            if address is None:
                kwargs.update({"include_dashboard": False})
                kwargs.update(init_kwargs or {})
            ray.init(**kwargs)
            self._started_ray = True
        self.env_id = env_id
        self.envs_per_actor = envs_per_actor
        options = {"num_cpus": cpus_per_actor}
        if spread:
            options["scheduling_strategy"] = "SPREAD"
        remote_class = ray.remote(StageActorBody).options(**options)
        self.actors = [remote_class.remote(env_id, envs_per_actor, env_kwargs)
                       for _ in range(actors)]
        actor_nodes = ray.get([actor.node_id.remote() for actor in self.actors])
        self.node_ids = [node for node in actor_nodes for _ in range(envs_per_actor)]
        self.actor_ids = [a for a in range(actors) for _ in range(envs_per_actor)]

    @property
    def num_envs(self) -> int:
        """N: all the environments of all the actors."""
        return len(self.node_ids)

    def reset(self, seed: Optional[int] = None) -> np.ndarray:
        """Reset every env; with ``seed``, env i gets seed + i. Returns (N, 28)."""
        k = self.envs_per_actor
        calls = [actor.reset.remote(None if seed is None else
                                    [seed + a * k + i for i in range(k)])
                 for a, actor in enumerate(self.actors)]
        return np.concatenate(self._ray.get(calls))

    def step_batch(self, actions) -> Batch:
        """Step every env with ``actions``: (M, N) ints 0..4 (or (N,) for one step), in one
        remote call per actor. NEXT_STEP autoreset: the step after one that ended an env's
        episode resets it and returns the next episode's first observation (reward 0, the
        flags False, its action ignored), in this batch or the next."""
        actions = np.asarray(actions, dtype=np.int64)
        if actions.ndim == 1:
            actions = actions[None, :]
        if actions.ndim != 2 or actions.shape[1] != self.num_envs:
            raise ValueError("actions of shape %s: expected (steps, %d)"
                             % (actions.shape, self.num_envs))
        k = self.envs_per_actor
        calls = [actor.step.remote(actions[:, a * k:(a + 1) * k])
                 for a, actor in enumerate(self.actors)]
        return self._gather(self._ray.get(calls))

    def rollout(self, policy: Callable[[np.ndarray], Sequence[int]], steps: int) -> Batch:
        """``steps`` steps of every env, each actor choosing its actions with ``policy``
        ((K, 28) observations -> K actions; pickled to the actors, so it must not hold
        locks or open files). The same NEXT_STEP autoreset as step_batch."""
        calls = [actor.rollout.remote(policy, steps) for actor in self.actors]
        return self._gather(self._ray.get(calls))

    def _gather(self, parts: List[dict]) -> Batch:
        def joined(key):
            return np.concatenate([part[key] for part in parts], axis=1)
        return Batch(joined("observations"), joined("rewards"), joined("terminated"),
                     joined("truncated"), joined("at_goal"), list(self.node_ids),
                     list(self.actor_ids), [part["wall_s"] for part in parts])

    def close(self) -> None:
        """End the actors (and Ray, when this runner started it)."""
        for actor in self.actors:
            try:
                self._ray.get(actor.close.remote(), timeout=30)
            except Exception:   # an actor already gone: nothing to close
                pass
            self._ray.kill(actor)
        self.actors = []
        if self._started_ray:
            self._ray.shutdown()
            self._started_ray = False

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
