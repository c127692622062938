"""The simulated world as Gazebo's world API sees it: models, spawning and its checks, frames,
physics properties, the robots, the schedules and pacing of sim time, and ``Simulation``. No ROS."""
