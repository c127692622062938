"""Textures of world meshes in a camera image (world_bullet, texture_budget): a Collada crate
written as 3ds Max writes one (test/fixtures/gazebo_models/max_style_crate, made by
make_texture_fixtures.py) drawn in its colours, and a texture set over the budget drawn halved,
never grey. A Waffle Pi at the origin facing +x looks at them; TinyRenderer and EGL. No ROS."""
import os

import numpy as np
import pytest

from tutorial_turtlebot.sim.engine import rendering, texture_budget
from tutorial_turtlebot.sim.files.meshes.mesh_file import cache_clear

from texture_fixtures import (QUADRANTS, RED, camera_sim, pixel, png_bytes, quadrant_texture,
                              write_textured_obj)
import unit_paths

CRATES = os.path.join(unit_paths.FIXTURES, "worlds", "textured", "max_style_crates.world")
MODELS = os.path.join(unit_paths.FIXTURES, "gazebo_models")
FACE_X = 1.5          # m: the crates' faces towards the robot
SIDE = 0.6            # m: a crate's side


@pytest.fixture(autouse=True)
def fresh_meshes():
    cache_clear()
    yield
    cache_clear()


@pytest.fixture(params=("tiny", "egl"))
def renderer(request):
    return request.param


def simulation(monkeypatch, world, renderer):
    """camera_sim with the fixtures' models on GAZEBO_MODEL_PATH."""
    monkeypatch.setenv("GAZEBO_MODEL_PATH", MODELS)
    return camera_sim(monkeypatch, world, renderer)


def colour_at(sim, rgb, y, z):
    """The median colour of the 5 x 5 pixels where the image shows the point (FACE_X, y, z)."""
    col, row = pixel(sim, (FACE_X, y, z))
    patch = rgb[row - 2:row + 3, col - 2:col + 3].reshape(-1, 3)
    return tuple(int(v) for v in np.median(patch, axis=0))


def looks(colour, rgb_full):
    """Whether a lit ``colour`` has the hue of the full-strength ``rgb_full``: its strong
    channels bright, its zero channels dark."""
    return all((c > 90) if full else (c < 50) for c, full in zip(colour, rgb_full))


def grey(colour):
    return max(colour) - min(colour) < 12


def quadrant_points(centre_y):
    """{quadrant: (y, z)} of the texture's quadrant centres on a face towards the robot,
    upright and seen from the robot (its left is +y)."""
    q = SIDE / 4
    return {"top left": (centre_y + q, 3 * q), "top right": (centre_y - q, 3 * q),
            "bottom left": (centre_y + q, q), "bottom right": (centre_y - q, q)}


# --- a Collada file written as 3ds Max writes one ------------------------------------------------

def test_a_3ds_max_style_collada_crate_is_drawn_in_its_textures(monkeypatch, renderer):
    """Its side (a texture named straight by its image id "Map #N-image", quads, inches, a bump
    map in the effect's <extra>) shows the quadrants upright; its lid side (the <newparam>
    chain) shows orange above brown. Each crate stands in a collision box a little larger than
    it, which cameras do not see (it hid the textures in grey before)."""
    sim = simulation(monkeypatch, CRATES, renderer)
    try:
        assert sim.world.warnings == ()
        rgb, _ = sim.robot.camera_image()
        for quadrant, (y, z) in quadrant_points(0.45).items():
            colour = colour_at(sim, rgb, y, z)
            assert looks(colour, QUADRANTS[quadrant]), (quadrant, colour)
        above, below = colour_at(sim, rgb, -0.45, 0.45), colour_at(sim, rgb, -0.45, 0.15)
        for colour in (above, below):
            assert colour[0] > colour[1] > colour[2] and not grey(colour), (above, below)
        assert above[0] > 1.5 * below[0], (above, below)       # orange, brown
    finally:
        sim.close()


def test_collisions_without_a_visual_are_not_seen(tmp_path, monkeypatch, renderer):
    """As in Gazebo, a camera sees visuals only: a static box collision without a visual twin
    (around a smaller sphere visual), a movable model of a collision alone. pybullet's renderers
    would draw a body without a visual shape as its collision shape."""
    world = tmp_path / "collisions.world"
    world.write_text("""<?xml version="1.0"?><sdf version="1.6"><world name="w">
      <model name="static_box"><static>true</static><pose>{x} 0.45 0.3 0 0 0</pose><link name="l">
        <collision name="c"><geometry><box><size>0.6 0.6 0.6</size></box></geometry></collision>
        <visual name="v"><geometry><sphere><radius>0.2</radius></sphere></geometry>
          <material><diffuse>1 0 0 1</diffuse></material></visual></link></model>
      <model name="movable_box"><pose>{x} -0.45 0.3 0 0 0</pose><link name="l">
        <inertial><mass>5</mass><inertia><ixx>0.3</ixx><iyy>0.3</iyy><izz>0.3</izz></inertia>
        </inertial>
        <collision name="c"><geometry><box><size>0.6 0.6 0.6</size></box></geometry></collision>
      </link></model></world></sdf>""".format(x=FACE_X + 0.3))
    sim = simulation(monkeypatch, str(world), renderer)
    try:
        rgb, depth = sim.robot.camera_image(depth=True)
        assert looks(colour_at(sim, rgb, 0.45, 0.3), RED)               # the sphere
        for y, z in ((0.6, 0.5), (-0.45, 0.3), (-0.6, 0.5)):          # no box
            assert colour_at(sim, rgb, y, z) == rendering.BACKGROUND_RGB
    finally:
        sim.close()


