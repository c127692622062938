"""Textured meshes for the tests, made from scratch: a 1 m cube whose every face shows a whole
texture of four strong colours in its quadrants, as Collada and as OBJ, and its PNG image
(written with zlib and struct). Used by test_textures.py and by
test/fixtures/make_texture_fixtures.py (the rostest's committed world)."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir,
                                "bench"))
import mesh_world  # noqa: E402

RED, GREEN, BLUE, YELLOW = (255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 0)
# the texture's quadrants, as the image shows them: row 0 at the top
QUADRANTS = {"top left": RED, "top right": GREEN, "bottom left": BLUE, "bottom right": YELLOW}


def png_bytes(rgb: np.ndarray) -> bytes:
    """An 8-bit RGB PNG of ``rgb`` (rows from the top): bench/mesh_world.py's writer."""
    height, width, _ = rgb.shape
    return mesh_world.png_bytes(width, height, lambda x, y: tuple(int(c) for c in rgb[y, x]))


def quadrant_texture(side: int = 16) -> np.ndarray:
    image = np.zeros((side, side, 3), dtype=np.uint8)
    half = side // 2
    image[:half, :half], image[:half, half:] = QUADRANTS["top left"], QUADRANTS["top right"]
    image[half:, :half], image[half:, half:] = QUADRANTS["bottom left"], QUADRANTS["bottom right"]
    return image


def cube():
    """(corners (8, 3), triangles (12, 3), per-corner uvs (12, 3, 2)) of a unit cube about the
    origin, counter-clockwise from outside. Each face shows the whole texture upright as seen
    from outside (sides: z up; top and bottom: y up)."""
    corners = np.array([(x, y, z) for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)])
    triangles, uvs = [], []
    for axis in range(3):
        for sign in (-1.0, 1.0):
            normal = np.zeros(3)
            normal[axis] = sign
            up = np.array([0.0, 0.0, 1.0]) if axis != 2 else np.array([0.0, 1.0, 0.0])
            right = np.cross(up, normal)
            on_face = [i for i, c in enumerate(corners) if c[axis] == sign * 0.5]
            order = sorted(on_face, key=lambda i: np.arctan2(corners[i] @ up, corners[i] @ right))
            for tri in ((order[0], order[1], order[2]), (order[0], order[2], order[3])):
                triangles.append(tri)
                uvs.append([(corners[i] @ right + 0.5, corners[i] @ up + 0.5) for i in tri])
    return corners, np.array(triangles), np.array(uvs)


def write_textured_obj(folder, texture="tex.png", kd="1 1 1", write_texture=True):
    corners, triangles, uvs = cube()
    lines = ["mtllib box.mtl", "usemtl skin"]
    lines += ["v %g %g %g" % tuple(c) for c in corners]
    lines += ["vt %g %g" % tuple(uv) for uv in uvs.reshape(-1, 2)]
    lines += ["f %d/%d %d/%d %d/%d" % (a + 1, 3 * k + 1, b + 1, 3 * k + 2, c + 1, 3 * k + 3)
              for k, (a, b, c) in enumerate(triangles)]
    (folder / "box.obj").write_text("\n".join(lines) + "\n")
    (folder / "box.mtl").write_text("newmtl skin\nKd %s\nmap_Kd -s 1 1 1 %s\n" % (kd, texture))
    if write_texture:
        (folder / texture).write_bytes(png_bytes(quadrant_texture()))
    return folder / "box.obj"


def write_textured_dae(folder, texture="tex.png", write_texture=True):
    corners, triangles, uvs = cube()
    indices = " ".join("%d %d" % (v, 3 * k + i) for k, tri in enumerate(triangles)
                       for i, v in enumerate(tri))
    text = """<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_images><image id="skin-image"><init_from>{texture}</init_from></image></library_images>
  <library_effects><effect id="skin-effect"><profile_COMMON>
    <newparam sid="skin-surface"><surface type="2D"><init_from>skin-image</init_from></surface></newparam>
    <newparam sid="skin-sampler"><sampler2D><source>skin-surface</source></sampler2D></newparam>
    <technique sid="common"><lambert>
      <diffuse><texture texture="skin-sampler" texcoord="UVMap"/></diffuse>
    </lambert></technique>
  </profile_COMMON></effect></library_effects>
  <library_materials><material id="skin"><instance_effect url="#skin-effect"/></material></library_materials>
  <library_geometries><geometry id="box"><mesh>
    <source id="pos"><float_array id="pos-a" count="{np}">{positions}</float_array>
      <technique_common><accessor source="#pos-a" count="8" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <source id="uv"><float_array id="uv-a" count="{nu}">{uvs}</float_array>
      <technique_common><accessor source="#uv-a" count="{nuv}" stride="2">
        <param name="S" type="float"/><param name="T" type="float"/>
      </accessor></technique_common></source>
    <vertices id="verts"><input semantic="POSITION" source="#pos"/></vertices>
    <triangles material="skin" count="{nt}">
      <input semantic="VERTEX" source="#verts" offset="0"/>
      <input semantic="TEXCOORD" source="#uv" offset="1" set="0"/>
      <p>{indices}</p>
    </triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="n">
    <instance_geometry url="#box"><bind_material><technique_common>
      <instance_material symbol="skin" target="#skin">
        <bind_vertex_input semantic="UVMap" input_semantic="TEXCOORD" input_set="0"/>
      </instance_material>
    </technique_common></bind_material></instance_geometry>
  </node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
""".format(texture=texture, np=corners.size, positions=" ".join("%g" % v for v in corners.ravel()),
           nu=uvs.size, nuv=len(uvs.reshape(-1, 2)),
           uvs=" ".join("%g" % v for v in uvs.ravel()), nt=len(triangles), indices=indices)
    (folder / "box.dae").write_text(text)
    if write_texture:
        (folder / texture).write_bytes(png_bytes(quadrant_texture()))
    return folder / "box.dae"
