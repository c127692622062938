"""A model's own OGRE material scripts (material_scripts): the colour and texture of a
``<material><script>`` name that is not one of Gazebo's, as world_sdf reads them and as a
pybullet camera sees a textured plane or box from above (world_bullet). No ROS master.

Every script and image is written here into tmp_path (texture_fixtures.png_bytes); the
autorace_like fixture's course is our own too.
"""
import os

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.sim.engine import rendering
from tutorial_turtlebot.sim.engine.client import Client
from tutorial_turtlebot.sim.devices.camera import CameraIntrinsics
from tutorial_turtlebot.sim.engine.rendering import CameraRenderer
from tutorial_turtlebot.sim.engine.world_bullet import build_world
from tutorial_turtlebot.sim.files.looks import material_scripts
from tutorial_turtlebot.sim.files.looks.material_scripts import WHITE, MaterialScripts
from tutorial_turtlebot.sim.files.plugins.robot_plugin_types import CameraSpec
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world
from tutorial_turtlebot.sim.files.world_types import DEFAULT_RGBA

import unit_paths
from texture_fixtures import QUADRANTS, png_bytes, quadrant_texture

SEVERAL = """// materials of our own { a brace in a comment }
material first { technique { pass { diffuse 1 0 0 } } }

material "second one"
{
  technique
  {
    pass main   // a named pass
    {
      ambient 0 0.5 0 1
      /* diffuse 1 1 1
         left out */
    }
    pass other { diffuse 1 1 1 }
  }
}

material third : first
{
}
"""


def model_folder(tmp_path, script, name="floor.material", texture=None):
    """materials/scripts/<name> holding ``script``, and materials/textures/<texture> (the
    quadrant image) if ``texture``; returns the scripts folder."""
    scripts = tmp_path / "materials" / "scripts"
    textures = tmp_path / "materials" / "textures"
    scripts.mkdir(parents=True, exist_ok=True)
    textures.mkdir(parents=True, exist_ok=True)
    (scripts / name).write_text(script)
    if texture:
        (textures / texture).write_bytes(png_bytes(quadrant_texture()))
    return scripts


def textured(name="floor", texture="quadrants.png", colour=""):
    return ("material %s\n{\n  technique\n  {\n    pass\n    {\n      %s\n      texture_unit\n"
            "      {\n        texture %s\n      }\n    }\n  }\n}\n" % (name, colour, texture))


# --- the parser ------------------------------------------------------------------------------

def test_several_materials_comments_quoted_names_and_inheritance(tmp_path):
    scripts = model_folder(tmp_path, SEVERAL)
    scripts_read = MaterialScripts()
    for name, rgba in (("first", (1.0, 0.0, 0.0, 1.0)), ("second one", (0.0, 0.5, 0.0, 1.0)),
                       ("third", (1.0, 0.0, 0.0, 1.0))):
        found, problems = scripts_read.material(name, [str(scripts)])
        assert problems == [] and found.rgba == rgba and found.texture is None, name
    found, problems = scripts_read.material("fourth", [str(scripts)])
    assert found is None and len(problems) == 1 and "defined in none of" in problems[0]


def test_a_texture_is_found_in_the_textures_folder_beside_scripts(tmp_path):
    scripts = model_folder(tmp_path, textured() + textured("tinted", colour="diffuse 0 0 1"),
                           texture="quadrants.png")
    found, problems = MaterialScripts().material("floor", [str(scripts)])
    assert problems == []
    assert found.texture == str(tmp_path / "materials" / "textures" / "quadrants.png")
    assert found.rgba == WHITE                          # a texture alone is drawn as it is
    found, _ = MaterialScripts().material("tinted", [str(scripts)])
    assert found.rgba == (0.0, 0.0, 1.0, 1.0) and found.texture is not None


def test_a_script_file_named_by_its_uri_and_its_textures_folder(tmp_path):
    """A <uri> may name the .material file itself; the textures folder is a uri too."""
    scripts = model_folder(tmp_path, textured(), texture="quadrants.png")
    textures = tmp_path / "materials" / "textures"
    found, problems = MaterialScripts().material(
        "floor", [str(scripts / "floor.material"), str(textures)])
    assert problems == [] and found.texture == str(textures / "quadrants.png")


