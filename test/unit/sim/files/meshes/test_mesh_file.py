"""Mesh files read as Gazebo reads them (mesh_file, through its readers collada_reader and
stl_obj_reader): Collada, STL, OBJ. No ROS master.

The fixtures in test/fixtures/gazebo_models are small meshes written for these tests (see
test/fixtures/make_mesh_fixtures.py); turtlebot3_world's two Collada files have the dimensions of
the TurtleBot3 world's arena, in inches, declaring Y_UP over z-up data as the originals do.
"""
import math
import os
import struct
import subprocess
import sys

import numpy as np
import pytest

from tutorial_turtlebot.errors import UserError
from tutorial_turtlebot.sim.files.meshes import mesh_file
from tutorial_turtlebot.sim.files.meshes.mesh_file import cache_clear, load_mesh
from tutorial_turtlebot.sim.files.meshes.mesh_types import MeshError, MeshUnreadable

from unit_helpers import within
import unit_paths

HERE = unit_paths.UNIT
MODELS = os.path.join(HERE, os.pardir, "fixtures", "gazebo_models")
HEXAGON = os.path.join(MODELS, "turtlebot3_world", "meshes", "hexagon.dae")
WALL = os.path.join(MODELS, "turtlebot3_world", "meshes", "wall.dae")
PILLAR = os.path.join(MODELS, "mesh_pillar", "meshes", "pillar.stl")
CAP = os.path.join(MODELS, "mesh_pillar", "meshes", "cap.obj")
GREEN, FLAT_BLACK = (0.0, 1.0, 0.0, 1.0), (0.1, 0.1, 0.1, 1.0)
RED, BLUE = (1.0, 0.0, 0.0, 1.0), (0.0, 0.0, 1.0, 1.0)


@pytest.fixture(autouse=True)
def fresh_cache():
    cache_clear()
    yield
    cache_clear()


def place(mesh, pose):
    """The mesh's vertices placed at pose (x, y, z, yaw)."""
    x, y, z, yaw = pose
    c, s = math.cos(yaw), math.sin(yaw)
    rotation = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    return mesh.vertices @ rotation.T + np.array([x, y, z])


def distinct(values, tolerance=1e-3):
    """The distinct absolute values, those closer than ``tolerance`` counted once (their mean)."""
    groups = []
    for v in sorted(np.abs(values).tolist()):
        if groups and v - groups[-1][-1] < tolerance:
            groups[-1].append(v)
        else:
            groups.append([v])
    return [sum(g) / len(g) for g in groups]


def signed_volume(mesh):
    """Positive when every face is counter-clockwise seen from outside (a closed mesh)."""
    v = mesh.vertices[mesh.faces]
    return float(np.einsum("ij,ij->i", v[:, 0], np.cross(v[:, 1], v[:, 2])).sum() / 6.0)


# --- Collada -------------------------------------------------------------------------------------

TRIANGLE = ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0))   # counter-clockwise from +z
ONE_TRIANGLE = ('<triangles count="1" material="{m}"><input semantic="VERTEX" source="#g-v" '
                'offset="0"/><p>0 1 2</p></triangles>')


