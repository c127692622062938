"""tutorial_turtlebot: a pybullet stand-in for the TurtleBot3 Gazebo simulation, and the lab's nodes.

ROS-free logic lives in the plain modules here; modules ending in ``_node`` are the thin ROS glue.
"""
