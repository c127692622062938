"""World bodies in pybullet (world_bullet): what rays and a camera find. No ROS master."""
import math

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.sim.engine.world_bullet import (WORLD_COLLISION_GROUP, WORLD_FRICTION,
                                                        build_world)
from tutorial_turtlebot.sim.files.sdf.world_catalogue import WORLDS, resolve_world
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world

SCAN_Z = 0.182          # burger scan plane, m
SPAWN = WORLDS["turtlebot3_world"].spawn
HULL_MARGIN = 0.0015    # pybullet inflates convex hulls (polylines) by its 1 mm collision margin


@pytest.fixture
def tb3(client):
    return build_world(load_world(resolve_world("turtlebot3_world")[0]), client), client


def cast(cid, start, end, mask=WORLD_COLLISION_GROUP):
    """(body id or -1, distance from start in m) of the first hit on the segment start..end."""
    hit = pybullet.rayTestBatch([start], [end], collisionFilterMask=mask, physicsClientId=cid)[0]
    return hit[0], hit[2] * math.dist(start, end)


def cast_dir(cid, start, heading, length=3.5):
    end = (start[0] + length * math.cos(heading), start[1] + length * math.sin(heading), start[2])
    return cast(cid, start, end)


def test_one_body_per_collision(tb3):
    bodies, cid = tb3
    assert len(bodies) == 21 == pybullet.getNumBodies(physicsClientId=cid)
    assert len(set(bodies.values())) == 21


def test_nearest_pillar_from_the_spawn(tb3):
    """The pillar centred at (-1.1, 0) is 1.03 m from the spawn; its surface 0.15 m nearer."""
    bodies, cid = tb3
    x, y = SPAWN[:2]
    centre = math.hypot(-1.1 - x, 0.0 - y)
    assert centre == pytest.approx(1.03, abs=0.005)
    body, distance = cast_dir(cid, (x, y, SCAN_Z), math.atan2(0.0 - y, -1.1 - x))
    assert body == bodies["ros_symbol::symbol::one_two"]
    assert distance == pytest.approx(centre - 0.15, abs=1e-3)


def test_left_wall_from_the_spawn(tb3):
    """Looking along -x at y = -0.5 the ray meets the south-west inner face at x = -2.644."""
    bodies, cid = tb3
    x, y = SPAWN[:2]
    body, distance = cast_dir(cid, (x, y, SCAN_Z), math.pi)
    expected_x = -(2.540 - 0.5 * abs(y)) / math.cos(math.pi / 6)   # on n . p = 2.540
    assert expected_x == pytest.approx(-2.64, abs=0.01)
    assert body == bodies["ros_symbol::symbol::body_sw"]
    assert x - distance == pytest.approx(expected_x, abs=1e-3)


@pytest.mark.parametrize("start, face_x", [
    ((1.3, 0.0), 3.5 - 1.173),                           # past pillar three_two, onto the corner
    ((0.0, 0.5), 3.5 - 1.173 + 0.5 / math.sqrt(3)),      # between the pillar rows, onto a face
])
def test_green_head_looking_along_x(tb3, start, face_x):
    bodies, cid = tb3
    body, distance = cast_dir(cid, start + (SCAN_Z,), 0.0)
    assert body == bodies["ros_symbol::symbol::head"]
    assert start[0] + distance == pytest.approx(face_x, abs=HULL_MARGIN)


def test_walls_close_the_arena(tb3):
    """Above the pillars every ray from inside ends on the ring or a hexagon within the corner
    radius: the six wall boxes leave no gap."""
    bodies, cid = tb3
    walls = {body for name, body in bodies.items()
             if "::body_" in name or name.endswith(("_hand", "_foot", "::head"))}
    for degree in range(360):
        body, distance = cast_dir(cid, (0.0, 0.55, 0.7), math.radians(degree + 0.5))
        assert body in walls and distance < 2.933 + 0.55, degree


def test_ground_top_is_at_zero_and_without_end(tb3):
    """The ground plane, drawn 100 m square, collides far beyond that."""
    bodies, cid = tb3
    for x, y in ((0.5, 0.5), (20.0, -30.0), (49.5, 0.0), (60.0, 0.0), (-3000.0, 800.0)):
        body, distance = cast(cid, (x, y, 1.0), (x, y, -1.0))
        assert body == bodies["ground_plane::link::collision"]
        assert 1.0 - distance == pytest.approx(0.0, abs=1e-6)


def plane_world(tmp_path, plane, pose="0 0 0 0 0 0"):
    """A world of one static model at ``pose`` whose link has one ``plane`` (its <plane>
    element's inside) as its collision and its visual."""
    geometry = "<geometry><plane>%s</plane></geometry>" % plane
    path = tmp_path / "plane.world"
    path.write_text('<sdf version="1.6"><world name="w"><model name="floor"><static>true</static>'
                    '<pose>%s</pose><link name="l"><collision name="c">%s</collision><visual '
                    'name="v">%s</visual></link></model></world></sdf>'
                    % (pose, geometry, geometry))
    return load_world(str(path))