def write_dae(tmp_path, name="mesh.dae", asset="", materials=None, primitives=None, nodes=None,
              positions=TRIANGLE):
    """A Collada file of one geometry "g" (``positions``; ``primitives`` default: one triangle
    of the first material) instanced by ``nodes`` (its "{geometry}" is the instance).
    ``materials``: symbol -> "r g b a", or "texture" for an image-textured diffuse."""
    materials = materials or {}
    effects, library = [], []
    for symbol, diffuse in materials.items():
        if diffuse == "texture":
            params = ('<newparam sid="surf"><surface type="2D"><init_from>img</init_from>'
                      '</surface></newparam><newparam sid="samp"><sampler2D><source>surf'
                      '</source></sampler2D></newparam>')
            diffuse_xml = '<texture texture="samp" texcoord="UVMap"/>'
        else:
            params, diffuse_xml = "", '<color sid="diffuse">%s</color>' % diffuse
        effects.append('<effect id="%s-fx"><profile_COMMON>%s<technique sid="common"><phong>'
                       '<diffuse>%s</diffuse></phong></technique></profile_COMMON></effect>'
                       % (symbol, params, diffuse_xml))
        library.append('<material id="%s-mat"><instance_effect url="#%s-fx"/></material>'
                       % (symbol, symbol))
    bind = ""
    if materials:
        bind = ("<bind_material><technique_common>%s</technique_common></bind_material>"
                % "".join('<instance_material symbol="%s" target="#%s-mat"/>' % (s, s)
                          for s in materials))
    if primitives is None:
        primitives = ONE_TRIANGLE.format(m=next(iter(materials), "none"))
    if nodes is None:
        nodes = '<node id="n">{geometry}</node>'
    geometry = '<instance_geometry url="#g">%s</instance_geometry>' % bind
    floats = " ".join("%r" % c for p in positions for c in p)
    text = """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset>%s</asset>
  <library_images><image id="img"><init_from>missing.png</init_from></image></library_images>
  <library_effects>%s</library_effects>
  <library_materials>%s</library_materials>
  <library_geometries><geometry id="g"><mesh>
    <source id="g-p"><float_array id="g-pa" count="%d">%s</float_array><technique_common>
      <accessor source="#g-pa" count="%d" stride="3"><param name="X" type="float"/>
      <param name="Y" type="float"/><param name="Z" type="float"/></accessor>
    </technique_common></source>
    <vertices id="g-v"><input semantic="POSITION" source="#g-p"/></vertices>
    %s
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="s">%s</visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
""" % (asset, "".join(effects), "".join(library), 3 * len(positions), floats, len(positions),
       primitives, nodes.replace("{geometry}", geometry))
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def test_hexagon_dae_gives_the_arena_prisms():
    head = load_mesh(HEXAGON, (0.8, 0.8, 0.8))
    low, high = head.bounds
    # Corners on +-x at the circumradius, flats at +-1.016, 2.032 m tall: inches and scale applied.
    assert np.allclose(low, (-1.1732, -1.016, 0.0), atol=1e-4)
    assert np.allclose(high, (1.1732, 1.016, 2.032), atol=1e-4)
    assert distinct(head.vertices[:, 0]) == pytest.approx([0.5866, 1.1732], abs=1e-4)
    assert len(head.vertices) == 12 and len(head.faces) == 20
    world = place(head, (3.5, 0.0, -0.5, 0.0))
    assert world[:, 2].min() == pytest.approx(-0.5) and world[:, 2].max() == pytest.approx(1.532)
    assert world[:, 0].min() == pytest.approx(2.3268, abs=1e-4)   # pokes into the arena
    hand = load_mesh(HEXAGON, (0.55, 0.55, 0.55))
    assert np.allclose(hand.bounds[1], (0.8066, 0.6985, 1.397), atol=1e-4)
    assert [p.rgba for p in head.parts] == [GREEN]
    assert signed_volume(head) > 0


def test_wall_dae_gives_the_arena_ring():
    wall = load_mesh(WALL, (0.25, 0.25, 0.25))
    world = place(wall, (0.0, 0.0, -0.3, -1.5708))
    # After the yaw the corners are on +-x: inner ring (2.933 circumradius, flats y = +-2.540),
    # outer ring (3.300, flats +-2.858).
    on_axis = np.abs(world[:, 1]) < 1e-3
    assert distinct(world[on_axis, 0]) == pytest.approx([2.9327, 3.2996], abs=1e-3)
    assert distinct(world[:, 1]) == pytest.approx([0.0, 2.540, 2.8575], abs=1e-3)
    assert distinct(world[:, 0]) == pytest.approx([1.4663, 1.6498, 2.9327, 3.2996], abs=1e-3)
    assert world[:, 2].min() == pytest.approx(-0.3) and world[:, 2].max() == pytest.approx(0.97)
    assert 2.858 - 2.540 == pytest.approx(0.3175, abs=1e-3)       # wall thickness
    assert [p.rgba for p in wall.parts] == [pytest.approx(FLAT_BLACK)]
    assert len(wall.faces) == 48 and signed_volume(wall) > 0


