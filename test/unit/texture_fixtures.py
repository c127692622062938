"""Textured meshes for the tests, made from scratch: a 1 m cube whose every face shows a whole
texture of four strong colours in its quadrants, as Collada and as OBJ, and its PNG image
(written with zlib and struct). Used by test_textures.py and by
test/fixtures/make_texture_fixtures.py (the rostest's committed world). Also the camera tests'
Waffle Pi (``camera_sim``) and where its image shows a world point (``pixel``)."""
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir,
                                "bench"))
import mesh_world  # noqa: E402

RED, GREEN, BLUE, YELLOW = (255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 0)
# the texture's quadrants, as the image shows them: row 0 at the top
QUADRANTS = {"top left": RED, "top right": GREEN, "bottom left": BLUE, "bottom right": YELLOW}


def camera_sim(monkeypatch, world, renderer):
    """A Waffle Pi at the origin of ``world`` facing +x, its camera drawn by ``renderer``
    ("tiny": TinyRenderer; "egl": skipped where EGL does not render here)."""
    import pytest
    from tutorial_turtlebot.sim.engine import physics, rendering
    from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
    if renderer == "egl" and not rendering.egl_available():
        pytest.skip("EGL does not render on this machine")
    if renderer == "tiny":
        monkeypatch.setattr(physics, "enable_egl", lambda client: False)
    sim = Simulation(SimConfig(model="waffle_pi", world=world, x=0.0, y=0.0, yaw=0.0))
    assert sim.physics.egl == (renderer == "egl")
    return sim


def pixel(sim, point):
    """(column, row) of the pixel of ``sim``'s robot camera image that shows world ``point``
    (m)."""
    from tutorial_turtlebot.sim.devices.camera import CameraIntrinsics
    position, rotation = sim.robot.camera_pose()
    spec = sim.robot.camera_spec
    f = CameraIntrinsics.from_spec(spec).f
    x, y, z = np.asarray(rotation).T @ (np.asarray(point, dtype=float) - position)
    return int(f * x / z + spec.width / 2), int(f * y / z + spec.height / 2)


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
    <newparam sid="skin-surface"><surface type="2D">\
<init_from>skin-image</init_from></surface></newparam>
    <newparam sid="skin-sampler"><sampler2D><source>skin-surface</source></sampler2D></newparam>
    <technique sid="common"><lambert>
      <diffuse><texture texture="skin-sampler" texcoord="UVMap"/></diffuse>
    </lambert></technique>
  </profile_COMMON></effect></library_effects>
  <library_materials><material id="skin">\
<instance_effect url="#skin-effect"/></material></library_materials>
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


# --- a crate written as 3ds Max's OpenCOLLADA exporter writes one ---------------------------

INCH = 0.0254                     # m: the file's <unit>
CRATE_SIDE = 0.6                  # m, a cube standing on z = 0 in its model frame
ORANGE, BROWN = (255, 128, 0), (110, 60, 20)
BASE_RGB = (0.2, 0.2, 0.2)        # the plain (untextured) material of the top and bottom
# 3ds Max names its maps "Map #<n>"; the image ids: the side's texture, the bump map's image
MAP_SIDE, MAP_BUMP = "Map #%d-image" % 1, "Map #%d-image" % 2


