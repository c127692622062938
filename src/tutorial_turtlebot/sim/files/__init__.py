"""The simulator's readers: XML, URDF, SDF worlds, meshes and the files they name, with the limits
every number and name entering the world is held to. No ROS, no pybullet: plain data out."""
