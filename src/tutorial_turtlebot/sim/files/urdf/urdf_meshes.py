"""What a robot URDF's ``<mesh>`` geometry costs and what of it is not drawn. No ROS, no pybullet.

A robot's meshes are built as any model's are (engine.movable_bodies, from the SDF model of its
URDF: files/urdf/urdf_to_sdf): each mesh read by ``mesh_file.load_mesh`` (Collada's unit
applied, its up axis not, as Gazebo; the URDF ``scale`` applied), a collision mesh colliding
as its convex hull. Here, before the build: ``mesh_triangles`` (the spawn budgets) and
``texture_warnings`` (the textures drawn as plain colours).
"""
from typing import List, Tuple

from ..meshes.mesh_file import load_mesh
from ....errors import UserError


def mesh_triangles(description) -> Tuple[int, int]:
    """(triangles of every mesh a ``urdf_file.RobotDescription`` uses, the most vertices of
    one of its collision meshes, which collide as hulls), its files read (and kept, as
    load_mesh keeps them)."""
    triangles = hull_vertices = 0
    for link in description.links.values():
        for shapes, collide in ((link.visuals, False), (link.collisions, True)):
            for shape in shapes:
                geometry = shape.geometry
                if geometry.shape != "mesh":
                    continue
                mesh = load_mesh(geometry.filename, geometry.size)
                triangles += sum(len(part.faces) for part in mesh.parts)
                if collide:
                    hull_vertices = max(hull_vertices, len(mesh.vertices))
    return triangles, hull_vertices


def texture_warnings(description) -> List[str]:
    """One line for each texture of a ``urdf_file.RobotDescription``'s visual meshes that is
    not drawn (mesh_file's ``texture_problem``: its part is drawn in its colour)."""
    lines: List[str] = []
    for link in description.links.values():
        for shape in link.visuals:
            geometry = shape.geometry
            if geometry.shape != "mesh":
                continue
            try:
                parts = load_mesh(geometry.filename, geometry.size).parts
            except UserError:
                continue                   # refused where the mesh is converted
            lines += [p.texture_problem for p in parts
                      if p.texture_problem and p.texture_problem not in lines]
    return lines
