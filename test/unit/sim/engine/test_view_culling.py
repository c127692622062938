"""engine/view_culling.py: the static bodies a camera cannot see are left out of its EGL image,
and the image stays the same. The frustum and shadow geometry without a renderer; then a
Waffle Pi in a small world of textured Collada models (bench/mesh_world.py's) through EGL.
No ROS master."""
import math

import numpy as np
import pybullet
import pytest

from texture_fixtures import mesh_world
from tutorial_turtlebot.sim.engine import rendering, view_culling, world_bullet
from tutorial_turtlebot.sim.engine.client import Client
from tutorial_turtlebot.sim.engine.view_culling import outside_frustum, with_shadows

# A camera at the origin looking along +x (optical frame: x right = -y, y down = -z, z = +x).
LOOK_X = np.column_stack([(0.0, -1.0, 0.0), (0.0, 0.0, -1.0), (1.0, 0.0, 0.0)])
HFOV, ASPECT, NEAR, FAR = math.radians(60.0), 0.75, 0.05, 10.0


def boxes(*centres, half=0.2):
    centres = np.asarray(centres, float)
    return centres - half, centres + half


def test_a_box_is_outside_only_when_wholly_beyond_a_plane_of_the_frustum():
    lows, highs = boxes((3, 0, 0),        # straight ahead
                        (-3, 0, 0),       # behind
                        (3, 3, 0),        # 45 degrees left: beyond the 30 degree half angle
                        (3, 1.8, 0),      # touching the left edge (30 degrees: y 1.73)
                        (12, 0, 0),       # beyond the far clip
                        (3, 0, 2.5),      # above the vertical field (22.5 degrees: z 1.24)
                        (0.02, 0, 0))     # straddling the near plane
    out = outside_frustum(lows, highs, (0, 0, 0), LOOK_X, HFOV, ASPECT, NEAR, FAR)
    assert out.tolist() == [False, True, True, False, True, True, False]


def test_the_frustum_turns_and_moves_with_the_camera():
    yaw = math.radians(90)                      # now looking along +y, from (1, 1, 0)
    turn = np.array([[math.cos(yaw), -math.sin(yaw), 0], [math.sin(yaw), math.cos(yaw), 0],
                     [0, 0, 1]])
    lows, highs = boxes((1, 4, 0), (4, 1, 0))
    out = outside_frustum(lows, highs, (1, 1, 0), turn @ LOOK_X, HFOV, ASPECT, NEAR, FAR)
    assert out.tolist() == [False, True]


def test_a_box_is_grown_by_the_shadow_it_casts_down_the_light():
    lows, highs = boxes((0, 0, 1.0), half=0.5)          # from z 0.5 to 1.5
    grown_lows, grown_highs = with_shadows(lows, highs, (1.0, 0.0, 1.0), floor=0.0)
    # the top corners' shadow reaches the floor 1.5 m further along -x
    assert grown_lows[0] == pytest.approx([-2.0, -0.5, -1.0])
    assert grown_highs[0] == pytest.approx([0.5, 0.5, 1.5])
    # a body that is behind the camera but whose shadow falls in front of it is not outside
    lows, highs = boxes((-0.5, 0, 3.0), half=0.3)
    assert outside_frustum(lows, highs, (0, 0, 0.1), LOOK_X, HFOV, ASPECT, NEAR, FAR)[0]
    lows, highs = with_shadows(lows, highs, (-1.0, 0.0, 1.0), floor=0.0)
    assert not outside_frustum(lows, highs, (0, 0, 0.1), LOOK_X, HFOV, ASPECT, NEAR, FAR)[0]


def test_the_plane_thickness_is_world_bullets():
    assert view_culling.PLANE_THICKNESS == world_bullet.PLANE_THICKNESS


# --- a Waffle Pi in a small textured world (EGL) -------------------------------------------------

# model (a mesh_world kind number) -> where it stands; the robot is at the origin facing +x
PLACES = [
    (0, "ahead", (3.0, 0.0)),          # a box, in view
    (0, "behind_twin", (-3.0, 0.0)),   # the same box's mesh behind: shares its drawing
    (1, "behind", (-3.0, 2.0)),        # a drum behind
    (2, "left", (0.5, 3.0)),           # a table to the left, out of the 62 degree view
    (4, "far_right", (2.0, -4.5)),     # a shelf to the right, out of view
]


@pytest.fixture
def textured_world(tmp_path, monkeypatch):
    """(Simulation, the world's body id of each PLACES name) of a Waffle Pi at the origin."""
    if not rendering.egl_available():
        pytest.skip("EGL does not render on this machine (see test_rendering)")
    from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
    models = str(tmp_path / "models")
    kinds = {number: mesh_world.write_model(models, number) for number, _, _ in PLACES}
    includes = ["<include><uri>model://ground_plane</uri></include>"]
    includes += ["<include><uri>model://%s</uri><name>%s</name><pose>%g %g 0 0 0 0</pose>"
                 "</include>" % (kinds[number], name, x, y) for number, name, (x, y) in PLACES]
    world = tmp_path / "small.world"
    world.write_text("<?xml version=\"1.0\"?>\n<sdf version=\"1.6\"><world name=\"small\">%s"
                     "</world></sdf>\n" % "".join(includes))
    monkeypatch.setenv("GAZEBO_MODEL_PATH", models)
    sim = Simulation(SimConfig(model="waffle_pi", world=str(world), x=0.0, y=0.0, yaw=0.0))
    bodies = {name: sim.physics.world_bodies["%s::link::collision" % name]
              for _, name, _ in PLACES}
    yield sim, bodies
    sim.close()


