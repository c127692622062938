"""A visual's <material> as world_sdf reads it (sdf_looks), in Gazebo 11's precedence
(rendering::Visual::Load: the <script>'s material, then the <diffuse> given beside it set on
its passes): a textured script beside a white <diffuse> draws the texture. Seen by a pybullet
camera from above in test/fixtures/worlds/textured/white_diffuse_script.world (ours). No ROS
master."""
import os

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.sim.devices.camera import CameraIntrinsics
from tutorial_turtlebot.sim.engine import rendering
from tutorial_turtlebot.sim.engine.client import Client
from tutorial_turtlebot.sim.engine.rendering import CameraRenderer
from tutorial_turtlebot.sim.engine.world_bullet import build_world
from tutorial_turtlebot.sim.files.plugins.robot_plugin_types import CameraSpec
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world
from tutorial_turtlebot.sim.files.world_types import DEFAULT_RGBA

import unit_paths
from texture_fixtures import QUADRANTS, png_bytes, quadrant_texture

TEXTURED = os.path.join(unit_paths.FIXTURES, "worlds", "textured")
WHITE_DIFFUSE = os.path.join(TEXTURED, "white_diffuse_script.world")
WHITE, RED, GREEN, BLUE = (1.0, 1.0, 1.0, 1.0), (1, 0, 0, 1), (0, 1, 0, 1), (0, 0, 1, 1)
OWN_SCRIPTS = """material textured { technique { pass { texture_unit { texture quadrants.png } } } }
material blue { technique { pass { diffuse 0 0 1 1 } } }
"""


def box_world(tmp_path, materials):
    """A world of one box a <material> body, each named after its index, beside a
    materials/scripts/own.material (OWN_SCRIPTS) and materials/textures/quadrants.png."""
    (tmp_path / "materials" / "scripts").mkdir(parents=True, exist_ok=True)
    (tmp_path / "materials" / "textures").mkdir(parents=True, exist_ok=True)
    (tmp_path / "materials" / "scripts" / "own.material").write_text(OWN_SCRIPTS)
    (tmp_path / "materials" / "textures" / "quadrants.png").write_bytes(
        png_bytes(quadrant_texture()))
    models = "".join(
        '<model name="m%d"><static>true</static><pose>%d 0 0.5 0 0 0</pose><link name="l">'
        '<visual name="v"><geometry><box><size>1 1 1</size></box></geometry>'
        '<material>%s</material></visual></link></model>' % (i, 2 * i, body)
        for i, body in enumerate(materials))
    path = tmp_path / "looks.world"
    path.write_text('<sdf version="1.6"><world name="w">%s</world></sdf>' % models)
    return str(path)


def own(name):
    return ("<script><uri>file://materials/scripts</uri><uri>file://materials/textures</uri>"
            "<name>%s</name></script>" % name)


@pytest.mark.parametrize("material, rgba, textured", [
    (own("textured"), WHITE, True),                                      # script alone
    (own("textured") + "<diffuse>1 1 1 1</diffuse>", WHITE, True),       # the office floors
    (own("textured") + "<diffuse>1 0 0 1</diffuse>", RED, True),         # a tinted texture
    (own("blue") + "<ambient>1 0 0 1</ambient>", BLUE, False),           # ambient: unlit part
    (own("blue") + "<diffuse>0 1 0 1</diffuse>", GREEN, False),          # diffuse replaces
    ("<script><name>Gazebo/Red</name></script><ambient>0 0 1 1</ambient>", RED, False),
    ("<script><name>Gazebo/Red</name></script><diffuse>0 1 0</diffuse>", GREEN, False),
    ("<script><name>Gazebo/Wood</name></script><diffuse>1 1 1 1</diffuse>",
     (0.62, 0.45, 0.28, 1.0), False),                                    # its texture, untinted
    ("<script><name>Gazebo/Wood</name></script><diffuse>0.5 1 0 1</diffuse>",
     (0.31, 0.45, 0.0, 1.0), False),                                     # tinted
    ("<ambient>0 0 1 1</ambient>", BLUE, False),                         # colour alone
    ("<diffuse>0 1 0 1</diffuse><ambient>0 0 1 1</ambient>", GREEN, False),
    (own("undefined") + "<ambient>0 0 1 1</ambient>", BLUE, False),      # no material found
    (own("undefined"), DEFAULT_RGBA, False),
])
def test_gazebos_precedence_of_script_diffuse_and_ambient(tmp_path, material, rgba, textured):
    world = load_world(box_world(tmp_path, [material]))
    [shape] = world.shapes
    assert shape.rgba == pytest.approx(rgba)
    texture = str(tmp_path / "materials" / "textures" / "quadrants.png")
    assert shape.texture == (texture if textured else None)