def drop_cube(cid, position, orientation=(0, 0, 0, 1), seconds=2.0, half=0.1):
    """(position, orientation) of a 1 kg cube of half side ``half`` let go at ``position``
    (m, world), after ``seconds`` under gravity (pybullet's 1/240 s step)."""
    pybullet.setGravity(0, 0, -9.8, physicsClientId=cid)
    shape = pybullet.createCollisionShape(pybullet.GEOM_BOX, halfExtents=(half,) * 3,
                                          physicsClientId=cid)
    cube = pybullet.createMultiBody(1.0, shape, basePosition=position,
                                    baseOrientation=orientation, physicsClientId=cid)
    for _ in range(round(seconds * 240)):
        pybullet.stepSimulation(physicsClientId=cid)
    return pybullet.getBasePositionAndOrientation(cube, physicsClientId=cid)


def test_a_cube_far_beyond_a_100_m_plane_lands_on_it(tmp_path, client):
    """Gazebo's plane is infinite: a cube let go at (5000, 5000), 50 times farther out than
    the plane is drawn, rests on it at its height, where it was let go."""
    bodies = build_world(plane_world(tmp_path, "<size>100 100</size>", "0 0 0.3 0 0 0"), client)
    low, high = pybullet.getAABB(bodies["floor::l::c"], physicsClientId=client)
    assert min(low) < -1e20 and max(high) > 1e20         # Bullet's plane: no bounds
    (x, y, z), _ = drop_cube(client, (5000.0, 5000.0, 1.0))
    assert z == pytest.approx(0.3 + 0.1, abs=2e-3)
    assert math.hypot(x - 5000.0, y - 5000.0) < 0.01


def test_a_tilted_plane_holds_a_cube_on_its_surface(tmp_path, client):
    """A plane of <normal> 0 -sin(0.2) cos(0.2) (an 11 degree slope, rising along +y) in a
    model raised 0.5 m: a cube set on it 100 m out, far beyond its drawn 4 m, stays on its
    surface (friction 1 holds it)."""
    slope = 0.2
    normal = np.array((0.0, -math.sin(slope), math.cos(slope)))
    bodies = build_world(plane_world(tmp_path, "<normal>0 %r %r</normal><size>4 4</size>"
                                     % tuple(normal[1:].tolist()), "0 0 0.5 0 0 0"), client)
    start = np.array((80.0, 60.0, 0.5)) + (60.0 * math.tan(slope)) * np.array((0, 0, 1))
    body, distance = cast(client, tuple(start + (0, 0, 1.0)), tuple(start - (0, 0, 1.0)))
    assert body == bodies["floor::l::c"] and distance == pytest.approx(1.0, abs=1e-4)
    orientation = pybullet.getQuaternionFromEuler((slope, 0.0, 0.0))
    position, _ = drop_cube(client, tuple(start + 0.11 * normal), orientation)
    off = np.array(position) - start
    assert float(off @ normal) == pytest.approx(0.1, abs=2e-3)      # on the surface
    assert np.linalg.norm(off - (off @ normal) * normal) < 0.01      # not sliding


def test_rays_outside_the_world_group_miss(tb3):
    _, cid = tb3
    assert cast(cid, SPAWN[:2] + (SCAN_Z,), (-5.0, SPAWN[1], SCAN_Z), mask=2)[0] == -1


def test_surfaces_and_filter(tb3):
    bodies, cid = tb3
    for body in bodies.values():
        info = pybullet.getDynamicsInfo(body, -1, physicsClientId=cid)
        assert info[0] == 0.0 and info[1] == WORLD_FRICTION and info[5] == 0.0   # mass, mu, e


def test_visual_colours(tb3):
    bodies, cid = tb3

    def rgba(name):
        return pybullet.getVisualShapeData(bodies[name], physicsClientId=cid)[0][7]
    assert rgba("ros_symbol::symbol::head") == pytest.approx((0, 1, 0, 1))
    assert rgba("ros_symbol::symbol::two_two") == pytest.approx((1, 1, 1, 1))
    assert rgba("ros_symbol::symbol::body_n") == pytest.approx((0.1, 0.1, 0.1, 1))


def test_camera_sees_the_green_head(tb3):
    _, cid = tb3
    view = pybullet.computeViewMatrix((0.0, 0.5, 0.3), (3.0, 0.5, 0.3), (0, 0, 1))
    projection = pybullet.computeProjectionMatrixFOV(60, 4 / 3, 0.05, 20)
    image = pybullet.getCameraImage(80, 60, view, projection, physicsClientId=cid)[2]
    r, g, b = np.reshape(image, (60, 80, 4))[30, 40, :3].astype(int)
    assert g > 100 and r < 30 and b < 30


def concave_world(tmp_path):
    """A U: 3 x 3 m with a 1 m wide notch from y = 1 up to the open top at y = 3."""
    corners = ("0 0", "3 0", "3 3", "2 3", "2 1", "1 1", "1 3", "0 3")
    points = "".join("<point>%s</point>" % p for p in corners)
    path = tmp_path / "u.world"
    path.write_text(
        '<sdf version="1.6"><world name="u"><model name="u"><static>true</static><link name="l">'
        '<collision name="c"><geometry><polyline>%s<height>0.5</height></polyline></geometry>'
        '</collision><visual name="v"><pose>10 0 0 0 0 0</pose><geometry><box><size>1 1 1</size>'
        '</box></geometry></visual></link></model></world></sdf>' % points)
    return load_world(str(path))


