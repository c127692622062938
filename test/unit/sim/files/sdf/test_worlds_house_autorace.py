"""turtlebot3_house and turtlebot3_autorace (doc/turtlebot3.md 4.3, 4.5), spawns among their
obstacles (spawn_check) and the turtlebot3_gazebo launch names (doc/turtlebot3.md 4.1). No ROS
master.

Every file in worlds/ passing `ign sdf -k` and loading is test_world_sdf.py's job (it globs them).
"""
import math
import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

import pybullet
import pytest
import yaml

from tutorial_turtlebot.sim.world.spawn_check import (FLOOR_CLEARANCE, find_obstacle,
                                                      footprint_radius)
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, urdf_path
from tutorial_turtlebot.sim.engine.client import Client
from tutorial_turtlebot.sim.engine.world_bullet import WORLD_COLLISION_GROUP, build_world
from tutorial_turtlebot.sim.files.sdf.world_catalogue import WORLDS, resolve_world
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world
import unit_paths

ROOT = unit_paths.ROOT
HOUSE = "turtlebot3_house::"
SCAN_Z = 0.182                 # burger scan plane, m
SCAN_BACK = 0.032              # burger base_scan is this far behind base_footprint, m
WHITE, YELLOW = (1.0, 1.0, 1.0, 1.0), (1.0, 1.0, 0.0, 1.0)
LANE_HALF = 0.1425             # half the 0.285 m between a lane's two lines, m
LINE_WIDTH = 0.02
LARGEST_FOOTPRINT = 0.24       # m: waffle's (0.238), the widest TurtleBot3


@pytest.fixture(scope="module")
def house():
    return load_world(resolve_world("turtlebot3_house")[0])


@pytest.fixture(scope="module")
def autorace():
    return load_world(resolve_world("turtlebot3_autorace")[0])


def _built(world):
    """(body id -> shape name, client id) of ``world`` built in a fresh pybullet client."""
    cid = Client.connect()     # an engine Client (int(cid) is its id)
    bodies = build_world(world, cid)
    yield {body: name for name, body in bodies.items()}, cid
    pybullet.disconnect(physicsClientId=cid)


@pytest.fixture(scope="module")
def house_bullet(house):
    yield from _built(house)


@pytest.fixture(scope="module")
def autorace_bullet(autorace):
    yield from _built(autorace)


def cast(world, start, heading, length=3.5, pitch=0.0):
    """(shape name or None, distance m) of the first world surface along a ray."""
    names, cid = world
    end = (start[0] + length * math.cos(heading) * math.cos(pitch),
           start[1] + length * math.sin(heading) * math.cos(pitch),
           start[2] + length * math.sin(pitch))
    hit = pybullet.rayTestBatch([start], [end], collisionFilterMask=WORLD_COLLISION_GROUP,
                                physicsClientId=cid)[0]
    return names.get(hit[0]), hit[2] * length


def world_box(shape):
    """(xmin, xmax, ymin, ymax, zmin, zmax) of a box or cylinder turned only about z."""
    x, y, z, roll, pitch, yaw = shape.pose
    assert abs(roll) < 1e-9 and abs(pitch) < 1e-9, shape.name
    if shape.kind == "cylinder":
        r, h = shape.size
        return x - r, x + r, y - r, y + r, z - h / 2, z + h / 2
    sx, sy, sz = shape.size
    c, s = abs(math.cos(yaw)), abs(math.sin(yaw))
    hx, hy = (sx * c + sy * s) / 2, (sx * s + sy * c) / 2
    return x - hx, x + hx, y - hy, y + hy, z - sz / 2, z + sz / 2


# --- the house ----------------------------------------------------------------------------------

WALL_NAMES = ["Wall_%d" % n for n in (81, 82, 83, 84, 85, 86, 87, 88, 90, 91, 92, 93, 94, 95, 96,
                                      98, 99, 101, 104, 106, 108)]
FURNITURE = ("Mailbox", "bookshelf", "bookshelf_0", "bookshelf_1", "cabinet", "cabinet_0",
             "cabinet_1", "cafe_table", "cafe_table_0", "first_2015_trash_can",
             "first_2015_trash_can_0", "table", "table_marble")