def test_the_white_diffuse_fixture_keeps_its_scripts_texture():
    world = load_world(WHITE_DIFFUSE)
    assert world.warnings == ()
    for shape in world.shapes:        # the collision draws its twin's look
        assert shape.texture == os.path.join(TEXTURED, "quadrants.png") and shape.rgba == WHITE


SPEC = CameraSpec(width=320, height=240, hfov=1.085595, near=0.03, far=100.0, rate=30.0)
CAMERA_Z = 2.5                                                          # m above the floor
# optical frame looking down (z along -z), image right along +x, image up along +y
DOWN = np.array([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]])


def looks(colour, rgb_full):
    """Whether a drawn (lit) ``colour`` is the hue of the full-strength ``rgb_full``."""
    return all((c > 90) if full else (c < 50) for c, full in zip(colour, rgb_full))


@pytest.mark.parametrize("renderer", ["tiny", "egl"])
def test_a_camera_sees_the_texture_beside_a_white_diffuse(renderer):
    """Seen from above (+x to the right, +y up) the floor shows the script's image upright,
    not plain white."""
    if renderer == "egl" and not rendering.egl_available():
        pytest.skip("EGL does not render on this machine")
    cid = Client.connect()
    try:
        if renderer == "egl":
            assert rendering.enable_egl(cid)
        build_world(load_world(WHITE_DIFFUSE), cid)
        position = np.array([0.0, 0.0, CAMERA_Z])
        rgb, _ = CameraRenderer(cid, SPEC, use_egl=renderer == "egl").render(position, DOWN)
        f = CameraIntrinsics.from_spec(SPEC).f
        for quadrant, (x, y) in {"top left": (-0.5, 0.5), "top right": (0.5, 0.5),
                                 "bottom left": (-0.5, -0.5),
                                 "bottom right": (0.5, -0.5)}.items():
            px, py, pz = DOWN.T @ (np.array([x, y, 0.0]) - position)
            col, row = int(f * px / pz + SPEC.width / 2), int(f * py / pz + SPEC.height / 2)
            colour = tuple(int(v) for v in np.median(
                rgb[row - 2:row + 3, col - 2:col + 3].reshape(-1, 3), axis=0))
            assert looks(colour, QUADRANTS[quadrant]), (quadrant, colour)
    finally:
        rendering.disable_egl(cid)
        pybullet.disconnect(physicsClientId=cid)


@pytest.mark.parametrize("material, own_colours", [
    ("<script><name>__default__</name></script>", True),       # Gazebo's SetMaterial: no-op
    ("<script><uri>file://media/materials/scripts/gazebo.material</uri>"
     "<name>__default__</name></script>", True),
    ("<script><name>__default__</name></script><diffuse>1 0 0 1</diffuse>", False),
    ("<script><name>Gazebo/Red</name></script>", False),
])
def test_a_default_script_leaves_a_mesh_its_own_colours(tmp_path, material, own_colours):
    mesh = os.path.join(TEXTURED, "box.dae")
    (tmp_path / "mesh.world").write_text(
        '<sdf version="1.6"><world name="w"><model name="m"><static>true</static>'
        '<link name="l"><visual name="v"><geometry><mesh><uri>file://%s</uri></mesh>'
        '</geometry><material>%s</material></visual></link></model></world></sdf>'
        % (mesh, material))
    world = load_world(str(tmp_path / "mesh.world"))
    [shape] = world.shapes
    assert shape.mesh_colours == own_colours
    if own_colours:      # the mesh's textures are drawn: no "texture ... not drawn" warning
        assert not [w for w in world.warnings if "not drawn" in w]