def test_concave_polyline_leaves_its_notch_empty(tmp_path, client):
    bodies = build_world(concave_world(tmp_path), client)
    u = bodies["u::l::c"]
    z = 0.25
    assert cast(client, (1.5, 5.0, z), (1.5, 1.2, z))[0] == -1          # down into the notch
    body, distance = cast(client, (1.5, 5.0, z), (1.5, -1.0, z))         # ... to its floor
    assert body == u and 5.0 - distance == pytest.approx(1.0, abs=HULL_MARGIN)
    body, distance = cast(client, (-1.0, 2.0, z), (4.0, 2.0, z))         # across the arms
    assert body == u and distance == pytest.approx(1.0, abs=HULL_MARGIN)
    body, distance = cast(client, (1.5, 2.0, z), (4.0, 2.0, z))          # from inside the notch
    assert body == u and distance == pytest.approx(0.5, abs=HULL_MARGIN)
    assert cast(client, (1.5, 2.0, 0.6), (1.5, 2.0, -0.1))[0] == -1      # floor of the notch open


def test_a_visual_without_collision_is_seen_but_not_hit(tmp_path, client):
    bodies = build_world(concave_world(tmp_path), client)
    ghost = bodies["u::l::v"]
    assert cast(client, (10.0, -3.0, 0.5), (10.0, 3.0, 0.5))[0] == -1
    assert pybullet.getVisualShapeData(ghost, physicsClientId=client)[0][7] == pytest.approx(
        (0.7, 0.7, 0.7, 1.0))
    # a camera 3 m in front of the 1 m box (at x 10, z 0) sees it in the middle of its image
    view = pybullet.computeViewMatrix((7.0, 0.0, 0.0), (10.0, 0.0, 0.0), (0, 0, 1))
    projection = pybullet.computeProjectionMatrixFOV(60, 1.0, 0.1, 20.0)
    _, _, _, _, seg = pybullet.getCameraImage(
        32, 32, view, projection, renderer=pybullet.ER_TINY_RENDERER, physicsClientId=client)
    assert np.asarray(seg).reshape(32, 32)[16, 16] == ghost
    # and nothing collides with it: a falling ball passes through it
    pybullet.setGravity(0, 0, -9.8, physicsClientId=client)
    ball = pybullet.createMultiBody(
        1.0, pybullet.createCollisionShape(pybullet.GEOM_SPHERE, radius=0.1,
                                           physicsClientId=client),
        basePosition=(10.0, 0.0, 1.0), physicsClientId=client)
    for _ in range(240):
        pybullet.stepSimulation(physicsClientId=client)
    assert pybullet.getBasePositionAndOrientation(ball, physicsClientId=client)[0][2] < -0.6


def test_a_static_mesh_beyond_one_pybullet_shape_is_built_in_chunks(tmp_path, client):
    """pybullet takes at most 131,072 vertices in one concave shape (beyond: a SystemError):
    a 2 x 1 m tiled floor of 2 * 300 * 150 = 90,000 triangles becomes three chunks, and a ray
    meets it at its top everywhere, first chunk and last alike."""
    from tutorial_turtlebot.sim.engine.world_bullet import TRIMESH_CHUNK
    nx, ny = 300, 150
    xs, ys = np.meshgrid(np.linspace(0.0, 2.0, nx + 1), np.linspace(0.0, 1.0, ny + 1))
    vertices = np.stack([xs.ravel(), ys.ravel(), np.full(xs.size, 0.3)], axis=1)
    index = np.arange(xs.size).reshape(ny + 1, nx + 1)
    a, b = index[:-1, :-1].ravel(), index[:-1, 1:].ravel()
    c, d = index[1:, :-1].ravel(), index[1:, 1:].ravel()
    faces = np.concatenate([np.stack([a, b, d], 1), np.stack([a, d, c], 1)]) + 1
    assert len(faces) > 2 * TRIMESH_CHUNK
    obj = tmp_path / "floor.obj"
    obj.write_text("".join("v %.4f %.4f %.4f\n" % tuple(v) for v in vertices)
                   + "".join("f %d %d %d\n" % tuple(f) for f in faces))
    world = tmp_path / "floor.world"
    world.write_text(
        '<sdf version="1.6"><world name="f"><model name="floor"><static>true</static><link '
        'name="l"><collision name="c"><geometry><mesh><uri>%s</uri></mesh></geometry>'
        '</collision></link></model></world></sdf>' % obj)
    bodies = build_world(load_world(str(world)), client)
    floor = bodies["floor::l::c"]
    assert pybullet.getNumJoints(floor, physicsClientId=client) == 2     # 3 chunks: base + 2
    for x, y in ((0.05, 0.05), (1.0, 0.5), (1.95, 0.95)):
        body, distance = cast(client, (x, y, 1.0), (x, y, 0.0))
        assert body == floor and distance == pytest.approx(0.7, abs=1e-3)
