"""URDF: robots and spawned models, and the URDF text pybullet loads."""
