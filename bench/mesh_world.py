#!/usr/bin/env python3
"""A generated Gazebo world of many textured Collada models (bench and tests; our own content).

``write_mesh_world(folder)`` writes into ``folder``:

- ``models/``: ``MODEL_KINDS`` model folders (model.config + model.sdf + meshes/), static, each
  with a Collada visual and collision of a few hundred to a few thousand triangles (boxes,
  cylinder-like drums, tables, chairs, shelves: unions of boxes and drums) whose diffuse is a
  ``<texture>`` of a PNG beside the .dae, with texture coordinates; some have a second, coarser
  collision .dae, some a ``<scale>``. ``SETS`` more model folders only include others (a
  table with two chairs: nested ``model://`` includes).
- ``mesh_world.world``: ground_plane and ``INCLUDES`` top-level includes spread over 10 x 10 m
  on a 1 m grid, leaving a 2.4 m square around the origin (the robot's spawn) clear.

Deterministic: the same files every time. Returns (world path, models folder), the folder to
put on GAZEBO_MODEL_PATH. Run as a script: ``python3 bench/mesh_world.py FOLDER``.
Units: metres.
"""
import math
import os
import struct
import sys
import zlib

MODEL_KINDS = 100   # model folders with meshes
SETS = 8            # model folders made of nested includes
INCLUDES = 110      # top-level includes in the world (besides ground_plane)
CLEAR = 1.2         # m: no model centre within this of the origin on x or y
SPACING = 1.0       # m between grid cells (a model stays within 0.8 x 0.8 m)

_KINDS = ("box", "drum", "table", "chair", "shelf")


def png_bytes(width, height, pixel):
    """An 8-bit RGB PNG: ``pixel(x, y)`` -> (r, g, b) 0..255."""
    rows = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y))
                    for y in range(height))

    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data
                + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)   # 8-bit RGB
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header)
            + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


class _Builder:
    """Triangles with texture coordinates, added solid by solid."""

    def __init__(self):
        self.positions, self.uvs, self.triangles = [], [], []   # triangles: 3 (p, t) pairs

    def quad_grid(self, origin, u_axis, v_axis, n):
        """A parallelogram origin + s*u + t*v (s, t in 0..1) as an n x n grid of quads,
        counter-clockwise seen from the side u x v points to."""
        base = len(self.positions)
        for j in range(n + 1):
            for i in range(n + 1):
                s, t = i / n, j / n
                self.positions.append(tuple(origin[k] + s * u_axis[k] + t * v_axis[k]
                                            for k in range(3)))
                self.uvs.append((s, t))
        for j in range(n):
            for i in range(n):
                a = base + j * (n + 1) + i
                b, c, d = a + 1, a + n + 2, a + n + 1
                self.triangles += [(a, b, c), (a, c, d)]

    def box(self, centre, size, n):
        """An axis-aligned box, each face an n x n grid."""
        cx, cy, cz = centre
        hx, hy, hz = (s / 2 for s in size)
        x0, x1, y0, y1, z0, z1 = cx - hx, cx + hx, cy - hy, cy + hy, cz - hz, cz + hz
        X, Y, Z = (2 * hx, 0, 0), (0, 2 * hy, 0), (0, 0, 2 * hz)

        def neg(v):
            return tuple(-c for c in v)

        self.quad_grid((x0, y0, z1), X, Y, n)          # top
        self.quad_grid((x0, y1, z0), X, neg(Y), n)     # bottom
        self.quad_grid((x1, y0, z0), Y, Z, n)          # +x
        self.quad_grid((x0, y1, z0), neg(Y), Z, n)     # -x
        self.quad_grid((x0, y0, z0), X, Z, n)          # -y
        self.quad_grid((x1, y1, z0), neg(X), Z, n)     # +y

    def drum(self, centre, radius, height, segments, rings):
        """A closed cylinder around z (z from centre - height/2), ``segments`` around,
        ``rings`` bands of side."""
        cx, cy, cz = centre
        z0 = cz - height / 2
        base = len(self.positions)
        for r in range(rings + 1):
            for s in range(segments + 1):
                a = 2 * math.pi * s / segments
                self.positions.append((cx + radius * math.cos(a), cy + radius * math.sin(a),
                                       z0 + height * r / rings))
                self.uvs.append((s / segments, r / rings))
        for r in range(rings):
            for s in range(segments):
                a = base + r * (segments + 1) + s
                b, c, d = a + 1, a + segments + 2, a + segments + 1
                self.triangles += [(a, b, c), (a, c, d)]
        for z, up in ((z0, False), (z0 + height, True)):     # caps: fans around a centre
            centre_index = len(self.positions)
            self.positions.append((cx, cy, z))
            self.uvs.append((0.5, 0.5))
            ring = []
            for s in range(segments):
                a = 2 * math.pi * s / segments
                ring.append(len(self.positions))
                self.positions.append((cx + radius * math.cos(a), cy + radius * math.sin(a), z))
                self.uvs.append((0.5 + 0.5 * math.cos(a), 0.5 + 0.5 * math.sin(a)))
            for s in range(segments):
                p, q = ring[s], ring[(s + 1) % segments]
                self.triangles.append((centre_index, p, q) if up else (centre_index, q, p))

    def collada(self, image):
        """The Collada document: one geometry, one textured material (``image`` beside it)."""
        pos = " ".join("%.6g %.6g %.6g" % p for p in self.positions)
        uv = " ".join("%.6g %.6g" % t for t in self.uvs)
        indices = " ".join("%d %d %d %d %d %d" % (a, a, b, b, c, c) for a, b, c in self.triangles)
        n, k = len(self.positions), len(self.triangles)
        return """<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Z_UP</up_axis></asset>
  <library_images><image id="skin-image"><init_from>%(image)s</init_from></image></library_images>
  <library_effects><effect id="skin-effect"><profile_COMMON>
    <newparam sid="skin-surface"><surface type="2D">\
<init_from>skin-image</init_from></surface></newparam>
    <newparam sid="skin-sampler"><sampler2D><source>skin-surface</source></sampler2D></newparam>
    <technique sid="common"><lambert>
      <diffuse><texture texture="skin-sampler" texcoord="UVMap"/></diffuse>
    </lambert></technique>
  </profile_COMMON></effect></library_effects>
  <library_materials><material id="skin" name="skin">\
<instance_effect url="#skin-effect"/></material></library_materials>
  <library_geometries><geometry id="shape"><mesh>
    <source id="shape-positions">\
<float_array id="shape-positions-array" count="%(n3)d">%(pos)s</float_array>
      <technique_common><accessor source="#shape-positions-array" count="%(n)d" stride="3">
        <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
      </accessor></technique_common></source>
    <source id="shape-uvs"><float_array id="shape-uvs-array" count="%(n2)d">%(uv)s</float_array>
      <technique_common><accessor source="#shape-uvs-array" count="%(n)d" stride="2">
        <param name="S" type="float"/><param name="T" type="float"/>
      </accessor></technique_common></source>
    <vertices id="shape-vertices"><input semantic="POSITION" source="#shape-positions"/></vertices>
    <triangles material="skin-material" count="%(k)d">
      <input semantic="VERTEX" source="#shape-vertices" offset="0"/>
      <input semantic="TEXCOORD" source="#shape-uvs" offset="1" set="0"/>
      <p>%(indices)s</p>
    </triangles>
  </mesh></geometry></library_geometries>
  <library_visual_scenes><visual_scene id="scene"><node id="shape-node" name="shape">
    <instance_geometry url="#shape"><bind_material><technique_common>
      <instance_material symbol="skin-material" target="#skin">
        <bind_vertex_input semantic="UVMap" input_semantic="TEXCOORD" input_set="0"/>
      </instance_material>
    </technique_common></bind_material></instance_geometry>
  </node></visual_scene></library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
""" % dict(image=image, pos=pos, uv=uv, indices=indices, n=n, n2=2 * n, n3=3 * n, k=k)