# doc/turtlebot3.md 4.3: footprints at z < 0.5 (x range, y range) and the openings at ground level.
WALL_FOOTPRINTS = {
    "Wall_87": ((-7.58, -5.08), (-4.00, -3.85), None),
    "Wall_88": ((-5.23, -5.08), (-4.00, 1.00), None),
    "Wall_98": ((-7.58, -5.08), (0.85, 1.00), ("x", -6.76, -5.86)),
    "Wall_99": ((-5.22, -5.08), (0.85, 5.35), ("y", 2.11, 4.52)),
    "Wall_101": ((-0.12, 0.03), (0.85, 5.35), None),
    "Wall_90": ((-0.12, 2.38), (0.85, 1.00), None),
    "Wall_104": ((2.23, 2.38), (0.85, 5.35), ("y", 4.18, 5.08)),
    "Wall_91": ((2.23, 2.38), (-0.25, 1.00), ("y", -0.05, 0.85)),
    "Wall_106": ((4.83, 7.58), (-0.25, -0.10), ("x", 5.77, 6.67)),
    "Wall_93": ((4.83, 4.97), (-5.35, -0.10), None),
    "Wall_94": ((4.83, 7.58), (-5.35, -5.20), None),
    "Wall_108": ((-5.12, 2.38), (-0.25, -0.10), ("x", 0.66, 1.56)),
    "Wall_92": ((2.23, 4.97), (-0.25, -0.10), None),
}
FOOTPRINT_TOLERANCE = 0.02     # m: the facts table rounds to 0.01


def wall_pieces(world, wall, below=None):
    pieces = [s for s in world.collisions if s.name.startswith(HOUSE + wall + "::")]
    if below is not None:
        pieces = [s for s in pieces if world_box(s)[4] < below]
    return pieces


def test_house_models_and_names(house):
    assert house.models == ("ground_plane", "turtlebot3_house")
    links = {s.name.split("::")[1] for s in house.shapes if s.name.startswith(HOUSE)}
    assert links == set(WALL_NAMES) | set(FURNITURE)
    assert all(s.static for s in house.shapes)
    assert len(house.collisions) == 113           # the ground plane and 112 house pieces


def test_walls_are_0_15_thick_and_2_5_high_except_wall_108(house):
    for wall in WALL_NAMES:
        pieces = wall_pieces(house, wall)
        assert pieces and all(p.kind == "box" and p.size[1] == pytest.approx(0.15) for p in pieces)
        top = max(world_box(p)[5] for p in pieces)
        assert top == pytest.approx(1.0 if wall == "Wall_108" else 2.5), wall
        assert min(world_box(p)[4] for p in pieces) == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("wall", sorted(WALL_FOOTPRINTS))