def test_collada_unit_is_applied(tmp_path):
    plain = load_mesh(write_dae(tmp_path, "plain.dae"))
    millimetres = load_mesh(write_dae(tmp_path, "mm.dae", asset='<unit name="mm" meter="0.001"/>'))
    inches = load_mesh(write_dae(tmp_path, "in.dae", asset='<unit name="inch" meter="0.0254"/>'))
    assert np.allclose(plain.bounds[1], (1.0, 1.0, 0.0))
    assert np.allclose(millimetres.bounds[1], (0.001, 0.001, 0.0))
    assert np.allclose(inches.bounds[1], (0.0254, 0.0254, 0.0))


def test_collada_up_axis_is_not_applied(tmp_path):
    """Gazebo uses the vertex data as written whatever <up_axis> says."""
    tall = ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 2.0))
    results = [load_mesh(write_dae(tmp_path, "%s.dae" % axis, positions=tall,
                                   asset="<up_axis>%s</up_axis>" % axis)).vertices
               for axis in ("Z_UP", "Y_UP", "X_UP")]
    assert np.array_equal(results[0], results[1]) and np.array_equal(results[0], results[2])
    assert np.allclose(results[1].max(axis=0), (1.0, 0.0, 2.0))
    # The arena's hexagon declares Y_UP and still stands 2.032 m tall along z at scale 0.8.
    assert load_mesh(HEXAGON, (0.8, 0.8, 0.8)).bounds[1][2] == pytest.approx(2.032)


def test_collada_node_transforms_are_applied(tmp_path):
    nodes = ('<node id="a"><translate>1 2 3</translate><rotate>0 0 1 90</rotate>'
             '<node id="b"><scale>2 2 2</scale>{geometry}</node></node>'
             '<node id="c"><matrix>1 0 0 10 0 1 0 0 0 0 1 0 0 0 0 1</matrix>{geometry}</node>')
    mesh = load_mesh(write_dae(tmp_path, nodes=nodes, asset='<unit meter="0.5"/>'))
    points = {tuple(np.round(v, 6)) for v in mesh.vertices}
    # Node a/b: scale 2, turn 90 degrees about z, move (1, 2, 3); then the unit halves it all.
    expected = {(0.5, 1.0, 1.5), (0.5, 2.0, 1.5), (-0.5, 1.0, 1.5)}
    # Node c: move 10 along x; halved.
    expected |= {(5.0, 0.0, 0.0), (5.5, 0.0, 0.0), (5.0, 0.5, 0.0)}
    assert points == expected
    assert len(mesh.faces) == 2


def test_collada_without_scene_gives_its_geometry_as_written(tmp_path):
    path = write_dae(tmp_path, asset='<unit meter="2"/>', materials={"red": "1 0 0 1"})
    with open(path) as f:
        text = f.read()
    with open(path, "w") as f:
        f.write(text.replace('<scene><instance_visual_scene url="#s"/></scene>', ""))
    mesh = load_mesh(path)
    assert np.allclose(mesh.bounds[1], (2.0, 2.0, 0.0))   # the unit still applies
    assert [p.rgba for p in mesh.parts] == [None]         # no node binds a material


