"""Wavefront files of meshes for pybullet (obj_writer): flat normals facing out, colours, and
textures copied (and halved) beside them. No ROS master."""
import os

import numpy as np
import pytest

from tutorial_turtlebot.sim.files.meshes.mesh_file import load_mesh
from tutorial_turtlebot.sim.files.meshes.obj_writer import mtl_name, texture_copy, write_obj_parts
from tutorial_turtlebot.sim.files.meshes.texture_images import image_size

from texture_fixtures import png_bytes, quadrant_texture, write_textured_obj
import unit_paths

MODELS = os.path.join(unit_paths.FIXTURES, "gazebo_models")
PILLAR = os.path.join(MODELS, "mesh_pillar", "meshes", "pillar.stl")
CAP = os.path.join(MODELS, "mesh_pillar", "meshes", "cap.obj")


def obj_faces(path):
    """(vertices, faces, per-face normals) of a Wavefront file written by write_obj_parts."""
    vertices, normals, faces, face_normals = [], [], [], []
    with open(path) as f:
        for line in f:
            words = line.split()
            if words and words[0] == "v":
                vertices.append([float(w) for w in words[1:]])
            elif words and words[0] == "vn":
                normals.append([float(w) for w in words[1:]])
            elif words and words[0] == "f":
                corners = [w.split("//") for w in words[1:]]
                assert len(corners) == 3 and len({n for _, n in corners}) == 1
                faces.append([int(v) - 1 for v, _ in corners])
                face_normals.append(normals[int(corners[0][1]) - 1])
    return np.array(vertices), np.array(faces), np.array(face_normals)


def test_write_obj_parts_flat_normals_outward(tmp_path):
    mesh = load_mesh(PILLAR, (1.0, 1.0, 2.0))
    [(path, rgba)] = write_obj_parts(mesh, str(tmp_path))
    assert rgba is None and os.path.dirname(path) == str(tmp_path)
    vertices, faces, normals = obj_faces(path)
    assert len(faces) == 12 and np.allclose(vertices.max(axis=0), (0.2, 0.2, 2.0))
    centre = np.array([0.0, 0.0, 1.0])
    outward = vertices[faces].mean(axis=1) - centre
    assert np.all(np.einsum("ij,ij->i", normals, outward) > 0)
    assert np.allclose(np.linalg.norm(normals, axis=1), 1.0)


def test_write_obj_parts_load_in_pybullet(tmp_path):
    pybullet = pytest.importorskip("pybullet")
    mesh = load_mesh(CAP)
    written = write_obj_parts(mesh, str(tmp_path))
    assert sorted(rgba for _, rgba in written) == sorted(p.rgba for p in mesh.parts)
    assert len({path for path, _ in written}) == 2
    cid = pybullet.connect(pybullet.DIRECT)
    try:
        boxes = []
        for path, rgba in written:
            visual = pybullet.createVisualShape(pybullet.GEOM_MESH, fileName=path,
                                                rgbaColor=rgba, physicsClientId=cid)
            collision = pybullet.createCollisionShape(pybullet.GEOM_MESH, fileName=path,
                                                      physicsClientId=cid)
            assert visual >= 0 and collision >= 0
            body = pybullet.createMultiBody(0, collision, visual, physicsClientId=cid)
            boxes.append(np.array(pybullet.getAABB(body, physicsClientId=cid)))
        low = np.min([b[0] for b in boxes], axis=0)
        high = np.max([b[1] for b in boxes], axis=0)
        assert np.allclose(low, (-0.25, -0.25, 0.0), atol=0.01)   # Bullet's margin aside
        assert np.allclose(high, (0.25, 0.25, 0.1), atol=0.01)
        # Seen from above, TinyRenderer draws the top lit in its red: the normals face out
        # (a top drawn with its normal down comes out about a third darker).
        view = pybullet.computeViewMatrix((0, 0, 2), (0, 0, 0), (0, 1, 0))
        projection = pybullet.computeProjectionMatrixFOV(30, 1, 0.1, 10)
        width, height, rgb, _, _ = pybullet.getCameraImage(
            32, 32, view, projection, renderer=pybullet.ER_TINY_RENDERER, physicsClientId=cid)
        image = np.reshape(np.asarray(rgb, dtype=np.uint8), (height, width, 4))
        red, green, blue = image[16, 16, :3]
        assert red > 170 and green < 40 and blue < 40, (red, green, blue)
    finally:
        pybullet.disconnect(cid)


def test_a_texture_is_copied_beside_the_obj_file_halved_as_asked(tmp_path):
    """Each part's texture image is a file beside its OBJ file, named by its .mtl; halved
    copies keep the colours of the quadrants (box filtered), at half the sides each time."""
    write_textured_obj(tmp_path, write_texture=False)
    (tmp_path / "tex.png").write_bytes(png_bytes(quadrant_texture(64)))
    out = tmp_path / "out"
    out.mkdir()
    for halvings, side in ((0, 64), (1, 32), (3, 8), (9, 8)):      # never below 8 px
        name = texture_copy(str(tmp_path / "tex.png"), str(out), halvings)
        data = (out / name).read_bytes()
        assert image_size(data) == (side, side)
        if halvings == 0:
            assert data == (tmp_path / "tex.png").read_bytes()
    mesh = load_mesh(str(tmp_path / "box.obj"))
    [(path, rgba)] = write_obj_parts(mesh, str(out), images=lambda texture: "given.png")
    text = open(path).read()
    assert "mtllib %s\n" % mtl_name("given.png") in text
    assert "map_Kd given.png" in (out / mtl_name("given.png")).read_text()
    [(plain, _)] = write_obj_parts(mesh, str(out), images=lambda texture: None)
    assert "mtllib" not in open(plain).read() and "vt " not in open(plain).read()