@pytest.mark.parametrize("script, what", [
    ("material a\n{\n  technique { pass { diffuse 1 0 0 }\n", "'{' never closed"),
    ("material a { technique { pass { diffuse 1 0 0 } } } }\n", "'}' without its '{'"),
    ('material "a { technique { pass { diffuse 1 0 0 } } }\n', "quoted name not closed"),
    ("/* material a { technique { pass { diffuse 1 0 0 } } }\n", "comment never closed"),
    ("{ technique }\n", "'{' without a name"),
    ("material a" + " { x" * 40 + " }" * 40 + "\n", "nested more than 32 deep"),
])
def test_a_malformed_script_is_one_line_and_no_material(tmp_path, script, what):
    scripts = model_folder(tmp_path, script)
    found, problems = MaterialScripts().material("a", [str(scripts)])
    assert found is None and len(problems) == 1, problems
    assert problems[0].startswith(str(scripts / "floor.material") + ":")
    assert "malformed material script" in problems[0] and what in problems[0]
    assert "\n" not in problems[0]


def test_a_colour_that_is_not_numbers_is_left_out(tmp_path):
    scripts = model_folder(tmp_path, "material a { technique { pass {\n"
                                     "  ambient 0 0 1\n  diffuse red green blue\n} } }\n")
    found, problems = MaterialScripts().material("a", [str(scripts)])
    assert found.rgba == (0.0, 0.0, 1.0, 1.0)
    [line] = problems
    assert line.startswith(str(scripts / "floor.material") + ":3: diffuse needs 3 or 4 numbers")


def test_an_unreadable_script_is_one_line(tmp_path, monkeypatch):
    scripts = model_folder(tmp_path, textured())
    os.mkfifo(str(scripts / "a_pipe.material"))
    found, problems = MaterialScripts().material("floor", [str(scripts)])
    assert found is not None            # floor.material is read after it, in name order
    [line] = [p for p in problems if "a_pipe.material" in p]
    assert "FIFO" in line and "\n" not in line
    monkeypatch.setattr(material_scripts, "MAX_SCRIPT_BYTES", 10)
    _, problems = MaterialScripts().material("floor", [str(scripts)])
    assert any("floor.material" in p and "more than the 10 allowed" in p for p in problems)


# --- in a world --------------------------------------------------------------------------------

def floor_model(name, kind="plane", y=0.0, material="floor", static=True,
                uris=("file://materials/scripts", "file://materials/textures")):
    """A 2 x 2 m plane at z 0 (or a box 2 x 2 x 0.02 m standing on it) centred at (0, y),
    drawn with the script material ``material``."""
    geometry = ("<plane><normal>0 0 1</normal><size>2 2</size></plane>" if kind == "plane"
                else "<box><size>2 2 0.02</size></box>")
    z = 0.0 if kind == "plane" else 0.01
    script = "".join("<uri>%s</uri>" % u for u in uris) + "<name>%s</name>" % material
    inertial = ("" if static else "<inertial><mass>1</mass><inertia><ixx>1</ixx><iyy>1</iyy>"
                "<izz>1</izz></inertia></inertial>")
    return """<model name="{n}"><static>{s}</static><pose>0 {y} {z} 0 0 0</pose><link name="l">{i}
  <collision name="c"><geometry>{g}</geometry></collision>
  <visual name="v"><geometry>{g}</geometry><material><script>{sc}</script></material></visual>
</link></model>""".format(n=name, s=str(static).lower(), y=y, z=z, i=inertial, g=geometry,
                          sc=script)


def write_world(folder, *models):
    path = folder / "scripted.world"
    path.write_text('<?xml version="1.0"?>\n<sdf version="1.6"><world name="w">%s</world></sdf>\n'
                    % "".join(models))
    return str(path)


def test_a_world_draws_the_scripts_texture_on_visual_and_collision(tmp_path):
    model_folder(tmp_path, textured(), texture="quadrants.png")
    world = load_world(write_world(tmp_path, floor_model("floor")))
    assert world.warnings == ()
    texture = str(tmp_path / "materials" / "textures" / "quadrants.png")
    for shape in world.model_shapes("floor"):       # the collision draws its twin's look
        assert shape.texture == texture and shape.rgba == WHITE, shape.name


def test_a_missing_texture_is_one_warning_and_the_colour(tmp_path):
    model_folder(tmp_path, textured(texture="gone.png", colour="diffuse 0 1 0 1"))
    world = load_world(write_world(tmp_path, floor_model("a", y=-2), floor_model("b", y=2)))
    [warning] = world.warnings
    assert "texture gone.png of material floor" in warning and "found nowhere" in warning
    assert str(tmp_path / "materials" / "scripts" / "floor.material") in warning
    assert "\n" not in warning
    for shape in world.shapes:
        assert shape.rgba == (0.0, 1.0, 0.0, 1.0) and shape.texture is None


