"""The learning stages' vector environment (learning/vector): its spaces, seeds, both autoreset
modes, a worker's error, and that close() (or a Ctrl-C before it) leaves no process behind.
Real workers on the real simulator; no ROS."""
import importlib
import os
import signal
import sys

import numpy as np
import pytest

gymnasium = pytest.importorskip("gymnasium")   # tools/setup.sh installs it; the error says so

importlib.import_module("tutorial_turtlebot.learning")   # registers the ids
from tutorial_turtlebot.learning import robotis_stages as rs  # noqa: E402
from tutorial_turtlebot.learning.vector import make_vector_env  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir,
                                os.pardir))
from process_helpers import wait_for  # noqa: E402

STAGE_1 = "TurtleBot3Stage1-v0"


def gone(pids):
    """True once none of ``pids`` exists any more (reaped: not even a zombie)."""
    return not any(os.path.exists("/proc/%d" % pid) for pid in pids)


@pytest.fixture
def make():
    """Factory of vector envs, each closed at the end of the test."""
    made = []

    def factory(*args, **kwargs):
        venv = make_vector_env(*args, **kwargs)
        made.append(venv)
        return venv

    yield factory
    for venv in made:
        venv.close()


def test_spaces_batch_the_stage_envs(make):
    venv = make(STAGE_1, num_envs=3, workers=2)
    assert venv.num_envs == 3 and venv.workers == 2 and venv.sizes == [2, 1]
    assert venv.single_observation_space.shape == (rs.OBSERVATION_SIZE,)
    assert venv.single_action_space == gymnasium.spaces.Discrete(rs.ACTIONS)
    assert venv.observation_space.shape == (3, rs.OBSERVATION_SIZE)
    assert venv.action_space == gymnasium.spaces.MultiDiscrete([rs.ACTIONS] * 3)
    obs, infos = venv.reset(seed=0)
    assert obs.shape == (3, rs.OBSERVATION_SIZE) and obs.dtype == np.float32
    assert venv.observation_space.contains(obs)
    assert infos["_sim_time"].all() and (infos["sim_time"] == 0).all()
    obs, rewards, terminated, truncated, infos = venv.step([0, 2, 4])
    assert obs.shape == (3, rs.OBSERVATION_SIZE) and rewards.shape == (3,)
    assert terminated.dtype == bool and truncated.dtype == bool
    assert np.allclose(infos["sim_time"], rs.STEP_TIME)
    assert venv.metadata["autoreset_mode"] == gymnasium.vector.AutoresetMode.NEXT_STEP


def test_seeds_give_reproducible_observations_per_env(make):
    """reset(seed=s) seeds env i with s + i, as a lone env reset with that seed; the same seed
    and actions give the same observations again."""
    venv = make(STAGE_1, num_envs=3, workers=2)
    actions = [[0, 1, 2], [4, 3, 2], [2, 2, 2]]

    def rollout(seed):
        obs, _ = venv.reset(seed=seed)
        out = [obs]
        for action in actions:
            out.append(venv.step(action)[0])
        return np.stack(out)

    first, again = rollout(7), rollout(7)
    assert np.array_equal(first, again)
    lone = gymnasium.make(STAGE_1)
    try:
        for i in range(3):
            obs, _ = lone.reset(seed=7 + i)
            assert np.array_equal(obs, first[0, i])
            for k, action in enumerate(actions):
                obs = lone.step(action[i])[0]
                assert np.array_equal(obs, first[k + 1, i])
    finally:
        lone.close()
    other = rollout([7, 100, 9])
    assert np.array_equal(other[:, 0], first[:, 0]) and np.array_equal(other[:, 2], first[:, 2])


def test_next_step_autoreset(make):
    """Gymnasium 1.x's default: the step after an episode's end (here a TimeLimit of 3 steps)
    is that env's reset: its first observation, reward 0, neither terminated nor truncated."""
    venv = make(STAGE_1, num_envs=2, workers=2, max_episode_steps=3)
    first, _ = venv.reset(seed=1)
    for _ in range(2):
        _, _, terminated, truncated, _ = venv.step([2, 1])
        assert not terminated.any() and not truncated.any()
    obs, _, terminated, truncated, infos = venv.step([2, 1])
    assert truncated.all() and not terminated.any()
    assert "final_obs" not in infos and np.allclose(infos["sim_time"], 3 * rs.STEP_TIME)
    obs, rewards, terminated, truncated, infos = venv.step([2, 1])
    assert (rewards == 0).all() and not terminated.any() and not truncated.any()
    assert (infos["sim_time"] == 0).all()
    assert np.array_equal(obs[:, 24:], first[:, 24:])   # at the spawn again, the same goal
    _, _, _, _, infos = venv.step([2, 1])                  # and a new episode runs
    assert np.allclose(infos["sim_time"], rs.STEP_TIME)


def test_same_step_autoreset(make):
    venv = make(STAGE_1, num_envs=3, workers=2, max_episode_steps=2,
                autoreset_mode=gymnasium.vector.AutoresetMode.SAME_STEP)
    assert venv.metadata["autoreset_mode"] == gymnasium.vector.AutoresetMode.SAME_STEP
    first, _ = venv.reset(seed=1)
    venv.step([2, 2, 2])
    obs, _, terminated, truncated, infos = venv.step([2, 2, 2])
    assert truncated.all() and infos["_final_obs"].all()
    assert (infos["sim_time"] == 0).all()                  # the new episode's first obs
    assert np.allclose(infos["final_info"]["sim_time"], 2 * rs.STEP_TIME)
    assert np.array_equal(obs[:, 24:], first[:, 24:])
    assert not np.array_equal(np.stack(infos["final_obs"])[:, 24:], first[:, 24:])


def test_a_workers_error_is_raised_and_ends_the_workers(make):
    venv = make(STAGE_1, num_envs=2, workers=2)
    venv.reset(seed=0)
    pids = venv.pids
    with pytest.raises(RuntimeError, match="the actions are 0 to 4"):
        venv.step([0, 9])
    assert venv.closed and wait_for(lambda: gone(pids), 10.0)


def test_close_leaves_no_process(make):
    venv = make(STAGE_1, num_envs=4, workers=2)
    venv.reset(seed=0)
    pids = venv.pids
    assert len(pids) == 2 and not gone(pids)
    venv.close()
    assert gone(pids)   # ended and reaped, at once
    venv.close()        # a second close does nothing


def test_ctrl_c_does_not_reach_the_workers(make):
    """A Ctrl-C goes to the whole foreground process group: the workers ignore it, so the
    main process can still close them in order."""
    venv = make(STAGE_1, num_envs=2, workers=2)
    venv.reset(seed=0)
    pids = venv.pids
    for pid in pids:
        os.kill(pid, signal.SIGINT)
    obs = venv.step([2, 2])[0]
    assert obs.shape == (2, rs.OBSERVATION_SIZE)
    venv.close()
    assert gone(pids)


def test_ctrl_c_during_a_step_ends_the_workers(make, monkeypatch):
    """A KeyboardInterrupt while the answers are being read (half of them read) terminates the
    workers and goes on up."""
    venv = make(STAGE_1, num_envs=2, workers=2)
    venv.reset(seed=0)
    pids = venv.pids
    recv = type(venv._conns[1]).recv

    def interrupted(conn):
        if conn is venv._conns[1]:
            raise KeyboardInterrupt
        return recv(conn)

    monkeypatch.setattr(type(venv._conns[1]), "recv", interrupted)
    with pytest.raises(KeyboardInterrupt):
        venv.step([2, 2])
    monkeypatch.undo()
    assert venv.closed and wait_for(lambda: gone(pids), 10.0)
