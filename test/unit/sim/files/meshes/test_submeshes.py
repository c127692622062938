"""One named submesh of a mesh file written as a file of its own (submeshes), with Gazebo 11's
names (collada_reader.submesh_names): a node's name, a nameless node's geometries named after
the last name read before them; centred about its bounding box; textured parts keep their
texture; written once for the same file. Meshes of our own in tmp_path (texture_fixtures) and
test/fixtures/worlds/submesh/two_parts.dae. No ROS."""
import os

import numpy as np
import pytest

from tutorial_turtlebot.sim.files.meshes import submeshes
from tutorial_turtlebot.sim.files.meshes.collada_reader import submesh_names
from tutorial_turtlebot.sim.files.meshes.mesh_file import cache_clear, load_mesh
from tutorial_turtlebot.sim.files.meshes.submeshes import SubmeshMissing, submesh_file

import unit_paths
from texture_fixtures import write_textured_dae

TWO_PARTS = os.path.join(unit_paths.FIXTURES, "worlds", "submesh", "two_parts.dae")


@pytest.fixture(autouse=True)
def fresh_meshes():
    cache_clear()
    yield
    cache_clear()


def scene_of(text):
    import collada
    import io
    return collada.Collada(io.BytesIO(text.encode())).scene


def test_gazebos_names_of_nested_and_nameless_nodes(tmp_path):
    """The fixture's "Tree" node holds "Trunk" and "Crown"; a nameless node after them takes
    "Crown" (the last name read), and a named parent's own geometry read after its named
    child takes the child's name, as Gazebo's ColladaLoader reads them."""
    text = open(TWO_PARTS).read()
    assert submesh_names(scene_of(text)) == ["Trunk", "Crown"]
    geometry = '<instance_geometry url="#trunk-geometry"/>'
    quirks = text.replace('</node>\n    </visual_scene>',
                          '</node>\n      <node id="x">%s</node>\n'
                          '      <node id="p" name="Parent"><node id="c" name="Child">%s</node>'
                          '%s</node>\n    </visual_scene>' % (geometry, geometry, geometry))
    assert submesh_names(scene_of(quirks)) == ["Trunk", "Crown", "Crown", "Child", "Child"]


def test_a_centred_submesh_and_one_as_written():
    crown = load_mesh(submesh_file(TWO_PARTS, "Crown", center=True))
    trunk = load_mesh(submesh_file(TWO_PARTS, "Trunk", center=False))
    assert np.allclose(crown.bounds, ([-0.5, -0.5, -0.3], [0.5, 0.5, 0.3]))
    assert np.allclose(trunk.bounds, ([-0.1, -0.1, 0.0], [0.1, 0.1, 1.0]))
    with pytest.raises(SubmeshMissing, match=r"no submesh named 'Leaf' \(its submeshes: Crown, "
                                             r"Trunk\)"):
        submesh_file(TWO_PARTS, "Leaf", center=False)


def test_a_textured_part_keeps_its_texture_and_is_written_once(tmp_path, monkeypatch):
    mesh = write_textured_dae(tmp_path)
    mesh.write_text(mesh.read_text().replace('<node id="n">', '<node id="n" name="Box">'))
    first = submesh_file(str(mesh), "Box", center=False)
    [part] = load_mesh(first).parts
    assert part.texture == str(tmp_path / "tex.png") and part.uvs.shape == (12, 3, 2)
    monkeypatch.setattr(submeshes, "read_collada", lambda *a, **k: 1 / 0)   # not read again
    assert submesh_file(str(mesh), "Box", center=False) == first