def test_collada_colours_one_part_per_material(tmp_path):
    primitives = (ONE_TRIANGLE.format(m="red") + ONE_TRIANGLE.format(m="blue")
                  + ONE_TRIANGLE.format(m="red") + ONE_TRIANGLE.format(m="tex")
                  + ONE_TRIANGLE.format(m="unbound"))
    path = write_dae(tmp_path, primitives=primitives,
                     materials={"red": "1 0 0 1", "blue": "0 0 1 1", "tex": "texture"})
    mesh = load_mesh(path)
    colours = {p.rgba: len(p.faces) for p in mesh.parts}
    # A textured diffuse and a triangle set without material have no colour: one part of None.
    assert colours == {RED: 2, BLUE: 1, None: 2}
    assert len(mesh.faces) == 5


def test_collada_polylist_quads_are_triangulated(tmp_path):
    square = ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0))
    polylist = ('<polylist count="1" material="m"><input semantic="VERTEX" source="#g-v" '
                'offset="0"/><vcount>4</vcount><p>0 1 2 3</p></polylist>')
    mesh = load_mesh(write_dae(tmp_path, positions=square, primitives=polylist,
                               materials={"m": "0.2 0.4 0.6 1"}))
    assert len(mesh.faces) == 2 and len(mesh.vertices) == 4
    assert mesh.parts[0].rgba == pytest.approx((0.2, 0.4, 0.6, 1.0))
    corners = mesh.vertices[mesh.faces]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    assert np.all(normals[:, 2] > 0)          # the winding as written: facing +z


# --- STL and OBJ ---------------------------------------------------------------------------------

def test_binary_stl_pillar():
    mesh = load_mesh(PILLAR)
    assert np.allclose(mesh.bounds[0], (-0.2, -0.2, 0.0))
    assert np.allclose(mesh.bounds[1], (0.2, 0.2, 1.0))
    assert len(mesh.vertices) == 8 and len(mesh.faces) == 12     # shared corners merged
    assert [p.rgba for p in mesh.parts] == [None]
    assert signed_volume(mesh) == pytest.approx(0.16)


def test_ascii_stl_is_metres_without_colour(tmp_path):
    path = tmp_path / "tri.STL"
    path.write_text("solid t\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
                    "   vertex 2 0 0\n   vertex 0 3 0\n  endloop\n endfacet\nendsolid t\n")
    mesh = load_mesh(str(path))
    assert np.allclose(mesh.bounds[1], (2.0, 3.0, 0.0))
    assert len(mesh.faces) == 1 and mesh.parts[0].rgba is None


def test_obj_parts_take_the_mtl_colours():
    mesh = load_mesh(CAP)
    colours = {p.rgba: len(p.faces) for p in mesh.parts}
    assert colours == {(0.8, 0.1, 0.1, 1.0): 2, (0.9, 0.9, 0.9, 1.0): 10}   # quads triangulated
    top = next(p for p in mesh.parts if p.rgba[0] == 0.8)
    assert np.allclose(mesh.vertices[top.faces][:, :, 2], 0.1)             # the red top face
    assert np.allclose(mesh.bounds[1], (0.25, 0.25, 0.1))
    assert signed_volume(mesh) == pytest.approx(0.025)


def test_obj_without_mtl_has_no_colour(tmp_path):
    path = tmp_path / "plain.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    mesh = load_mesh(str(path))
    assert [p.rgba for p in mesh.parts] == [None]
    assert np.allclose(mesh.vertices[mesh.faces[0]], TRIANGLE)


# --- scale ---------------------------------------------------------------------------------------

def test_scale_per_axis():
    mesh = load_mesh(PILLAR, (0.5, 1.0, 1.5))      # as the mesh_pillar model uses it
    assert np.allclose(mesh.bounds[0], (-0.1, -0.2, 0.0))
    assert np.allclose(mesh.bounds[1], (0.1, 0.2, 1.5))


def test_mirroring_scale_keeps_faces_outward():
    mirrored = load_mesh(PILLAR, (-1.0, 1.0, 1.0))
    assert np.allclose(mirrored.bounds[1], (0.2, 0.2, 1.0))
    assert signed_volume(mirrored) == pytest.approx(0.16)
    twice = load_mesh(PILLAR, (-1.0, -2.0, 1.0))
    assert signed_volume(twice) == pytest.approx(0.32)