def test_wall_footprint_and_opening_at_the_scan_plane(house, wall):
    (x0, x1), (y0, y1), opening = WALL_FOOTPRINTS[wall]
    boxes = [world_box(p) for p in wall_pieces(house, wall, below=SCAN_Z)]
    assert min(b[0] for b in boxes) == pytest.approx(x0, abs=FOOTPRINT_TOLERANCE)
    assert max(b[1] for b in boxes) == pytest.approx(x1, abs=FOOTPRINT_TOLERANCE)
    assert min(b[2] for b in boxes) == pytest.approx(y0, abs=FOOTPRINT_TOLERANCE)
    assert max(b[3] for b in boxes) == pytest.approx(y1, abs=FOOTPRINT_TOLERANCE)
    axis = 0 if (x1 - x0) > (y1 - y0) else 2
    spans = sorted((b[axis], b[axis + 1]) for b in boxes)
    gaps = [(a[1], b[0]) for a, b in zip(spans, spans[1:]) if b[0] - a[1] > 0.05]
    if opening is None:
        assert gaps == []
    else:
        (g0, g1), = gaps
        assert "xy"[axis // 2] == opening[0]
        assert (g0, g1) == pytest.approx(opening[1:], abs=FOOTPRINT_TOLERANCE)
        above = [world_box(p) for p in wall_pieces(house, wall) if world_box(p)[4] >= 1.9]
        if wall != "Wall_108":     # a door: open from 0 to 2.0 m, a lintel above
            lintel, = [b for b in above if b[axis] <= g0 + 0.01 and b[axis + 1] >= g1 - 0.01]
            assert lintel[4] == pytest.approx(2.0)


def test_outer_walls_close_the_house_at_the_scan_plane(house):
    """North y 5.19..5.35, west x -7.58..-7.42, east x 7.42..7.58: sills where the windows are."""
    def extent(walls, axis):
        boxes = [world_box(p) for w in walls for p in wall_pieces(house, w, below=SCAN_Z)]
        return min(b[axis] for b in boxes), max(b[axis + 1] for b in boxes)
    assert extent(("Wall_81", "Wall_82", "Wall_83", "Wall_84"), 0) == pytest.approx(
        (-7.58, 7.58), abs=FOOTPRINT_TOLERANCE)
    assert extent(("Wall_85", "Wall_86"), 2) == pytest.approx((-4.0, 5.35),
                                                              abs=FOOTPRINT_TOLERANCE)
    assert extent(("Wall_95", "Wall_96"), 2) == pytest.approx((-5.35, 5.25),
                                                              abs=FOOTPRINT_TOLERANCE)
    sill, = [p for p in wall_pieces(house, "Wall_83") if p.name.endswith("::sill")]
    assert world_box(sill)[:2] == pytest.approx((-4.97, -0.14), abs=FOOTPRINT_TOLERANCE)
    assert world_box(sill)[4:] == pytest.approx((0.0, 0.5))


def test_scan_from_the_house_spawn(house_bullet):
    """From the Burger's scan origin at (-3.032, 1.0): Wall_101 ahead, Wall_99 behind, the low
    Wall_108 to the right, nothing within 3.5 m to the left."""
    origin = (WORLDS["turtlebot3_house"].spawn[0] - SCAN_BACK, 1.0, SCAN_Z)
    name, distance = cast(house_bullet, origin, 0.0)
    assert name == HOUSE + "Wall_101::wall" and distance == pytest.approx(2.907, abs=0.005)
    name, distance = cast(house_bullet, origin, math.pi)
    assert name.startswith((HOUSE + "Wall_99::", HOUSE + "Wall_88::"))
    assert distance == pytest.approx(2.043, abs=0.005)
    name, distance = cast(house_bullet, origin, -math.pi / 2)
    assert name == HOUSE + "Wall_108::wall_0" and distance == pytest.approx(1.100, abs=0.005)
    assert cast(house_bullet, origin, math.pi / 2)[0] is None


def test_low_wall_window_sill_and_gap(house_bullet):
    # Wall_108 is 1.0 m high: the laser meets it, a ray at 1.2 m passes over into the yard.
    assert cast(house_bullet, (-3.0, 1.0, 0.9), -math.pi / 2)[0] == HOUSE + "Wall_108::wall_0"
    assert cast(house_bullet, (-3.0, 1.0, 1.2), -math.pi / 2)[0] is None
    # ... and its 0.9 m gap (x 0.66..1.56) is open at every height.
    assert cast(house_bullet, (1.11, 0.5, SCAN_Z), -math.pi / 2)[0] is None
    # Wall_83's window: the sill stops the laser, the window above it is open.
    name, distance = cast(house_bullet, (-3.5, 4.5, SCAN_Z), math.pi / 2)
    assert name == HOUSE + "Wall_83::sill" and distance == pytest.approx(0.7, abs=0.005)
    assert cast(house_bullet, (-3.5, 4.5, 1.0), math.pi / 2)[0] is None
    # Wall_98's door (x -6.76..-5.86) is open up to 2.0 m, then the lintel.
    assert cast(house_bullet, (-6.3, 2.0, 1.9), -math.pi / 2)[0] is None
    assert cast(house_bullet, (-6.3, 2.0, 2.1), -math.pi / 2)[0] == HOUSE + "Wall_98::lintel"


def test_furniture_at_the_scan_plane(house_bullet):
    # table: legs (r 0.02) at the scan plane, the top at 1.0 m above a robot under it
    name, distance = cast(house_bullet, (-2.657 + 0.68 - 1.0, 2.424 + 0.38, SCAN_Z), 0.0)
    assert name == HOUSE + "table::link::front_left_leg"
    assert distance == pytest.approx(1.0 - 0.02, abs=0.005)
    name, distance = cast(house_bullet, (-2.657, 2.424, 0.5), 0.0, pitch=math.pi / 2)
    assert name == HOUSE + "table::link::surface" and distance == pytest.approx(0.485, abs=0.005)
    # cafe table: only the 0.042 m column at the scan plane
    name, distance = cast(house_bullet, (6.359 - 1.0, -3.192, SCAN_Z), 0.0)
    assert name == HOUSE + "cafe_table::link::column"
    assert distance == pytest.approx(1.0 - 0.021, abs=0.005)
    # bookshelf: at the scan plane the laser passes between the bottom board and the lowest
    # shelf (0.43 m) to the back panel
    name, _ = cast(house_bullet, (-6.544, 4.5, SCAN_Z), math.pi / 2)
    assert name == HOUSE + "bookshelf::link::back"
    # trash can, mailbox post, marble table leg
    name, distance = cast(house_bullet, (1.883 - 1.0, 1.912, SCAN_Z), 0.0)
    assert name == HOUSE + "first_2015_trash_can::link::collision"
    assert distance == pytest.approx(1.0 - 0.229, abs=0.005)
    post = cast(house_bullet, (0.883, 0.5, SCAN_Z), -math.pi / 2)[0]
    assert post == HOUSE + "Mailbox::link::post"
    name, _ = cast(house_bullet, (3.0, 2.138, SCAN_Z), 0.0)
    assert name.startswith(HOUSE + "table_marble::link::leg_")


def test_furniture_poses(house):
    def xy(name):
        return house.shape(HOUSE + name).pose[:2]
    assert xy("table::link::front_left_leg") == pytest.approx((-2.657 + 0.68, 2.424 + 0.38),
                                                              abs=0.002)
    assert xy("cafe_table::link::column") == pytest.approx((6.359, -3.192), abs=0.001)
    assert xy("cafe_table_0::link::column") == pytest.approx((6.359, -2.278), abs=0.001)
    for name, (x, y) in (("bookshelf", (-6.544, 5.195)), ("bookshelf_0", (4.724, 5.179)),
                         ("bookshelf_1", (5.644, 5.179))):
        back = house.shape(HOUSE + name + "::link::back")
        assert back.pose[:2] == pytest.approx((x, y + 0.005), abs=0.001)
        assert back.size == pytest.approx((0.9, 0.01, 1.2))
    for name, (x, y) in (("cabinet", (-5.472, -1.576)), ("cabinet_0", (-5.473, -2.065)),
                         ("cabinet_1", (-7.184, 1.248))):
        assert xy(name + "::link::middle_plate") == pytest.approx((x, y), abs=0.001)
    back = house.shape(HOUSE + "cabinet_1::link::back_plate")         # yaw -90 degrees
    assert back.pose[:2] == pytest.approx((-7.184, 1.248 - 0.235), abs=0.001)
    for name, (x, y) in (("first_2015_trash_can", (1.883, 1.912)),
                         ("first_2015_trash_can_0", (-4.694, 4.894))):
        can = house.shape(HOUSE + name + "::link::collision")
        assert can.kind == "cylinder" and can.pose[:2] == pytest.approx((x, y), abs=0.001)
        assert (can.size[1] == pytest.approx(0.74, abs=0.01)
                and can.pose[2] == pytest.approx(0.368, abs=0.001))
    post = house.shape(HOUSE + "Mailbox::link::post")
    assert post.pose[:2] == pytest.approx((0.883, -0.576), abs=0.001)
    top = house.shape(HOUSE + "table_marble::link::top")
    assert top.pose[0] == pytest.approx(4.883, abs=0.001)
    assert world_box(top)[5] == pytest.approx(0.965, abs=0.005)
    legs = [s for s in house.collisions if s.name.startswith(HOUSE + "table_marble::link::leg")]
    assert len(legs) == 4 and all(world_box(leg)[4] == pytest.approx(0.0, abs=1e-6) for leg in legs)


# --- AutoRace -----------------------------------------------------------------------------------

AUTORACE_SPAWN = WORLDS["turtlebot3_autorace"].spawn
TUNNEL_WALLS = {                # doc/turtlebot3.md 4.5: (x range, y range)
    "tunnel::link::wall_west": ((-1.945, -1.945), (-1.986, 0.014)),
    "tunnel::link::wall_south": ((-1.965, 0.035), (-1.971, -1.971)),
    "tunnel::link::wall_east": ((-0.021, -0.021), (-1.62, -0.08)),
    "tunnel::link::wall_north": ((-1.61, -0.03), (-0.121, -0.121)),
}
OBSTACLES = ((-0.618, -1.339), (-1.365, -1.414), (-1.141, -0.627))
SIGNS = {"traffic_parking": (1.84, 1.27, -0.356), "traffic_tunnel": (-1.544, -0.08, 0.0),
         "traffic_stop": (-2.05, 0.65, 0.0)}


def lines(world, colour=None):
    out = [s for s in world.visuals if s.name.startswith("course::link::")
           and s.name != "course::link::visual"]
    return [s for s in out if colour is None or s.rgba == colour]


def line_ends(shape):
    """The two ends (x, y) of a line's centre: a box's, or an arc polyline's (outer edge out,
    inner edge back)."""
    x, y, _, _, _, yaw = shape.pose
    if shape.kind == "box":
        dx, dy = shape.size[0] / 2 * math.cos(yaw), shape.size[0] / 2 * math.sin(yaw)
        return (x - dx, y - dy), (x + dx, y + dy)
    p, n = shape.points, len(shape.points)
    k = n // 2
    ends = []
    for a, b in ((p[0], p[-1]), (p[k - 1], p[k])):
        ends.append((x + (a[0] + b[0]) / 2, y + (a[1] + b[1]) / 2))
    return tuple(ends)


def test_autorace_models_and_no_ground_plane(autorace):
    assert autorace.models == ("course", "ground2", "tunnel") + tuple(SIGNS)
    floor = autorace.shape("course::link::collision")
    assert floor.kind == "plane" and floor.size == (4.0, 4.0)
    assert floor.pose == pytest.approx((0,) * 6)
    assert floor.rgba[:3] == pytest.approx((10 / 255,) * 3, abs=0.005)
    ground2 = autorace.shape("ground2::link::collision")
    assert ground2.kind == "box" and ground2.size == (8.0, 8.0, 0.01)
    assert ground2.pose[:3] == pytest.approx((0, 0, -0.1))


def test_lines_are_thin_visuals_on_the_floor(autorace):
    all_lines = lines(autorace)
    assert all_lines and all(not s.collision and s.twin is None for s in all_lines)
    assert {s.rgba for s in all_lines} == {WHITE, YELLOW}
    for s in all_lines:
        if s.kind == "box":
            assert s.size[1] == pytest.approx(LINE_WIDTH) and s.size[2] <= 0.002
            assert 0.0 < s.pose[2] - s.size[2] / 2 and s.pose[2] + s.size[2] / 2 <= 0.003
        else:
            assert s.kind == "polyline" and 0.0 < s.pose[2] and s.pose[2] + s.size[0] <= 0.003
        assert all(abs(c) <= 2.0 for end in line_ends(s) for c in end)      # on the 4 x 4 floor


@pytest.mark.parametrize("colour, side", [(WHITE, -1), (YELLOW, 1)], ids=["white", "yellow"])
def test_spawn_lane_white_right_yellow_left(autorace, colour, side):
    """At the spawn, facing +x: the nearest line on that side runs along +x 0.1425 m to the
    right (white) or left (yellow)."""
    x, y, yaw = AUTORACE_SPAWN
    assert yaw == 0.0
    under = []
    for s in lines(autorace, colour):
        (x0, y0), (x1, y1) = line_ends(s)
        if s.kind == "box" and min(x0, x1) < x < max(x0, x1) and abs(s.pose[1] - y) < 0.5:
            under.append((s.pose[1], abs(y1 - y0)))
    (line_y, drift), = under
    assert drift < 1e-9                                              # the lane runs along x
    assert line_y - y == pytest.approx(side * LANE_HALF, abs=0.005)


@pytest.mark.parametrize("colour", [WHITE, YELLOW], ids=["white", "yellow"])
def test_lines_join_into_the_loop_through_the_tunnel(autorace, colour):
    """Each colour's pieces join end to end into one path from the tunnel's south-east mouth
    around the course to its north-west mouth (the tunnel closes the loop)."""
    pieces = [list(line_ends(s)) for s in lines(autorace, colour)]
    ends = [end for piece in pieces for end in piece]
    loose = [e for e in ends if sum(math.dist(e, o) < 1e-3 for o in ends) == 1]
    assert len(loose) == 2 and len(ends) == 2 * len(pieces)
    south = min(loose, key=lambda e: e[1])
    north = max(loose, key=lambda e: e[1])
    side = -1 if colour == WHITE else 1
    assert south == pytest.approx((0.04, AUTORACE_SPAWN[1] + side * LANE_HALF), abs=0.005)
    assert north[1] == pytest.approx(-0.096, abs=0.005)                     # tunnel's north face
    assert -1.92 < north[0] < -1.61                                          # its mouth


def test_straights_come_in_pairs_0_285_apart(autorace):
    whites = [s for s in lines(autorace, WHITE) if s.kind == "box"]
    yellows = [s for s in lines(autorace, YELLOW) if s.kind == "box"]
    assert len(whites) == len(yellows) == 4
    for w in whites:
        gaps = [math.dist(w.pose[:2], y.pose[:2]) for y in yellows
                if abs(math.sin(w.pose[5] - y.pose[5])) < 1e-9]
        assert min(gaps) == pytest.approx(2 * LANE_HALF, abs=0.001)


def test_tunnel_walls_obstacles_and_signs(autorace):
    for name, ((x0, x1), (y0, y1)) in TUNNEL_WALLS.items():
        b = world_box(autorace.shape(name))
        thickness = min(b[1] - b[0], b[3] - b[2])
        assert thickness == pytest.approx(0.05) and b[4:] == pytest.approx((0.0, 0.5))
        assert ((b[0] + b[1]) / 2, (b[2] + b[3]) / 2) == pytest.approx(
            ((x0 + x1) / 2, (y0 + y1) / 2), abs=0.001)
        assert max(b[1] - b[0], b[3] - b[2]) == pytest.approx(
            max(x1 - x0, y1 - y0), abs=0.001)
    for i, (x, y) in enumerate(OBSTACLES):
        obstacle = autorace.shape("tunnel::link::obstacle_%d" % i)
        assert obstacle.kind == "cylinder" and obstacle.size == pytest.approx((0.1, 0.464))
        assert obstacle.pose[:3] == pytest.approx((x, y, 0.232))
    for name, (x, y, yaw) in SIGNS.items():
        board = autorace.shape(name + "::link::collision")
        assert board.size == pytest.approx((0.12, 0.025, 0.25))
        assert board.pose == pytest.approx((x, y, 0.125, 0, 0, yaw))


def test_laser_at_the_spawn_sees_the_tunnel_not_the_lines(autorace_bullet):
    x, y, _ = AUTORACE_SPAWN
    origin = (x - SCAN_BACK, y, SCAN_Z)
    assert cast(autorace_bullet, origin, 0.0)[0] is None            # the lane ahead is open
    name, distance = cast(autorace_bullet, origin, math.pi)         # back through the mouth
    assert name == "tunnel::link::wall_west"
    assert distance == pytest.approx(origin[0] + 1.92, abs=0.005)
    name, distance = cast(autorace_bullet, (x, y, 1.0), 0.0, pitch=-math.pi / 2)
    assert name == "course::link::collision" and distance == pytest.approx(1.0, abs=1e-3)


def test_camera_view_at_the_spawn():
    """What the AutoRace burger's camera (doc/turtlebot3.md 4.5: 320x240, HFOV 1.085595, pitched 10
    degrees down) shows at the spawn, rendered by the sim's own camera (what /camera/image
    publishes): yellow lane pixels in the left half, white ones in the right, dark floor
    between."""
    sim = Simulation(SimConfig(model="burger", world="turtlebot3_autorace", camera=True))
    try:
        for _ in range(40):                                      # settle on the wheels
            sim.step()
        rgb, _ = sim.robot.camera_image()
    finally:
        sim.close()
    height, width, _ = rgb.shape
    assert (width, height) == (320, 240)
    bottom = rgb[height // 2:].astype(int)                       # the floor in front
    yellow = (bottom[:, :, 0] > 180) & (bottom[:, :, 1] > 180) & (bottom[:, :, 2] < 80)
    white = (bottom > 200).all(axis=2)
    dark = (bottom < 40).all(axis=2)
    half = width // 2
    assert yellow[:, :half].sum() > 40 and yellow[:, half:].sum() == 0
    assert white[:, half:].sum() > 40 and white[:, :half].sum() == 0
    assert dark[-1, half - 20:half + 20].all()                   # the lane itself is dark


def test_robot_stands_on_the_course_at_the_spawn():
    sim = Simulation(SimConfig(model="burger", world="turtlebot3_autorace", camera=True))
    try:
        for _ in range(400):                                     # 1 s of sim time
            sim.step()
        (px, py, pz), _ = sim.robot.ground_truth()
    finally:
        sim.close()
    assert (px, py) == pytest.approx(AUTORACE_SPAWN[:2], abs=0.005)
    assert pz == pytest.approx(0.0, abs=0.005)


# --- a spawn among obstacles: find_obstacle's plan measure, and no refusal ---------------------

@pytest.fixture(scope="module")
def tb3_world():
    return load_world(resolve_world("turtlebot3_world")[0])


def inside(world, x, y, radius):
    """The name of the shape whose inside (x, y) is in, by find_obstacle's plan measure."""
    hit = find_obstacle(world, x, y, radius)
    assert hit is not None and hit[1] <= 0.0, hit
    return hit[0].name


def test_a_spawn_inside_a_pillar_is_taken_with_one_warning(tb3_world):
    """Gazebo refuses no spawn for overlap (spawn_check): the robot is spawned, and one line
    names the model and a z_pos. Its root is in the pillar (radius 0.15 m, axis at x -1.1), its
    footprint (0.124 m) partly out: a pillar holding all of it is stood on (the landing rule)."""
    assert inside(tb3_world, -1.0, 0.0, 0.105) == "ros_symbol::symbol::one_two"
    sim = Simulation(SimConfig(world="turtlebot3_world", x=-1.0, y=0.0))
    try:
        (warning,) = sim.robot.warnings
        assert warning.startswith("at (-1.0, 0.0, 0.0) it overlaps ros_symbol by ")
        assert "z_pos" in warning and "\n" not in warning
    finally:
        sim.close()


def test_a_spawn_near_a_pillar_is_measured_in_plan(tb3_world):
    # centre 0.2 m from the pillar's axis: 0.05 m from its surface
    shape, distance = find_obstacle(tb3_world, -1.1, 0.2, 0.105)
    assert shape.name == "ros_symbol::symbol::one_two" and distance == pytest.approx(0.05)
    assert find_obstacle(tb3_world, -1.1, 0.2, 0.04) is None     # a thinner robot fits


@pytest.mark.parametrize("x, y, obstacle", [
    (3.0, 0.0, "ros_symbol::symbol::head"),                     # a polyline (hexagonal prism)
    (-2.7, -0.5, "ros_symbol::symbol::body_sw"),                # a turned box
])
def test_inside_arena_pieces(tb3_world, x, y, obstacle):
    assert inside(tb3_world, x, y, 0.105) == obstacle


@pytest.mark.parametrize("name", sorted(WORLDS))
def test_the_real_spawns_are_clear(name):
    world = load_world(resolve_world(name)[0])
    x, y, _ = WORLDS[name].spawn
    assert find_obstacle(world, x, y, LARGEST_FOOTPRINT) is None


def test_house_and_autorace_obstacles(house, autorace):
    assert inside(house, -5.15, -1.0, 0.105) == "turtlebot3_house::Wall_88::wall"
    assert inside(autorace, -0.618, -1.339, 0.105) == "tunnel::link::obstacle_0"
    # under the table (its top is at 1.0 m) and between its legs: clear
    assert find_obstacle(house, -2.657, 2.424, 0.105) is None
    # on a lane line: the lines are paint, not obstacles
    assert find_obstacle(autorace, 0.245, AUTORACE_SPAWN[1] - LANE_HALF, 0.105) is None


def test_tilted_and_round_shapes(tmp_path):
    path = tmp_path / "shapes.world"
    path.write_text(
        '<sdf version="1.6"><world name="w"><model name="m"><static>true</static><link name="l">'
        # a 2 m plank, rolled 90 degrees: 0.4 m wide in y, 0.1 m high
        '<collision name="plank"><pose>0 0 0.05 1.5708 0 0</pose><geometry><box>'
        '<size>2 0.1 0.4</size></box></geometry></collision>'
        # a ball resting 0.5 m up: below it the robot (0.2 m high) fits
        '<collision name="ball"><pose>5 0 0.5 0 0 0</pose><geometry><sphere><radius>0.25'
        '</radius></sphere></geometry></collision>'
        # a ball on the floor
        '<collision name="rock"><pose>-5 0 0.1 0 0 0</pose><geometry><sphere><radius>0.2'
        '</radius></sphere></geometry></collision>'
        # a 5 mm mat: under FLOOR_CLEARANCE, the robot drives onto it
        '<collision name="mat"><pose>0 5 0.0025 0 0 0</pose><geometry><box><size>1 1 0.005'
        '</size></box></geometry></collision>'
        '</link></model></world></sdf>')
    world = load_world(str(path))
    assert 0.005 < FLOOR_CLEARANCE
    assert inside(world, 0.5, 0.0, 0.1) == "m::l::plank"
    shape, distance = find_obstacle(world, 0.5, 0.3, 0.3)
    assert shape.name == "m::l::plank" and distance == pytest.approx(0.1, abs=0.01)
    assert find_obstacle(world, 0.5, 0.6, 0.3) is None
    assert find_obstacle(world, 5.0, 0.0, 0.1) is None
    assert inside(world, -5.1, 0.0, 0.05) == "m::l::rock"
    assert find_obstacle(world, 0.0, 5.0, 0.1) is None


def test_footprint_radius_of_the_models():
    burger = footprint_radius(read_urdf(urdf_path("burger")))
    waffle = footprint_radius(read_urdf(urdf_path("waffle")))
    assert 0.105 < burger < 0.13               # 0.14 m square body, caster behind
    assert 0.2 < waffle < LARGEST_FOOTPRINT     # 0.266 m square body centred 0.064 m behind
    assert footprint_radius(read_urdf(urdf_path("waffle_pi"))) == pytest.approx(waffle, abs=0.01)


# --- launch files -------------------------------------------------------------------------------

LAUNCHES = {                    # doc/turtlebot3.md 4.1: launch -> (world, x_pos, y_pos, z_pos)
    "turtlebot3_empty_world": ("empty", 0.0, 0.0, 0.0),
    "turtlebot3_world": ("turtlebot3_world", -2.0, -0.5, 0.0),
    "turtlebot3_house": ("turtlebot3_house", -3.0, 1.0, 0.0),
    "turtlebot3_autorace": ("turtlebot3_autorace", 0.245, -1.787, 0.0),
}


def launch_path(name):
    return os.path.join(ROOT, "launch", name + ".launch")


@pytest.mark.parametrize("name", sorted(LAUNCHES))
def test_launch_file_names_its_world_and_spawn(name):
    world, x, y, z = LAUNCHES[name]
    root = ElementTree.parse(launch_path(name)).getroot()
    defaults = {a.get("name"): a.get("default") for a in root.findall("arg")}
    assert {"model", "x_pos", "y_pos", "z_pos"} <= set(defaults)
    assert tuple(float(defaults[k]) for k in ("x_pos", "y_pos", "z_pos")) == (x, y, z)
    assert WORLDS[world].spawn[:2] == (x, y)
    include, = root.findall("include")
    assert include.get("file") == "$(find tutorial_turtlebot)/launch/sim.launch"
    assert include.get("pass_all_args") == "true"
    assert {a.get("name"): a.get("value") for a in include.findall("arg")} == {"world": world}
    sim_args = {a.get("name") for a in ElementTree.parse(launch_path("sim")).getroot()
                .findall("arg")}
    assert set(defaults) <= sim_args                  # pass_all_args: sim.launch knows them all


@pytest.mark.parametrize("name", sorted(LAUNCHES))
def test_roslaunch_resolves_world_spawn_and_model(name):
    """roslaunch --dump-params (no master): the sim node's parameters as launched."""
    if shutil.which("roslaunch") is None:
        pytest.fail("'roslaunch' not found: install ROS 1 (tools/setup.sh) or source its setup")
    env = dict(os.environ)
    env["ROS_PACKAGE_PATH"] = os.pathsep.join(p for p in (ROOT, env.get("ROS_PACKAGE_PATH")) if p)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (os.path.join(ROOT, "src"),
                                                    env.get("PYTHONPATH")) if p)
    env["PATH"] = os.path.dirname(sys.executable) + os.pathsep + env.get("PATH", "")
    env.pop("TURTLEBOT3_MODEL", None)
    env["ROS_MASTER_URI"] = "http://localhost:9"  # no master (a running sim would be refused)
    run = subprocess.run(["roslaunch", "--dump-params", launch_path(name)], capture_output=True,
                         text=True, timeout=60, env=env)
    assert run.returncode == 0, run.stdout + run.stderr
    params = yaml.safe_load(run.stdout)
    world, x, y, z = LAUNCHES[name]
    assert params["/gazebo/world"] == world
    assert (float(params["/gazebo/x_pos"]), float(params["/gazebo/y_pos"]),
            float(params["/gazebo/z_pos"])) == (x, y, z)
    assert params["/gazebo/model"] == "burger"
    autorace = name == "turtlebot3_autorace"
    # the AutoRace burger carries its camera; elsewhere the URDF's own (no ~camera param)
    assert params.get("/gazebo/camera") is (True if autorace else None)
    assert "camera_rgb_optical_frame" in params["/robot_description"] or not autorace
