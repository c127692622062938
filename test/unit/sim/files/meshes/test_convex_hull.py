"""Convex hulls of meshes (convex_hull). No ROS master. The meshes are test/fixtures/gazebo_models'
(see test_mesh_file.py)."""
import os

import numpy as np

from tutorial_turtlebot.sim.files.meshes.convex_hull import convex_hull_vertices
from tutorial_turtlebot.sim.files.meshes.mesh_file import load_mesh
from tutorial_turtlebot.sim.files.meshes.mesh_types import Mesh, MeshPart
import unit_paths

MODELS = os.path.join(unit_paths.FIXTURES, "gazebo_models")
WALL = os.path.join(MODELS, "turtlebot3_world", "meshes", "wall.dae")
PILLAR = os.path.join(MODELS, "mesh_pillar", "meshes", "pillar.stl")


def test_convex_hull_corners(tmp_path):
    pillar = convex_hull_vertices(load_mesh(PILLAR))
    assert sorted(map(tuple, np.round(pillar, 6).tolist())) == sorted(
        (x, y, z) for x in (-0.2, 0.2) for y in (-0.2, 0.2) for z in (0.0, 1.0))
    wall = convex_hull_vertices(load_mesh(WALL, (0.25, 0.25, 0.25)))
    assert len(wall) == 12                    # the outer ring's corners, top and bottom
    assert np.allclose(np.hypot(wall[:, 0], wall[:, 1]), 3.2996, atol=1e-4)
    # A subdivided cube: the points in its faces and edges are no corners.
    grid = np.array([(x, y, z) for x in (0, 1, 2) for y in (0, 1, 2) for z in (0, 1, 2)], float)
    faces = np.arange(27).reshape(-1, 3)
    cube = convex_hull_vertices(Mesh("cube", grid, (MeshPart(faces, None),)))
    assert sorted(map(tuple, cube.tolist())) == sorted(
        (x, y, z) for x in (0.0, 2.0) for y in (0.0, 2.0) for z in (0.0, 2.0))
    # A flat mesh: the corners of its outline.
    square = tmp_path / "flat.obj"
    square.write_text("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0\nv 0.5 0 0\n"
                      "f 1 6 5\nf 6 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n")
    flat = convex_hull_vertices(load_mesh(str(square)))
    assert len(flat) == 4 and np.allclose(flat[:, 2], 0.0)