def test_a_malformed_script_is_one_warning_and_grey(tmp_path, monkeypatch):
    model_folder(tmp_path, "material floor { technique { pass { diffuse 1 0 0 }\n")
    reads = []
    real_read = material_scripts.read_file
    monkeypatch.setattr(material_scripts, "read_file",
                        lambda *args, **kw: reads.append(args[0]) or real_read(*args, **kw))
    world = load_world(write_world(tmp_path, floor_model("a", y=-2), floor_model("b", y=2)))
    [warning] = world.warnings
    assert warning.startswith(str(tmp_path / "scripted.world") + ":")
    assert "floor.material:1: malformed material script (a '{' never closed)" in warning
    assert all(s.rgba == DEFAULT_RGBA and s.texture is None for s in world.shapes)
    assert len(reads) == 1      # the file once for both visuals


def test_uris_found_nowhere_leave_the_material_grey_without_a_word(tmp_path):
    """As the autorace traffic signs whose materials folder is missing: Gazebo draws them in
    its default, and so does this loader, with no warning."""
    world = load_world(write_world(tmp_path, floor_model("floor")))
    assert world.warnings == ()
    assert all(s.rgba == DEFAULT_RGBA and s.texture is None for s in world.shapes)


def test_the_autorace_like_course_has_its_picture(monkeypatch):
    models = os.path.join(unit_paths.FIXTURES, "gazebo_models")
    monkeypatch.setenv("GAZEBO_MODEL_PATH", models)
    world = load_world(os.path.join(unit_paths.FIXTURES, "worlds", "autorace_like.world"))
    picture = os.path.join(models, "autorace_like", "course", "materials", "textures",
                           "course.png")
    assert world.warnings == ()
    for shape in world.model_shapes("course"):
        assert shape.kind == "plane" and shape.texture == picture and shape.rgba == WHITE
    assert os.path.getsize(picture) < 4096


# --- drawn, seen from above --------------------------------------------------------------------

SPEC = CameraSpec(width=320, height=240, hfov=1.085595, near=0.03, far=100.0, rate=30.0)
CAMERA_Z = 2.5                                                          # m above the floor
# optical frame looking down (z along -z), image right along +x, image up along +y
DOWN = np.array([[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]])


def pixel(position, point):
    """(column, row) of the image pixel that shows world ``point``."""
    f = CameraIntrinsics.from_spec(SPEC).f
    x, y, z = DOWN.T @ (np.asarray(point, dtype=float) - position)
    return int(f * x / z + SPEC.width / 2), int(f * y / z + SPEC.height / 2)


def looks(colour, rgb_full):
    """Whether a drawn (lit) ``colour`` is the hue of the full-strength ``rgb_full``."""
    return all((c > 90) if full else (c < 50) for c, full in zip(colour, rgb_full))


@pytest.mark.parametrize("renderer", ["tiny", "egl"])
@pytest.mark.parametrize("kind, static", [("plane", True), ("box", True), ("box", False)])
def test_the_texture_is_drawn_upright_seen_from_above(tmp_path, renderer, kind, static):
    """A 2 x 2 m floor whose script texture has four coloured quadrants: seen from above
    with +x to the right and +y up, the image is upright (its top left quadrant at -x, +y)."""
    if renderer == "egl" and not rendering.egl_available():
        pytest.skip("EGL does not render on this machine")
    model_folder(tmp_path, textured(), texture="quadrants.png")
    world = load_world(write_world(tmp_path, floor_model("floor", kind=kind, static=static)))
    cid = Client.connect()     # an engine Client (int(cid) is its id)
    try:
        if renderer == "egl":
            assert rendering.enable_egl(cid)
        build_world(world, cid)
        position = np.array([0.0, 0.0, CAMERA_Z])
        rgb, _ = CameraRenderer(cid, SPEC, use_egl=renderer == "egl").render(position, DOWN)
        top = 0.0 if kind == "plane" else 0.02
        for quadrant, (x, y) in {"top left": (-0.5, 0.5), "top right": (0.5, 0.5),
                                 "bottom left": (-0.5, -0.5),
                                 "bottom right": (0.5, -0.5)}.items():
            col, row = pixel(position, (x, y, top))
            colour = tuple(int(v) for v in np.median(
                rgb[row - 2:row + 3, col - 2:col + 3].reshape(-1, 3), axis=0))
            assert looks(colour, QUADRANTS[quadrant]), (quadrant, colour)
    finally:
        rendering.disable_egl(cid)
        pybullet.disconnect(physicsClientId=cid)
