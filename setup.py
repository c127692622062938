"""Python package of tutorial_turtlebot, installed by catkin_python_setup()."""
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(
    packages=["tutorial_turtlebot", "tutorial_turtlebot.sim", "tutorial_turtlebot.sim.files",
              "tutorial_turtlebot.sim.files.sdf", "tutorial_turtlebot.sim.files.urdf",
              "tutorial_turtlebot.sim.files.meshes", "tutorial_turtlebot.sim.files.looks",
              "tutorial_turtlebot.sim.files.plugins",
              "tutorial_turtlebot.sim.engine", "tutorial_turtlebot.sim.devices",
              "tutorial_turtlebot.sim.world", "tutorial_turtlebot.gazebo",
              "tutorial_turtlebot.gazebo.impl", "tutorial_turtlebot.lab",
              "tutorial_turtlebot.learning"],
    package_dir={"": "src"}))