def _solid(kind, number, detail):
    """A _Builder of model ``number``'s shape; ``detail`` 1 (fine) or 0 (coarse collision).
    Every shape stands on z = 0 within x, y of +-0.4 m."""
    b = _Builder()
    grid = (4 + number % 9) if detail else 1          # box faces: 32..200 triangles each
    segments = (16 + 4 * (number % 9)) if detail else 12
    rings = (4 + number % 6) if detail else 1
    if kind == "box":
        b.box((0, 0, 0.25), (0.5, 0.4 + 0.02 * (number % 5), 0.5), grid + 3)
    elif kind == "drum":
        b.drum((0, 0, 0.35), 0.3, 0.7, segments, rings * 2)
    elif kind == "table":
        b.box((0, 0, 0.72), (0.75, 0.75, 0.04), grid)
        for sx in (-1, 1):
            for sy in (-1, 1):
                b.drum((0.32 * sx, 0.32 * sy, 0.35), 0.025, 0.7, segments // 2, rings)
    elif kind == "chair":
        b.box((0, 0, 0.45), (0.42, 0.42, 0.04), grid)
        b.box((0, 0.19, 0.7), (0.42, 0.04, 0.5), grid)
        for sx in (-1, 1):
            for sy in (-1, 1):
                b.box((0.18 * sx, 0.18 * sy, 0.22), (0.04, 0.04, 0.44), max(1, grid // 2))
    else:   # shelf: two sides and four boards
        for sx in (-1, 1):
            b.box((0.36 * sx, 0, 0.8), (0.03, 0.35, 1.6), grid)
        for z in (0.05, 0.55, 1.05, 1.55):
            b.box((0, 0, z), (0.69, 0.35, 0.03), grid)
    return b


def _texture(number):
    colours = [(200, 60, 40), (40, 140, 60), (50, 80, 190), (210, 180, 60), (120, 90, 60)]
    a, c = colours[number % 5], colours[(number + 2) % 5]
    return png_bytes(16, 16, lambda x, y: a if (x // 4 + y // 4) % 2 else c)


def _write(path, data):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb" if isinstance(data, bytes) else "w") as f:
        f.write(data)


def _config(name):
    return ("<?xml version=\"1.0\"?>\n<model>\n  <name>%s</name>\n  <version>1.0</version>\n"
            "  <sdf version=\"1.6\">model.sdf</sdf>\n  <description>generated</description>\n"
            "</model>\n" % name)


def _mesh(uri, scale):
    return ("<mesh><uri>%s</uri>%s</mesh>"
            % (uri, "<scale>%g %g %g</scale>" % scale if scale else ""))


def model_name(number):
    return "gen_%s_%03d" % (_KINDS[number % len(_KINDS)], number)


def write_model(models, number):
    """Write model folder ``number`` (its kind: number % 5) into ``models``; its name."""
    name = model_name(number)
    kind = _KINDS[number % len(_KINDS)]
    folder = os.path.join(models, name)
    _write(os.path.join(folder, "meshes", "skin.png"), _texture(number))
    _write(os.path.join(folder, "meshes", "%s.dae" % name),
           _solid(kind, number, 1).collada("skin.png"))
    collision_file = name
    if number % 3 == 0:       # a coarser collision mesh of its own
        collision_file = name + "_collision"
        _write(os.path.join(folder, "meshes", collision_file + ".dae"),
               _solid(kind, number, 0).collada("skin.png"))
    scale = (0.9, 0.9, 1.1) if number % 4 == 1 else None
    sdf = """<?xml version="1.0"?>
<sdf version="1.6">
  <model name="%(name)s">
    <static>true</static>
    <link name="link">
      <collision name="collision"><geometry>%(collision)s</geometry></collision>
      <visual name="visual"><geometry>%(visual)s</geometry></visual>
    </link>
  </model>
</sdf>
""" % dict(name=name,
           collision=_mesh("model://%s/meshes/%s.dae" % (name, collision_file), scale),
           visual=_mesh("model://%s/meshes/%s.dae" % (name, name), scale))
    _write(os.path.join(folder, "model.sdf"), sdf)
    _write(os.path.join(folder, "model.config"), _config(name))
    return name


def _set_model(models, number, kinds):
    """A table with two chairs, by nested includes."""
    name = "gen_set_%02d" % number
    table = model_name(2 + 5 * (number % (kinds // 5)))      # a table's number: 2 mod 5
    chair = model_name(3 + 5 * (number % (kinds // 5)))      # a chair's: 3 mod 5
    parts = ["<include><uri>model://%s</uri><name>table</name><pose>0 0 0 0 0 0</pose></include>"
             % table]
    for k, (y, yaw) in enumerate(((-0.3, 0.0), (0.3, math.pi))):
        parts.append("<include><uri>model://%s</uri><name>chair_%d</name>"
                     "<pose>0 %g 0 0 0 %.6f</pose></include>" % (chair, k, y, yaw))
    sdf = ("<?xml version=\"1.0\"?>\n<sdf version=\"1.6\">\n  <model name=\"%s\">\n"
           "    <static>true</static>\n    %s\n  </model>\n</sdf>\n" % (name, "\n    ".join(parts)))
    folder = os.path.join(models, name)
    _write(os.path.join(folder, "model.sdf"), sdf)
    _write(os.path.join(folder, "model.config"), _config(name))
    return name


def grid_cells():
    """(x, y) of the grid cells a model may stand on, in a fixed order: 10 x 10 m, the
    spawn square (|x|, |y| < CLEAR) left out."""
    cells = []
    for j in range(11):
        for i in range(11):
            x, y = -5.0 + SPACING * i, -5.0 + SPACING * j
            if abs(x) < CLEAR and abs(y) < CLEAR:
                continue
            cells.append((x, y))
    return cells


def write_mesh_world(folder, includes=INCLUDES, kinds=MODEL_KINDS):
    """Write the world and its models into ``folder``; (world file, models folder)."""
    models = os.path.join(folder, "models")
    names = [write_model(models, n) for n in range(kinds)]
    names += [_set_model(models, n, kinds) for n in range(SETS if kinds >= 5 else 0)]
    cells = grid_cells()
    if includes > len(cells):
        raise ValueError("at most %d includes fit the grid" % len(cells))
    order = sorted(range(len(cells)), key=lambda k: (k * 37) % len(cells))   # a fixed shuffle
    lines = ["<include><uri>model://ground_plane</uri></include>"]
    for k in range(includes):
        x, y = cells[order[k]]
        lines.append("<include><uri>model://%s</uri><name>m%03d</name>"
                     "<pose>%g %g 0 0 0 %.4f</pose></include>"
                     % (names[k % len(names)], k, x, y, (k * 0.7) % (2 * math.pi)))
    world = os.path.join(folder, "mesh_world.world")
    _write(world, "<?xml version=\"1.0\"?>\n<sdf version=\"1.6\">\n  <world name=\"mesh_world\">\n"
           "    %s\n  </world>\n</sdf>\n" % "\n    ".join(lines))
    return world, models


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: mesh_world.py FOLDER")
    world_file, model_folder = write_mesh_world(sys.argv[1])
    print("GAZEBO_MODEL_PATH=%s %s" % (model_folder, world_file))
