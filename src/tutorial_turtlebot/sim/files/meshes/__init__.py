"""Mesh files: STL, OBJ, Collada; their textures, the disk cache, the files pybullet reads."""