def lid_texture(side: int = 16) -> np.ndarray:
    """Orange above, brown below (rows from the top)."""
    image = np.zeros((side, side, 3), dtype=np.uint8)
    image[:side // 2], image[side // 2:] = ORANGE, BROWN
    return image


def _crate_faces():
    """[(material, corners (4, 3) m, counter-clockwise from outside, uvs (4, 2))] of the crate:
    the +-x faces "side", the +-y faces "lid", top and bottom "base". Each face shows its whole
    texture upright seen from outside (sides: z up; top and bottom: y up)."""
    faces = []
    for axis, material in ((0, "side"), (1, "lid"), (2, "base")):
        for sign in (-1.0, 1.0):
            normal = np.zeros(3)
            normal[axis] = sign
            up = np.array([0.0, 0.0, 1.0]) if axis != 2 else np.array([0.0, 1.0, 0.0])
            right = np.cross(up, normal)
            centre = normal * CRATE_SIDE / 2 + np.array([0.0, 0.0, CRATE_SIDE / 2])
            uvs = np.array([(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)])
            corners = np.array([centre + ((u - 0.5) * right + (v - 0.5) * up) * CRATE_SIDE
                                for u, v in uvs])
            faces.append((material, corners, uvs))
    return faces


def max_style_crate_dae() -> str:
    """A Collada file as 3ds Max's OpenCOLLADA exporter writes it: inches, the pivot at the
    bottom (a node <translate>), a diffuse texture named straight by its image id (MAP_SIDE)
    (no <newparam>), a bump map in the effect's <extra> naming an image that is not there, a
    second material through the <newparam> surface -> sampler2D chain, a third of a plain colour,
    two texture coordinate sets (the first, S T P, is the one drawn; the second is a lightmap
    channel), normals, and quads (<polylist>) beside triangles."""
    faces = _crate_faces()
    positions, normals, map1, map2 = [], [], [], []
    groups = {"side": [], "lid": [], "base": []}    # per face: its 4 corners' index tuples
    for material, corners, uvs in faces:
        normal = np.cross(corners[1] - corners[0], corners[2] - corners[0])
        normals.append(normal / np.linalg.norm(normal))
        corner_indices = []
        for corner, uv in zip(corners, uvs):
            positions.append((corner - (0.0, 0.0, CRATE_SIDE / 2)) / INCH)  # pivot: translate
            map1.append((uv[0], uv[1], 0.0))
            map2.append((0.93, 0.07))                                       # a lightmap corner
            i = len(positions) - 1
            corner_indices.append((i, len(normals) - 1, i, i))
        groups[material].append(corner_indices)

    def floats(rows):
        return " ".join("%.7g" % v for row in rows for v in row)

    def quads(face_list):
        return " ".join("%d %d %d %d" % c for face in face_list for c in face)

    def triangles(face_list):
        return " ".join("%d %d %d %d" % face[k] for face in face_list
                        for k in (0, 1, 2, 0, 2, 3))

    inputs = """
          <input semantic="VERTEX" source="#geom-Crate-vertices" offset="0"/>
          <input semantic="NORMAL" source="#geom-Crate-normals" offset="1"/>
          <input semantic="TEXCOORD" source="#geom-Crate-map1" offset="2" set="0"/>
          <input semantic="TEXCOORD" source="#geom-Crate-map2" offset="3" set="1"/>"""
    bind = """
              <instance_material symbol="{0}" target="#{0}-material">
                <bind_vertex_input semantic="CHANNEL1" input_semantic="TEXCOORD" input_set="0"/>
                <bind_vertex_input semantic="CHANNEL2" input_semantic="TEXCOORD" input_set="1"/>
              </instance_material>"""
    return """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset>
    <contributor><authoring_tool>OpenCOLLADA for 3ds Max (a test fixture)</authoring_tool>
    </contributor>
    <unit name="inch" meter="{inch}"/>
    <up_axis>Z_UP</up_axis>
  </asset>
  <library_images>
    <image id="{map_side}" name="{map_side_name}">
      <init_from>file:///C:/Projects/crate/textures/crate_side.png</init_from>
    </image>
    <image id="{map_bump}"><init_from>crate_bump.png</init_from></image>
    <image id="crate_lid_png"><init_from>../materials/textures/crate_lid.png</init_from></image>
  </library_images>
  <library_effects>
    <effect id="side">
      <profile_COMMON>
        <technique sid="common">
          <blinn>
            <emission><color>0 0 0 1</color></emission>
            <ambient><color>0.588 0.588 0.588 1</color></ambient>
            <diffuse><texture texture="{map_side}" texcoord="CHANNEL1"/></diffuse>
            <specular><color>0 0 0 1</color></specular>
            <shininess><float>10</float></shininess>
            <transparent opaque="A_ONE"><color>1 1 1 1</color></transparent>
            <transparency><float>1</float></transparency>
          </blinn>
        </technique>
      </profile_COMMON>
      <extra>
        <technique profile="OpenCOLLADA3dsMax">
          <bump bumptype="HEIGHTFIELD"><texture texture="{map_bump}" texcoord="CHANNEL1"/>
          </bump>
        </technique>
      </extra>
    </effect>
    <effect id="lid">
      <profile_COMMON>
        <newparam sid="crate_lid_png-surface">
          <surface type="2D"><init_from>crate_lid_png</init_from></surface>
        </newparam>
        <newparam sid="crate_lid_png-sampler">
          <sampler2D><source>crate_lid_png-surface</source></sampler2D>
        </newparam>
        <technique sid="common">
          <blinn>
            <ambient><color>0.588 0.588 0.588 1</color></ambient>
            <diffuse><texture texture="crate_lid_png-sampler" texcoord="CHANNEL1"/></diffuse>
            <transparent opaque="A_ONE"><color>1 1 1 1</color></transparent>
            <transparency><float>1</float></transparency>
          </blinn>
        </technique>
      </profile_COMMON>
    </effect>
    <effect id="base">
      <profile_COMMON>
        <technique sid="common">
          <phong><diffuse><color>{base} 1</color></diffuse></phong>
        </technique>
      </profile_COMMON>
    </effect>
  </library_effects>
  <library_materials>
    <material id="side-material" name="side"><instance_effect url="#side"/></material>
    <material id="lid-material" name="lid"><instance_effect url="#lid"/></material>
    <material id="base-material" name="base"><instance_effect url="#base"/></material>
  </library_materials>
  <library_geometries>
    <geometry id="geom-Crate" name="Crate">
      <mesh>
        <source id="geom-Crate-positions">
          <float_array id="geom-Crate-positions-array" count="{np}">{positions}</float_array>
          <technique_common>
            <accessor source="#geom-Crate-positions-array" count="{nv}" stride="3">
              <param name="X" type="float"/><param name="Y" type="float"/>
              <param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <source id="geom-Crate-normals">
          <float_array id="geom-Crate-normals-array" count="{nn}">{normals}</float_array>
          <technique_common>
            <accessor source="#geom-Crate-normals-array" count="{nnv}" stride="3">
              <param name="X" type="float"/><param name="Y" type="float"/>
              <param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <source id="geom-Crate-map1">
          <float_array id="geom-Crate-map1-array" count="{nm1}">{map1}</float_array>
          <technique_common>
            <accessor source="#geom-Crate-map1-array" count="{nv}" stride="3">
              <param name="S" type="float"/><param name="T" type="float"/>
              <param name="P" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <source id="geom-Crate-map2">
          <float_array id="geom-Crate-map2-array" count="{nm2}">{map2}</float_array>
          <technique_common>
            <accessor source="#geom-Crate-map2-array" count="{nv}" stride="2">
              <param name="S" type="float"/><param name="T" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <vertices id="geom-Crate-vertices">
          <input semantic="POSITION" source="#geom-Crate-positions"/>
        </vertices>
        <polylist material="side" count="2">{inputs}
          <vcount>4 4 </vcount>
          <p>{side}</p>
        </polylist>
        <triangles material="lid" count="4">{inputs}
          <p>{lid}</p>
        </triangles>
        <triangles material="base" count="4">{inputs}
          <p>{base_p}</p>
        </triangles>
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="MaxScene">
      <node id="node-Crate" name="Crate">
        <translate>0 0 {lift}</translate>
        <instance_geometry url="#geom-Crate">
          <bind_material>
            <technique_common>{bind_side}{bind_lid}{bind_base}
            </technique_common>
          </bind_material>
        </instance_geometry>
      </node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#MaxScene"/></scene>
</COLLADA>
""".format(inch=INCH, base=" ".join("%g" % c for c in BASE_RGB), map_side=MAP_SIDE,
           map_side_name=MAP_SIDE[:-len("-image")], map_bump=MAP_BUMP,
           np=3 * len(positions), nv=len(positions), positions=floats(positions),
           nn=3 * len(normals), nnv=len(normals), normals=floats(normals),
           nm1=3 * len(map1), map1=floats(map1), nm2=2 * len(map2), map2=floats(map2),
           inputs=inputs, side=quads(groups["side"]), lid=triangles(groups["lid"]),
           base_p=triangles(groups["base"]), lift="%.7g" % (CRATE_SIDE / 2 / INCH),
           bind_side=bind.format("side"), bind_lid=bind.format("lid"),
           bind_base=bind.format("base"))


MAX_STYLE_CRATE_SDF = """<?xml version="1.0"?>
<sdf version="1.6">
  <model name="max_style_crate">
    <static>true</static>
    <link name="link">
      <!-- A collision box a little larger than the visual mesh, as many models have (a hull or
           a box around it): a camera must see the visual, not the collision. -->
      <collision name="collision">
        <pose>0 0 {half} 0 0 0</pose>
        <geometry><box><size>{box} {box} {box}</size></box></geometry>
      </collision>
      <visual name="visual">
        <geometry><mesh><uri>model://max_style_crate/meshes/crate.dae</uri></mesh></geometry>
      </visual>
    </link>
  </model>
</sdf>
""".format(half=CRATE_SIDE / 2, box=CRATE_SIDE + 0.01)

MAX_STYLE_CRATE_CONFIG = """<?xml version="1.0"?>
<model>
  <name>max_style_crate</name>
  <version>1.0</version>
  <sdf version="1.6">model.sdf</sdf>
  <description>A test crate written as 3ds Max's Collada exporter writes one.</description>
</model>
"""


def write_max_style_crate(models):
    """The Gazebo model folder ``models``/max_style_crate (model.config, model.sdf,
    meshes/crate.dae, materials/textures/crate_side.png and crate_lid.png); returns it."""
    folder = models / "max_style_crate"
    (folder / "meshes").mkdir(parents=True, exist_ok=True)
    (folder / "materials" / "textures").mkdir(parents=True, exist_ok=True)
    (folder / "model.config").write_text(MAX_STYLE_CRATE_CONFIG)
    (folder / "model.sdf").write_text(MAX_STYLE_CRATE_SDF)
    (folder / "meshes" / "crate.dae").write_text(max_style_crate_dae())
    textures = folder / "materials" / "textures"
    (textures / "crate_side.png").write_bytes(png_bytes(quadrant_texture()))
    (textures / "crate_lid.png").write_bytes(png_bytes(lid_texture()))
    return folder