@pytest.mark.parametrize("scale", [(0.0, 1.0, 1.0), (1.0, float("nan"), 1.0),
                                   (1.0, 1.0, float("inf")), (1.0, 1.0), ("a", 1, 1)])
def test_bad_scale_is_refused(scale):
    with pytest.raises(MeshError) as err:
        load_mesh(PILLAR, scale)
    assert "scale" in str(err.value) and PILLAR in str(err.value)
    assert "\n" not in str(err.value)


# --- cache ---------------------------------------------------------------------------------------

def test_a_file_is_read_once(tmp_path, monkeypatch):
    reads = []
    real_read = mesh_file._read
    monkeypatch.setattr(mesh_file, "_read", lambda *a: reads.append(a) or real_read(*a))
    first = load_mesh(HEXAGON, (0.8, 0.8, 0.8))
    assert load_mesh(HEXAGON, [0.8, 0.8, 0.8]) is first
    link = tmp_path / "link.dae"
    link.symlink_to(os.path.abspath(HEXAGON))
    assert load_mesh(str(link), (0.8, 0.8, 0.8)) is first        # the same real path
    small = load_mesh(HEXAGON, (0.55, 0.55, 0.55))                # another scale: not re-read
    assert small is not first and len(reads) == 1
    copy = tmp_path / "copy.stl"
    copy.write_bytes(open(PILLAR, "rb").read())
    load_mesh(str(copy))
    os.utime(str(copy), ns=(0, 10 ** 9))        # touched, same bytes: from the disk cache
    load_mesh(str(copy))
    assert len(reads) == 2
    copy.write_bytes(b"X" + open(PILLAR, "rb").read()[1:])   # changed bytes: read again
    load_mesh(str(copy))
    assert len(reads) == 3


def test_loaded_meshes_are_read_only():
    mesh = load_mesh(PILLAR)
    with pytest.raises(ValueError):
        mesh.vertices[0, 0] = 5.0
    with pytest.raises(ValueError):
        mesh.parts[0].faces[0, 0] = 1


def test_trimesh_and_collada_are_imported_lazily():
    code = ("import sys; import tutorial_turtlebot.sim.files.meshes.mesh_file; "
            "print(sorted(m for m in ('trimesh', 'collada') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], stdout=subprocess.PIPE, check=True,
                         universal_newlines=True).stdout
    assert out.strip() == "[]"


# --- errors --------------------------------------------------------------------------------------

def one_line_error(path, *words):
    with pytest.raises(MeshError) as err:
        load_mesh(str(path))
    message = str(err.value)
    assert "\n" not in message and str(path) in message, message
    assert isinstance(err.value, UserError)
    assert err.value.__cause__ is None
    assert err.value.__context__ is None or err.value.__suppress_context__
    for word in words:
        assert word in message, message
    return message


