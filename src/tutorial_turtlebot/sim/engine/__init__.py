"""The physics engine: the only modules that talk to pybullet. Bodies, collision shapes, contacts,
forces, rays and rendering, in the world frame (metres, radians, seconds). No ROS."""