def test_every_texture_found_is_drawn_or_named_in_one_warning(tmp_path):
    """A mesh whose visual has an SDF <material> is drawn in that colour: its texture, found by
    the reader, is named in one line (at most 200 characters, once however many models use
    the mesh); so is a texture found nowhere."""
    from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world
    write_textured_obj(tmp_path)
    (tmp_path / "gone").mkdir()
    write_textured_obj(tmp_path / "gone", texture="gone.png", write_texture=False)
    models = "".join("""<model name="{n}"><static>true</static><pose>0 {y} 0 0 0 0</pose>
      <link name="l"><visual name="v"><geometry><mesh><uri>{uri}</uri></mesh></geometry>{m}
      </visual></link></model>""".format(n=n, y=y, uri=uri, m=m) for n, y, uri, m in (
        ("a", 0, "box.obj", "<material><diffuse>1 0 0 1</diffuse></material>"),
        ("b", 2, "box.obj", "<material><diffuse>1 0 0 1</diffuse></material>"),
        ("c", 4, "gone/box.obj", "")))
    world = tmp_path / "w.world"
    world.write_text('<?xml version="1.0"?><sdf version="1.6"><world name="w">%s</world></sdf>'
                     % models)
    coloured, gone = load_world(str(world)).warnings
    assert "box.obj: texture tex.png not drawn: the visual's <material> colours the mesh" \
        in coloured
    assert "box.obj: texture gone.png not drawn (found nowhere" in gone
    assert len(coloured) <= 200 and len(gone) <= 200


# --- the texture budget --------------------------------------------------------------------------

def write_boxes(folder, count):
    """``count`` textured cubes (OBJ, each its own 64 x 64 texture of four colours, as
    texture_fixtures' quadrants) in a row across the view; returns the world file."""
    models = []
    for i in range(count):
        box = folder / ("box%d" % i)
        box.mkdir()
        write_textured_obj(box, write_texture=False)
        image = quadrant_texture(64)
        image[0, 0] = (i, i, i)                  # each image its own content
        (box / "tex.png").write_bytes(png_bytes(image))
        y = 0.7 * (i - (count - 1) / 2)
        models.append("""<model name="box{i}"><static>true</static>
          <pose>{x} {y} 0.3 0 0 0</pose><link name="l">
          <collision name="c"><geometry><mesh><uri>box{i}/box.obj</uri>
            <scale>0.6 0.6 0.6</scale></mesh></geometry></collision>
          <visual name="v"><geometry><mesh><uri>box{i}/box.obj</uri>
            <scale>0.6 0.6 0.6</scale></mesh></geometry></visual></link></model>"""
                      .format(i=i, x=FACE_X + 0.3, y=y))
    world = folder / "boxes.world"
    world.write_text('<?xml version="1.0"?><sdf version="1.6"><world name="w">%s</world></sdf>'
                     % "".join(models))
    return str(world)


def test_a_texture_set_over_the_budget_is_halved_not_dropped(tmp_path, monkeypatch, renderer):
    """Three distinct 64 x 64 images, each used by one cube, in a budget of 8,000 px: the
    largest are halved until they fit (3 x 4096 px; one halved: 9,216; two: 6,144), every cube
    still shows its four colours, and one warning line of at most 200 characters says so."""
    world = write_boxes(tmp_path, 3)
    monkeypatch.setattr(texture_budget, "MAX_TEXTURE_PIXELS", 8_000)
    sim = simulation(monkeypatch, world, renderer)
    try:
        [line] = [w for w in sim.physics.warnings if "texture budget" in w]
        assert "2 of 3 texture images halved" in line and len(line) <= 200, line
        sizes = sorted(texture_budget.halved_images(sim.physics.client).values())
        assert sizes == [(32, 32), (32, 32), (64, 64)]
        rgb, _ = sim.robot.camera_image()
        for i in range(3):
            for quadrant, (y, z) in quadrant_points(0.7 * (i - 1)).items():
                colour = colour_at(sim, rgb, y, z)
                assert looks(colour, QUADRANTS[quadrant]), (i, quadrant, colour)
    finally:
        sim.close()