def test_errors_are_one_line(tmp_path):
    one_line_error(tmp_path / "missing.dae", "no such")
    one_line_error(tmp_path, "it is a directory, not a regular file (a mesh file is needed)")
    (tmp_path / "mesh.ply").write_text("ply\n")
    one_line_error(tmp_path / "mesh.ply", ".ply", ".dae", ".stl", ".obj")
    (tmp_path / "broken.dae").write_text("<COLLADA><asset>\n<unit meter=")
    one_line_error(tmp_path / "broken.dae", "cannot read", "Collada")
    (tmp_path / "text.dae").write_text("not xml at all\n" * 3)
    one_line_error(tmp_path / "text.dae", "cannot read")
    (tmp_path / "empty.stl").write_bytes(b"")
    one_line_error(tmp_path / "empty.stl")
    (tmp_path / "short.stl").write_bytes(b"\0" * 80 + struct.pack("<I", 5) + b"\0" * 10)
    one_line_error(tmp_path / "short.stl")
    (tmp_path / "points.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    one_line_error(tmp_path / "points.obj", "no triangles")
    (tmp_path / "outside.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    one_line_error(tmp_path / "outside.obj")
    lines = '<lines count="1" material="m"><input semantic="VERTEX" source="#g-v" offset="0"/>' \
            '<p>0 1</p></lines>'
    one_line_error(write_dae(tmp_path, "lines.dae", primitives=lines), "no triangles")
    one_line_error(write_dae(tmp_path, "flat.dae", positions=((0, 0, 0), (0, 0, 0), (1, 1, 1))),
                   "no triangles")


def test_a_collada_file_that_cannot_be_read_is_unreadable_not_refused(tmp_path):
    """world_sdf makes MeshUnreadable a warning (the link loads without it, as in Gazebo);
    STL and OBJ faults and refusals of the file itself stay plain MeshErrors."""
    (tmp_path / "text.dae").write_text("not xml at all\n")
    (tmp_path / "points.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    lines = '<lines count="1" material="m"><input semantic="VERTEX" source="#g-v" offset="0"/>' \
            '<p>0 1</p></lines>'
    for path in (tmp_path / "text.dae", write_dae(tmp_path, "lines.dae", primitives=lines),
                 write_dae(tmp_path, "flat.dae", positions=((0, 0, 0), (0, 0, 0), (1, 1, 1)))):
        with pytest.raises(MeshUnreadable):
            load_mesh(str(path))
    for path in (tmp_path / "points.obj", tmp_path / "missing.dae", tmp_path):
        with pytest.raises(MeshError) as err:
            load_mesh(str(path))
        assert not isinstance(err.value, MeshUnreadable)


# --- Collada as exporters write it ---------------------------------------------------------------

def edited_dae(tmp_path, name, old, new, **kwargs):
    path = write_dae(tmp_path, name, **kwargs)
    with open(path) as f:
        text = f.read()
    assert old in text
    with open(path, "w") as f:
        f.write(text.replace(old, new))
    return path


@pytest.mark.parametrize("old, new", [
    ("<mesh>", "<mesh><!-- exported by SketchUp -->"),                 # pycollada: no triangles
    ("<mesh>", "<mesh><?exporter version='2'?>"),
    ('count="9">', 'count="9"><!-- x y z -->'),                        # text cut at the comment
    ("<p>0 1 2</p>", "<p>0 1<!-- first two --> 2</p>"),               # p cut short
    ("</mesh>", "<extra><technique profile='MAYA'><double_sided>1</double_sided></technique>"
                "</extra></mesh>"),
    ('<node id="n">', '<node id="n"><extra><technique profile="FCOLLADA"><visibility>1'
                      '</visibility></technique></extra>'),
    ("<p>0 1 2</p>", "<p>0 1 2</p><extra><technique profile='x'/></extra>"),
])
def test_collada_comments_and_extras_are_read_as_gazebo_reads_them(tmp_path, old, new):
    mesh = load_mesh(edited_dae(tmp_path, "m.dae", old, new, asset='<unit meter="0.5"/>'))
    assert len(mesh.faces) == 1
    assert np.allclose(mesh.bounds[1], (0.5, 0.5, 0.0))            # the unit still applies


def test_collada_several_instances_in_a_node_are_all_read(tmp_path):
    nodes = ('<node id="n">{geometry}<node id="up"><translate>0 0 2</translate>{geometry}</node>'
             '<instance_geometry url="#g"/></node>')
    mesh = load_mesh(write_dae(tmp_path, nodes=nodes))
    assert len(mesh.faces) == 3 and np.allclose(mesh.bounds[1], (1.0, 1.0, 2.0))


def test_collada_a_second_mesh_in_a_geometry_is_not_read(tmp_path):
    """Gazebo's Collada loader reads the first <mesh> of a <geometry>; so does pycollada."""
    second = ('<mesh><source id="h-p"><float_array id="h-pa" count="9">0 0 5 1 0 5 0 1 5'
              '</float_array><technique_common><accessor source="#h-pa" count="3" stride="3">'
              '<param name="X" type="float"/><param name="Y" type="float"/><param name="Z" '
              'type="float"/></accessor></technique_common></source><vertices id="h-v"><input '
              'semantic="POSITION" source="#h-p"/></vertices><triangles count="1"><input '
              'semantic="VERTEX" source="#h-v" offset="0"/><p>0 1 2</p></triangles></mesh>')
    mesh = load_mesh(edited_dae(tmp_path, "two.dae", "</mesh></geometry>",
                                "</mesh>%s</geometry>" % second))
    assert len(mesh.faces) == 1 and mesh.bounds[1][2] == 0.0


# --- under abuse: files that are no regular files, or too big; vertices beyond the world --------

def triangles_stl(name=b"binary stl"):
    """A binary STL of two triangles (a unit square), exactly as long as its count says."""
    data = name.ljust(80, b" ") + struct.pack("<I", 2)
    for a, b, c in (((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((1, 0, 0), (1, 1, 0), (0, 1, 0))):
        data += struct.pack("<12fH", 0, 0, 1, *a, *b, *c, 0)
    return data


def test_a_binary_stl_with_a_byte_after_its_triangles_is_read_as_gazebo_reads_it(tmp_path):
    path = tmp_path / "trailing.stl"
    path.write_bytes(triangles_stl() + b"\0")
    mesh = load_mesh(str(path))
    assert len(mesh.faces) == 2 and np.allclose(mesh.bounds[1], (1.0, 1.0, 0.0))


def test_an_ascii_stl_named_in_latin_1_is_read(tmp_path):
    """trimesh guesses the text's encoding with charset-normalizer (tools/setup_plan.py)."""
    path = tmp_path / "latin1.stl"
    path.write_bytes("solid caf\xe9\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n"
                     "   vertex 2 0 0\n   vertex 0 3 0\n  endloop\n endfacet\nendsolid caf\xe9\n"
                     .encode("latin-1"))
    mesh = load_mesh(str(path))
    assert len(mesh.faces) == 1 and np.allclose(mesh.bounds[1], (2.0, 3.0, 0.0))


def obj_with(tmp_path, mtl_lines=None, vertices=("0 0 0", "1 0 0", "0 1 0")):
    """An OBJ of one triangle using material ``m`` of m.mtl (``mtl_lines``; None: no file)."""
    path = tmp_path / "thing.obj"
    path.write_text("mtllib m.mtl\n%s\nusemtl m\nf 1 2 3\n"
                    % "\n".join("v " + v for v in vertices))
    if mtl_lines is not None:
        (tmp_path / "m.mtl").write_text("newmtl m\n" + "\n".join(mtl_lines) + "\n")
    return str(path)


def test_an_obj_whose_mtllib_is_a_fifo_is_refused_without_waiting(tmp_path):
    path = obj_with(tmp_path)
    os.mkfifo(str(tmp_path / "m.mtl"))
    with pytest.raises(MeshError) as err:
        within(10, load_mesh, path)
    assert str(err.value) == ("%s: cannot read a file the mesh names: it is a FIFO, not a "
                              "regular file" % (tmp_path / "m.mtl"))


def test_an_obj_whose_texture_is_a_device_keeps_its_colour_unread(tmp_path):
    """A texture that is no regular file is not opened: the part is drawn in its Kd, and one
    line says why (test_textures.py has the rest of the texture cases)."""
    path = obj_with(tmp_path, ["Kd 1 0 0", "map_Kd skin.png"])
    (tmp_path / "skin.png").symlink_to("/dev/zero")
    [part] = within(10, load_mesh, path).parts
    assert part.rgba == RED and part.texture is None and part.uvs is None
    assert "skin.png: cannot read a texture: it is a character device" in part.texture_problem


def test_an_obj_with_its_mtl_is_coloured_and_without_it_is_not(tmp_path):
    assert [p.rgba for p in load_mesh(obj_with(tmp_path, ["Kd 1 0 0"])).parts] == [RED]
    cache_clear()
    os.unlink(str(tmp_path / "m.mtl"))          # a missing mtl is left out, as in Gazebo
    assert [p.rgba for p in load_mesh(obj_with(tmp_path)).parts] == [None]


def test_a_mesh_larger_than_its_bound_is_refused_unread(tmp_path, monkeypatch):
    monkeypatch.setattr(mesh_file, "MAX_MESH_FILE_BYTES", 100)
    path = tmp_path / "big.stl"
    path.write_bytes(triangles_stl())
    message = one_line_error(path)
    assert message.endswith("cannot read this STL file: it is %d bytes, more than the 100 "
                            "allowed" % len(triangles_stl()))


def test_a_zipped_collada_file_is_refused(tmp_path):
    import zipfile
    with zipfile.ZipFile(str(tmp_path / "zipped.dae"), "w") as archive:
        archive.write(HEXAGON, "inner.dae")
    one_line_error(tmp_path / "zipped.dae", "zip archive")


@pytest.mark.parametrize("coordinate, scale, words", [
    ("1e308", (10.0, 10.0, 10.0), "vertex coordinate inf is outside [-1e+06, 1e+06] m (the "
                                  "file's 1e+308 scaled by 10)"),
    ("-1e12", (1.0, 1.0, 1.0), "vertex coordinate -1e+12 is outside [-1e+06, 1e+06] m"),
    ("1e5", (-100.0, 1.0, 1.0), "vertex coordinate -1e+07 is outside"),
])
def test_vertices_beyond_the_world_after_scaling_are_refused(tmp_path, coordinate, scale, words):
    path = obj_with(tmp_path, vertices=("0 0 0", "%s 0 0" % coordinate, "0 1 0"))
    with pytest.raises(MeshError) as err:
        load_mesh(path, scale)
    assert str(err.value).startswith(path + ": ") and words in str(err.value)
    assert "\n" not in str(err.value)


def test_an_unused_vertex_beyond_the_world_is_no_matter(tmp_path):
    path = obj_with(tmp_path, vertices=("0 0 0", "1 0 0", "0 1 0", "1e308 0 0"))
    assert np.allclose(load_mesh(path, (10.0, 10.0, 10.0)).bounds[1], (10.0, 10.0, 0.0))


# --- the modules -------------------------------------------------------------------------------

MESH_MODULES = ("mesh_types", "mesh_file", "mesh_lru", "mesh_side_files", "collada_reader",
                "stl_obj_reader", "texture_images", "obj_writer", "convex_hull", "mesh_cache",
                "mesh_prefetch")


def test_the_mesh_modules_import_each_other_at_the_top_without_a_circle():
    """Each job its module (mesh_file.py split by job): every import of the package is at
    the top of the module (none inside a function, where it would hide a circle), and no
    module reaches itself through its imports."""
    import ast
    folder = os.path.dirname(mesh_file.__file__)
    graph = {}
    for name in MESH_MODULES:
        tree = ast.parse(open(os.path.join(folder, name + ".py")).read())
        graph[name] = set()
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom) and node.level:
                modules = [node.module] if node.module else [a.name for a in node.names]
                assert node in tree.body, "%s imports %s inside a function" % (name, modules)
                graph[name].update(m for m in modules if node.level == 1
                                   and os.path.isfile(os.path.join(folder, m + ".py")))

    def reaches(start, goal, seen=()):
        return any(m == goal or (m not in seen and m in graph
                                 and reaches(m, goal, seen + (m,))) for m in graph[start])
    assert [m for m in MESH_MODULES if reaches(m, m)] == []
