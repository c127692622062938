"""The simulator, without ROS: the world and its models, physics, sensors and the sim clock.

Everything here is plain Python over pybullet; the ``/gazebo`` node (``..gazebo``) only converts
to and from ROS messages. Units: SI (m, s, rad); frames as REP 103/105.
"""
