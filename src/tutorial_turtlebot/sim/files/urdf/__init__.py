"""URDF: robots and spawned models, read and checked, and the SDF model Gazebo makes of them."""
