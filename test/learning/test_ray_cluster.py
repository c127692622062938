"""RayStageRunner on a Ray cluster of two nodes started on this machine (doc/learning.md).

Not a unit test (Ray starts in 4 to 15 s, and is an optional extra): run it on its own,

    source catkin_ws/devel/setup.bash && python3 -m pytest -s test/learning/test_ray_cluster.py

It installs the ray extra on first use (bash tools/install_extra.sh ray), and skips, with one
line, only when PyPI is unreachable. It starts a head node and a second node (each one CPU,
so that Ray must place one actor on each), steps two actors of two StageEnvs each in batches,
and checks that steps came back from both nodes, and that the step after an episode's end
returns the next episode's first observation (NEXT_STEP autoreset), the one a lone env seeded
alike gives. It prints how long the cluster took to start and the stepping rate.
"""
import importlib
import os
import sys
import time

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from extras import ensure_extra  # noqa: E402

STEPS = 20              # environment steps per env per batch
ENVS_PER_ACTOR = 2


def say(capsys, text):
    """A line on the terminal, also without pytest -s."""
    with capsys.disabled():
        sys.stdout.write("\n" + text + "\n")


def ensure_ray():
    """Ray, installed first if missing."""
    return ensure_extra("ray", "ray", timeout=900)


@pytest.fixture(scope="module")
def cluster(request):
    ray = ensure_ray()
    Cluster = importlib.import_module("ray.cluster_utils").Cluster

    started = time.monotonic()
    node_args = {"num_cpus": 1, "object_store_memory": 80 * 1024 * 1024}
    cluster = Cluster(initialize_head=True,
                      head_node_args=dict(node_args, include_dashboard=False))
    cluster.add_node(**node_args)
    cluster.wait_for_nodes()
    ray.init(address=cluster.address, log_to_driver=False)
    cluster.start_seconds = time.monotonic() - started
    yield cluster
    ray.shutdown()
    cluster.shutdown()


def test_steps_come_back_from_both_nodes(cluster, capsys):
    ray = importlib.import_module("ray")
    from tutorial_turtlebot.learning.ray_actors import RayStageRunner

    say(capsys, "ray cluster of 2 nodes started in %.1f s" % cluster.start_seconds)
    nodes = {node["NodeID"] for node in ray.nodes() if node["Alive"]}
    assert len(nodes) == 2, ray.nodes()

    started = time.monotonic()
    runner = RayStageRunner("TurtleBot3Stage1-v0", actors=2, envs_per_actor=ENVS_PER_ACTOR,
                            address=cluster.address)
    try:
        made = time.monotonic() - started
        first = runner.reset(seed=3)
        assert first.shape == (2 * ENVS_PER_ACTOR, 28)
        assert set(runner.node_ids) == nodes, "the actors are not on both nodes"

        actions = np.random.default_rng(0).integers(0, 5, size=(STEPS, runner.num_envs))
        started = time.monotonic()
        batch = runner.step_batch(actions)
        stepped = time.monotonic() - started
        assert batch.observations.shape == (STEPS, runner.num_envs, 28)
        assert batch.rewards.shape == (STEPS, runner.num_envs)
        assert np.isfinite(batch.observations).all() and np.isfinite(batch.rewards).all()
        assert set(batch.node_ids) == nodes
        # each node stepped its envs: their observations moved away from the reset's
        for env, node in enumerate(batch.node_ids):
            assert not np.allclose(batch.observations[-1, env], first[env]), (env, node)

        batch = runner.rollout(lambda obs: np.full(len(obs), 2), steps=STEPS)   # straight on
        assert set(batch.node_ids) == nodes and batch.rewards.shape == (STEPS, runner.num_envs)
        say(capsys, "2 actors x %d envs made in %.1f s; a batch of %d x %d steps took %.2f s "
                    "(%.0f env steps/s)" % (ENVS_PER_ACTOR, made, STEPS, runner.num_envs,
                                            stepped, STEPS * runner.num_envs / stepped))
    finally:
        runner.close()


def test_the_step_after_an_episodes_end_returns_the_next_first_observation(cluster):
    """Episodes of 3 steps (a TimeLimit): a first batch of 3 steps ends every episode, so the
    next batch's first step is each env's reset, and gives what a lone env gives at the reset
    after the same seed and actions; the step after it is a step again."""
    import gymnasium
    from tutorial_turtlebot.learning.ray_actors import RayStageRunner

    seed, limit = 11, 3
    runner = RayStageRunner("TurtleBot3Stage1-v0", actors=2, envs_per_actor=ENVS_PER_ACTOR,
                            address=cluster.address, env_kwargs={"max_episode_steps": limit})
    lone = gymnasium.make("TurtleBot3Stage1-v0", max_episode_steps=limit)
    try:
        first = runner.reset(seed=seed)
        actions = np.random.default_rng(1).integers(0, 5, size=(limit + 2, runner.num_envs))
        ended = runner.step_batch(actions[:limit])
        assert ended.truncated[-1].all() and not ended.truncated[:-1].any()
        after = runner.step_batch(actions[limit:])
        assert not (after.terminated | after.truncated).any()
        assert (after.rewards[0] == 0).all() and not after.at_goal[0].any()
        for env in range(runner.num_envs):
            obs, _ = lone.reset(seed=seed + env)
            assert np.array_equal(obs, first[env])
            for index in range(limit):
                obs, reward, _, truncated, _ = lone.step(actions[index, env])
                assert np.array_equal(obs, ended.observations[index, env]), (env, index)
            assert truncated
            obs, info = lone.reset()                  # the next episode's first observation
            assert info["sim_time"] == 0.0
            assert np.array_equal(after.observations[0, env], obs), env
            obs, reward, _, _, _ = lone.step(actions[limit + 1, env])   # (action limit: ignored)
            assert np.array_equal(after.observations[1, env], obs), env
            assert after.rewards[1, env] == reward
    finally:
        lone.close()
        runner.close()
