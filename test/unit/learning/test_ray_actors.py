"""The Ray actors' stepping (learning/ray_actors) without Ray: NextStepAutoreset, Gymnasium
1.x's NEXT_STEP autoreset, on scripted environments and beside learning/vector's, and
StageActorBody (what one actor holds) on the real stage 1. No ROS, no Ray (the unit tests stay
free of it: node_id, the one method that needs it, is not called)."""
import importlib
import inspect

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")   # tools/setup.sh installs it

importlib.import_module("tutorial_turtlebot.learning")   # registers the ids
from tutorial_turtlebot.learning import vector  # noqa: E402
from tutorial_turtlebot.learning.ray_actors import (  # noqa: E402
    AUTORESET_MODE, NextStepAutoreset, StageActorBody)

SCRIPTED_ID = "RayActorsTestScripted-v0"


class ScriptedEnv(gymnasium.Env):
    """An episode of ``length`` steps that ends terminated (or truncated). The observation is
    (episode number, step in the episode, last action); the reward is the step's number; a
    step whose number is ``goal_step`` is at the goal."""

    observation_space = gymnasium.spaces.Box(-1.0, 1e3, shape=(3,), dtype=np.float32)
    action_space = gymnasium.spaces.Discrete(5)

    def __init__(self, length=2, truncate=False, goal_step=None):
        self.length, self.truncate, self.goal_step = length, truncate, goal_step
        self.episode, self.step_number, self.actions = -1, 0, []

    def reset(self, *, seed=None, options=None):
        super().reset(seed=seed)
        self.episode, self.step_number = self.episode + 1, 0
        return self._obs(-1), {"at_goal": False}

    def step(self, action):
        self.actions.append(int(action))
        self.step_number += 1
        ended = self.step_number >= self.length
        info = {"at_goal": self.step_number == self.goal_step}
        return (self._obs(action), float(self.step_number), ended and not self.truncate,
                ended and self.truncate, info)

    def _obs(self, action):
        return np.array([self.episode, self.step_number, action], dtype=np.float32)


def test_the_step_after_an_episodes_end_returns_the_next_episodes_first_observation():
    ending = ScriptedEnv(length=2, goal_step=1)            # terminated at its 2nd step
    timed_out = ScriptedEnv(length=3, truncate=True)       # truncated at its 3rd
    stepper = NextStepAutoreset([ending, timed_out])
    first = stepper.reset()
    assert first.tolist() == [[0, 0, -1], [0, 0, -1]]
    steps = [stepper.step([a, a + 1]) for a in range(5)]
    obs = np.stack([s[0] for s in steps])
    rewards, terminated, truncated, at_goal = (np.stack([s[k] for s in steps])
                                               for k in (1, 2, 3, 4))
    # env 0: steps 1, 2 (terminated), its reset, steps 1, 2 (terminated)
    assert obs[:, 0].tolist() == [[0, 1, 0], [0, 2, 1], [1, 0, -1], [1, 1, 3], [1, 2, 4]]
    assert rewards[:, 0].tolist() == [1, 2, 0, 1, 2]
    assert terminated[:, 0].tolist() == [False, True, False, False, True]
    assert at_goal[:, 0].tolist() == [True, False, False, True, False]
    assert ending.actions == [0, 1, 3, 4]                  # the reset step's action 2 ignored
    # env 1: steps 1, 2, 3 (truncated), its reset, step 1
    assert obs[:, 1].tolist() == [[0, 1, 1], [0, 2, 2], [0, 3, 3], [1, 0, -1], [1, 1, 5]]
    assert truncated[:, 1].tolist() == [False, False, True, False, False]
    assert not truncated[:, 0].any() and not terminated[:, 1].any()
    assert rewards[3, 1] == 0 and timed_out.actions == [1, 2, 3, 5]


def test_the_mode_is_gymnasiums_next_step_as_the_vector_envs_default():
    mode = gymnasium.vector.AutoresetMode(AUTORESET_MODE)
    assert mode is gymnasium.vector.AutoresetMode.NEXT_STEP
    assert inspect.signature(vector.make_vector_env).parameters["autoreset_mode"].default is mode


def test_a_reset_clears_a_pending_autoreset():
    env = ScriptedEnv(length=1)
    stepper = NextStepAutoreset([env])
    stepper.reset()
    assert stepper.step([0])[2].tolist() == [True]
    assert stepper.reset().tolist() == [[1, 0, -1]]        # reset by hand instead
    assert stepper.step([4])[0].tolist() == [[1, 1, 4]]    # a real step: no second reset


def test_same_as_the_vector_envs_next_step():
    """learning/vector's worker step in NEXT_STEP mode gives the same observations, rewards
    and flags on the same scripted environments."""
    def envs():
        return [ScriptedEnv(length=2), ScriptedEnv(length=3, truncate=True), ScriptedEnv(4)]

    stepper = NextStepAutoreset(envs())
    stepper.reset()
    theirs = envs()
    for env in theirs:
        env.reset()
    done = np.zeros(len(theirs), dtype=bool)
    actions = np.random.default_rng(0).integers(0, 5, size=(9, len(theirs)))
    for step_actions in actions:
        ours = stepper.step(step_actions)
        obs, rewards, terminated, truncated, _ = vector._step(theirs, step_actions, done, False)
        for mine, their in zip(ours[:4], (obs, rewards, terminated, truncated)):
            assert np.array_equal(mine, their)


@pytest.fixture
def scripted_id():
    gymnasium.register(SCRIPTED_ID, entry_point=ScriptedEnv)
    yield SCRIPTED_ID
    del gymnasium.registry[SCRIPTED_ID]


def test_an_actor_resets_across_calls(scripted_id):
    """An episode that a call's last step ends is reset by the next call's first step, in
    step and rollout alike; the policy sees what the last step returned."""
    body = StageActorBody(scripted_id, 1, {"length": 2})
    try:
        body.reset(seeds=[0])
        out = body.step([[1], [2]])
        assert out["terminated"][:, 0].tolist() == [False, True]
        seen = []
        out = body.rollout(lambda obs: seen.append(obs.copy()) or [3], steps=2)
        assert out["observations"][:, 0].tolist() == [[1, 0, -1], [1, 1, 3]]
        assert out["rewards"][:, 0].tolist() == [0, 1]
        assert [s.tolist() for s in seen] == [[[0, 2, 2]], [[1, 0, -1]]]
    finally:
        body.close()


def test_an_actor_on_stage_1_returns_what_a_lone_env_gives():
    """Two real stage 1 envs with a 2-step limit: the step after the truncation returns the
    new episode's first observation, the one a lone env seeded alike gives at its reset."""
    body = StageActorBody("TurtleBot3Stage1-v0", 2, {"max_episode_steps": 2})
    lone = gymnasium.make("TurtleBot3Stage1-v0", max_episode_steps=2)
    try:
        body.reset(seeds=[5, 6])
        first = body.step([[0, 4], [1, 2]])                # ends both episodes
        assert first["truncated"][1].all()
        then = body.step([[2, 2]])                         # their resets
        assert not then["truncated"].any() and (then["rewards"] == 0).all()
        for k, (seed, actions) in enumerate(((5, (0, 1)), (6, (4, 2)))):
            lone.reset(seed=seed)
            for index, action in enumerate(actions):
                assert np.array_equal(lone.step(action)[0], first["observations"][index, k])
            expected, info = lone.reset()
            assert info["sim_time"] == 0.0
            assert np.array_equal(then["observations"][0, k], expected)
    finally:
        body.close()
        lone.close()
