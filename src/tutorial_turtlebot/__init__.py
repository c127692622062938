"""tutorial_turtlebot: a pybullet stand-in for the TurtleBot3 Gazebo simulation,
and the lab's nodes.

Three wings: ``sim`` (the simulator, no ROS), ``gazebo`` (the ``/gazebo`` node: messages, topics,
services) and ``lab`` (the lab's nodes and their ROS-free logic). ``errors`` is shared by all.
"""
