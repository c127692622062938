"""ROBOTIS' learning stages for reinforcement learning, as Gymnasium environments on the
simulator, without ROS (doc/learning.md). Importing this package registers them:

    import gymnasium, tutorial_turtlebot.learning
    env = gymnasium.make("TurtleBot3Stage1-v0")          # stages 1 to 4; model="waffle", ...
    env = gymnasium.make("TurtleBot3Stage1Ros2-v0")      # ROBOTIS' ROS 2 stages 1 to 4

It needs gymnasium (tools/setup.sh installs it); the simulator and the lab's nodes do not.
"""
import gymnasium

from . import robotis_stages_ros2
from .robotis_stages import MAX_EPISODE_STEPS, STAGES

ENV_IDS = tuple("TurtleBot3Stage%d-v0" % stage for stage in STAGES)
# variant="ros2": ROBOTIS' ROS 2 stages (learning.robotis_stages_ros2), 799 steps an episode
ROS2_ENV_IDS = tuple("TurtleBot3Stage%dRos2-v0" % stage for stage in STAGES)

for _stage, _env_id in zip(STAGES, ENV_IDS):
    if _env_id not in gymnasium.registry:
        gymnasium.register(_env_id, entry_point="tutorial_turtlebot.learning.stage_env:StageEnv",
                           kwargs={"stage": _stage}, max_episode_steps=MAX_EPISODE_STEPS)

for _stage, _env_id in zip(STAGES, ROS2_ENV_IDS):
    if _env_id not in gymnasium.registry:
        gymnasium.register(_env_id, entry_point="tutorial_turtlebot.learning.stage_env:StageEnv",
                           kwargs={"stage": _stage, "variant": "ros2"},
                           max_episode_steps=robotis_stages_ros2.MAX_EPISODE_STEPS)
