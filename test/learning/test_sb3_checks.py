"""stable-baselines3 takes the learning environments as they are: its env checker passes, without
a warning, for every stage of both variants (ROBOTIS' noetic and ROS 2 stages), and its
``make_vec_env`` of an env id (which asks for render_mode "rgb_array") warns of nothing.

Not a unit test: stable-baselines3 comes with the train extra (torch, about 800 MB), which it
installs on first use (bash tools/install_extra.sh train) where pip finds torch's CPU build
(pip's find-links); it skips, with one line, where pip would take PyPI's CUDA build instead
(several GB: the Debian 13 root of tools/try_platform.sh) and where PyPI is unreachable. Run it
on its own:

    source catkin_ws/devel/setup.bash && python3 -m pytest test/learning/test_sb3_checks.py
"""
import importlib
import os
import subprocess
import sys
import warnings

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from extras import ensure_extra  # noqa: E402


@pytest.fixture(scope="module")
def sb3():
    """stable_baselines3, installed first if missing (an extra, not in package.xml)."""
    try:
        return importlib.import_module("stable_baselines3")
    except ImportError:
        pass
    cpu_build = subprocess.run([sys.executable, "-m", "pip", "install", "--dry-run", "--no-deps",
                                "--no-index", "torch==2.13.0+cpu"],
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if cpu_build.returncode != 0:
        pytest.skip("pip finds no CPU build of torch 2.13.0 here (only PyPI's CUDA build, "
                    "several GB): the train extra is not installed for a test")
    return ensure_extra("train", "stable_baselines3", timeout=1800)


def env_ids():
    from tutorial_turtlebot.learning import ENV_IDS, ROS2_ENV_IDS

    return ENV_IDS + ROS2_ENV_IDS


@pytest.mark.parametrize("env_id", env_ids())
def test_stable_baselines3s_env_checker_passes_without_a_warning(sb3, env_id):
    import gymnasium

    check_env = importlib.import_module("stable_baselines3.common.env_checker").check_env
    env = gymnasium.make(env_id, disable_env_checker=True)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            check_env(env.unwrapped, warn=True)
    finally:
        env.close()


def test_make_vec_env_of_an_env_id_warns_of_nothing(sb3):
    make_vec_env = importlib.import_module("stable_baselines3.common.env_util").make_vec_env
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        venv = make_vec_env("TurtleBot3Stage1-v0", n_envs=2)
        try:
            observations = venv.reset()
            assert observations.shape == (2, 28)
            venv.step([2, 2])
            frame = venv.render(mode="rgb_array")
            assert frame is not None and frame.ndim == 3
        finally:
            venv.close()