def _images(sim, culled):
    """(rgb, depth) of the robot's camera with or without view culling."""
    camera = sim.robot.camera
    keep = camera.view_culling
    if not culled:
        camera.view_culling = None
    try:
        return camera.render(*sim.robot.camera_pose(), depth=True)
    finally:
        camera.view_culling = keep


def _differing_pixels(a, b):
    rgb_a, depth_a = a
    rgb_b, depth_b = b
    return int(np.count_nonzero(np.any(rgb_a != rgb_b, axis=2)
                                | ~np.isclose(depth_a, depth_b, equal_nan=True)))


def test_bodies_out_of_view_are_left_out_and_the_image_is_the_same(textured_world):
    sim, bodies = textured_world
    culling = sim.robot.camera.view_culling
    assert culling is not None and sim.physics.client.textured
    culled, whole = _images(sim, culled=True), _images(sim, culled=False)
    # behind, left and far_right; behind_twin shares its drawing with the box in view
    assert culling.hidden_bodies == {bodies[name] for name in ("behind", "left", "far_right")}
    assert _differing_pixels(culled, whole) <= 3     # surfaces at one depth may swap
    rgb = culled[0]
    assert len(np.unique(rgb.reshape(-1, 3), axis=0)) > 20   # the textured box is drawn
    # every colour is given back: turned around, the bodies behind are drawn as before
    turned = sim.robot.camera_pose()[1] @ np.diag([-1.0, 1.0, -1.0])
    camera = sim.robot.camera
    keep, camera.view_culling = camera.view_culling, None
    behind = camera.render(sim.robot.camera_pose()[0], turned, depth=True)
    camera.view_culling = keep
    sim.physics.client.view_noted.clear()           # nothing left out any more
    assert _differing_pixels(camera.render(sim.robot.camera_pose()[0], turned, depth=True),
                             behind) == 0


def test_a_body_in_view_is_drawn(textured_world):
    sim, bodies = textured_world
    culling = sim.robot.camera.view_culling
    position, rotation = sim.robot.camera_pose()
    with culling.hidden_outside(position, rotation) as count:
        assert count == 3
        assert bodies["ahead"] not in culling.hidden_bodies
        assert bodies["behind_twin"] not in culling.hidden_bodies   # the box's mesh is in view
    # turned around, the box ahead is out of view, and its twin behind in view: neither hidden
    turned = rotation @ np.diag([-1.0, 1.0, -1.0])
    with culling.hidden_outside(position, turned):
        assert culling.hidden_bodies == {bodies["left"], bodies["far_right"]}


def test_a_moved_body_is_judged_where_it_stands_now(textured_world):
    sim, bodies = textured_world
    cid = sim.physics.client
    _, orientation = pybullet.getBasePositionAndOrientation(bodies["behind"], physicsClientId=cid)
    pybullet.resetBasePositionAndOrientation(bodies["behind"], (3.0, 1.0, 0.0), orientation,
                                             physicsClientId=cid)   # into view, beside the box
    culled, whole = _images(sim, culled=True), _images(sim, culled=False)
    assert sim.robot.camera.view_culling.hidden_bodies == {bodies["left"], bodies["far_right"]}
    assert _differing_pixels(culled, whole) <= 3


def test_a_body_id_given_to_a_new_body_is_not_hidden(textured_world):
    sim, bodies = textured_world
    cid = sim.physics.client
    gone = bodies["left"]
    pybullet.removeBody(gone, physicsClientId=cid)
    shape = pybullet.createVisualShape(pybullet.GEOM_SPHERE, radius=0.2, physicsClientId=cid)
    new = pybullet.createMultiBody(0.0, -1, shape, basePosition=(0.5, 3.0, 0.2),
                                   physicsClientId=cid)
    assert new == gone                     # pybullet gives the id again
    culling = sim.robot.camera.view_culling
    with culling.hidden_outside(*sim.robot.camera_pose()):
        assert culling.hidden_bodies == {bodies["behind"], bodies["far_right"]}


def test_nothing_is_noted_without_egl(monkeypatch, tmp_path):
    monkeypatch.setattr(world_bullet, "egl_enabled", lambda cid: False)
    client = Client.connect()
    try:
        from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world
        from tutorial_turtlebot.sim.files.sdf.world_catalogue import resolve_world
        world_bullet.build_world(load_world(resolve_world("turtlebot3_world")[0]), client)
        assert not client.view_noted
    finally:
        client.disconnect()


def test_disable_egl_forgets_the_client(textured_world):
    sim, _ = textured_world
    client = sim.physics.client
    assert client.view_noted
    rendering.disable_egl(client)          # (sim.close does it again: harmless)
    assert not client.view_noted


def test_a_body_parked_far_below_leaves_the_others_hidden(textured_world):
    sim, bodies = textured_world
    cid = sim.physics.client
    _, orientation = pybullet.getBasePositionAndOrientation(bodies["left"], physicsClientId=cid)
    pybullet.resetBasePositionAndOrientation(bodies["left"], (0.0, 0.0, -1e4), orientation,
                                             physicsClientId=cid)   # as BodyPool parks one
    culled, whole = _images(sim, culled=True), _images(sim, culled=False)
    assert sim.robot.camera.view_culling.hidden_bodies == {
        bodies[name] for name in ("behind", "left", "far_right")}
    assert _differing_pixels(culled, whole) <= 3
