"""Textures and material colours in camera images: a mesh's diffuse texture (Collada and OBJ),
SDF <material> colours and Gazebo/* scripts, as a Waffle Pi's camera sees them in a world built
by world_sdf -> world_bullet (Simulation), with TinyRenderer and with EGL. No ROS master.

Every fixture is made in tmp_path (texture_fixtures.py): a textured cube whose texture has four
strong colours in its quadrants, its image written with zlib and struct.
"""
import os

import numpy as np
import pytest

from tutorial_turtlebot.sim.engine import rendering
from tutorial_turtlebot.sim.engine.client import Client
from tutorial_turtlebot.sim.files.meshes import obj_writer, texture_images
from tutorial_turtlebot.sim.engine.rendering import CameraRenderer
from tutorial_turtlebot.sim.files.meshes.mesh_file import cache_clear, load_mesh
from tutorial_turtlebot.sim.files.meshes.obj_writer import write_obj_parts
from tutorial_turtlebot.sim.files.plugins.robot_plugin_types import CameraSpec

from texture_fixtures import (QUADRANTS, camera_sim, cube, pixel, png_bytes, quadrant_texture,
                              write_textured_dae, write_textured_obj)

CUBE_X = 1.5          # m: the cube's face towards the robot (at the origin, facing +x)
CUBE_SIDE = 0.6       # m


@pytest.fixture(autouse=True)
def fresh_caches():
    cache_clear()
    yield
    cache_clear()


# --- fixtures: worlds ------------------------------------------------------------------------

GROUND = """<model name="ground"><static>true</static><link name="l">
  <collision name="c"><geometry><plane><normal>0 0 1</normal><size>20 20</size></plane></geometry>\
</collision>
  <visual name="v"><geometry><plane><normal>0 0 1</normal><size>20 20</size></plane></geometry>
    <material><script><name>Gazebo/Grey</name></script></material></visual></link></model>"""


def mesh_model(name, uri, y=0.0, scale="0.6 0.6 0.6", material="", static=True):
    """A model of one mesh, its visual and its collision (its twin: only the visual is
    drawn), whose -x face is at CUBE_X."""
    x, z = CUBE_X + CUBE_SIDE / 2, CUBE_SIDE / 2
    return """<model name="{n}"><static>{s}</static><pose>{x} {y} {z} 0 0 0</pose><link name="l">
  <inertial><mass>5</mass><inertia><ixx>0.3</ixx><iyy>0.3</iyy><izz>0.3</izz></inertia></inertial>
  <collision name="c"><geometry><mesh><uri>{u}</uri><scale>{sc}</scale></mesh></geometry>\
</collision>
  <visual name="v"><geometry><mesh><uri>{u}</uri><scale>{sc}</scale></mesh></geometry>{m}</visual>
</link></model>""".format(n=name, s=str(static).lower(), x=x, y=y, z=z, u=uri, sc=scale,
                          m=material)


def box_model(name, y, material):
    x, z = CUBE_X + CUBE_SIDE / 2, CUBE_SIDE / 2
    return """<model name="{n}"><static>true</static><pose>{x} {y} {z} 0 0 0</pose><link name="l">
  <collision name="c"><geometry><box><size>0.6 0.6 0.6</size></box></geometry></collision>
  <visual name="v"><geometry><box><size>0.6 0.6 0.6</size></box></geometry>{m}</visual>
</link></model>""".format(n=name, x=x, y=y, z=z, m=material)


def write_world(folder, *models):
    path = folder / "textured.world"
    path.write_text('<?xml version="1.0"?>\n<sdf version="1.6"><world name="w">%s%s</world></sdf>\n'
                    % (GROUND, "".join(models)))
    return str(path)


# --- the camera ----------------------------------------------------------------------------------

@pytest.fixture(params=("tiny", "egl"))
def renderer(request):
    return request.param


def face_colour(sim, rgb, y, z, name=""):
    """The median colour of a 5 x 5 patch where the image shows the point (CUBE_X, y, z) of a
    cube's face towards the robot."""
    col, row = pixel(sim, (CUBE_X, y, z))
    patch = rgb[row - 2:row + 3, col - 2:col + 3].reshape(-1, 3)
    return tuple(int(v) for v in np.median(patch, axis=0))


def looks(colour, rgb_full):
    """Whether a drawn (lit) ``colour`` is the hue of the full-strength ``rgb_full``: its
    strong channels bright, its zero channels dark."""
    return all((c > 90) if full else (c < 50) for c, full in zip(colour, rgb_full))


def quadrant_points(centre_y=0.0):
    """{quadrant: (y, z)} of the centres of the texture's quadrants on a cube face towards the
    robot, upright and seen from the robot (its left is +y)."""
    q = CUBE_SIDE / 4
    return {"top left": (centre_y + q, 3 * q), "top right": (centre_y - q, 3 * q),
            "bottom left": (centre_y + q, q), "bottom right": (centre_y - q, q)}


def assert_textured(sim, rgb, centre_y=0.0, mirrored=False):
    for quadrant, (y, z) in quadrant_points(centre_y).items():
        if mirrored:
            quadrant = {"top left": "top right", "top right": "top left",
                        "bottom left": "bottom right", "bottom right": "bottom left"}[quadrant]
        colour = face_colour(sim, rgb, y, z)
        assert looks(colour, QUADRANTS[quadrant]), (quadrant, colour)


# --- the texture drawn ---------------------------------------------------------------------------

@pytest.mark.parametrize("kind", ["dae", "obj"])
def test_a_textured_mesh_shows_its_texture(tmp_path, monkeypatch, renderer, kind):
    mesh = write_textured_dae(tmp_path) if kind == "dae" else write_textured_obj(tmp_path)
    world = write_world(tmp_path, mesh_model("box", mesh.name))
    sim = camera_sim(monkeypatch, world, renderer)
    try:
        assert sim.world.warnings == ()
        rgb, _ = sim.robot.camera_image()
        assert_textured(sim, rgb)
    finally:
        sim.close()


def test_a_movable_textured_mesh_and_a_mirrored_one(tmp_path, monkeypatch, renderer):
    """A movable model's visual (createVisualShapeArray) is textured too; a mirroring scale
    mirrors the image with the mesh (Gazebo does the same)."""
    write_textured_obj(tmp_path)
    world = write_world(tmp_path, mesh_model("movable", "box.obj", y=0.4, static=False),
                        mesh_model("mirrored", "box.obj", y=-0.4, scale="0.6 -0.6 0.6"))
    sim = camera_sim(monkeypatch, world, renderer)
    try:
        rgb, _ = sim.robot.camera_image()
        assert_textured(sim, rgb, centre_y=0.4)
        assert_textured(sim, rgb, centre_y=-0.4, mirrored=True)
    finally:
        sim.close()


def test_material_colours_and_gazebo_scripts(tmp_path, monkeypatch, renderer):
    """SDF <diffuse>, <ambient> alone and a Gazebo/* script colour boxes; an SDF <material> on a
    textured mesh draws it in that colour, its texture left out."""
    write_textured_obj(tmp_path)
    world = write_world(
        tmp_path,
        box_model("diffuse", 0.75, "<material><ambient>0 1 0 1</ambient>"
                                   "<diffuse>1 0 1 1</diffuse></material>"),
        box_model("ambient", -0.75, "<material><ambient>0 0 1 1</ambient></material>"),
        mesh_model("script", "box.obj", y=0.0, scale="0.6 0.6 0.6",
                   material="<material><script><name>Gazebo/Turquoise</name>"
                            "<uri>file://media/materials/scripts/gazebo.material</uri>"
                            "</script></material>"))
    sim = camera_sim(monkeypatch, world, renderer)
    try:
        rgb, _ = sim.robot.camera_image()
        for y, expected in ((0.75, (255, 0, 255)), (-0.75, (0, 0, 255)), (0.0, (0, 255, 255))):
            for dy, z in ((0.1, 0.45), (-0.1, 0.15)):
                colour = face_colour(sim, rgb, y + dy, z)
                assert looks(colour, expected), (y, colour)
    finally:
        sim.close()


@pytest.mark.parametrize("kind", ["dae", "obj"])
def test_a_missing_texture_warns_once_and_keeps_the_colour(tmp_path, monkeypatch, kind):
    """An OBJ part keeps its Kd, a Collada one (no colour: its texture was its colour) is
    drawn grey; one warning line names the texture."""
    if kind == "obj":
        write_textured_obj(tmp_path, texture="gone.png", kd="1 0 0", write_texture=False)
        expected = (255, 0, 0)
    else:
        write_textured_dae(tmp_path, texture="gone.png", write_texture=False)
        expected = None
    world = write_world(tmp_path, mesh_model("a", "box." + kind, y=0.4),
                        mesh_model("b", "box." + kind, y=-0.4))
    sim = camera_sim(monkeypatch, world, "tiny")
    try:
        [warning] = sim.world.warnings
        assert "gone.png not drawn (found nowhere" in warning and "\n" not in warning
        rgb, _ = sim.robot.camera_image()
        for y in (0.4, -0.4):
            colour = face_colour(sim, rgb, y, 0.3)
            if expected is None:      # grey: all channels alike and neither dark nor white
                assert max(colour) - min(colour) < 8 and 100 < colour[0] < 230, colour
            else:
                assert looks(colour, expected), colour
    finally:
        sim.close()


# --- the texture as read ------------------------------------------------------------------------

def test_uvs_survive_vertex_merging_and_scale(tmp_path):
    """The cube's 8 corners are shared by faces with different uvs: the corners merge, each
    triangle keeps its own corners' uvs; a mirror reverses corners and uvs together."""
    write_textured_obj(tmp_path)
    corners, triangles, uvs = cube()
    for scale, mirror in (((1, 1, 1), False), ((2, -1, 1), True)):
        [part] = load_mesh(str(tmp_path / "box.obj"), scale).parts
        mesh = load_mesh(str(tmp_path / "box.obj"), scale)
        assert len(mesh.vertices) == 8
        assert part.texture == str(tmp_path / "tex.png") and os.path.isabs(part.texture)
        assert part.uvs.shape == (12, 3, 2) and part.uvs.dtype == np.float64
        # each corner's uv is the one the file gives that corner of that triangle
        expected = {}
        for tri, tri_uvs in zip(triangles, uvs):
            key = frozenset(tuple(corners[i] * scale) for i in tri)
            expected[key] = {tuple(corners[i] * scale): tuple(uv) for i, uv in zip(tri, tri_uvs)}
        for face, face_uvs in zip(part.faces, part.uvs):
            points = [tuple(mesh.vertices[i]) for i in face]
            want = expected[frozenset(points)]
            assert [want[p] for p in points] == [tuple(uv) for uv in face_uvs]
        normal = np.cross(*(mesh.vertices[part.faces[:, k]] - mesh.vertices[part.faces[:, 0]]
                            for k in (1, 2)))
        centres = mesh.vertices[part.faces].mean(axis=1)
        assert np.all(np.einsum("ij,ij->i", normal, centres) > 0)   # still outward


def test_collada_texture_and_uvs(tmp_path):
    write_textured_dae(tmp_path)
    [part] = load_mesh(str(tmp_path / "box.dae")).parts
    assert part.rgba is None and part.texture == str(tmp_path / "tex.png")
    assert part.uvs.shape == (12, 3, 2) and part.texture_problem is None


def test_textures_are_looked_for_as_gazebo_models_keep_them(tmp_path):
    """In ../materials/textures of the mesh's folder, and by a file:// URI with %-escapes."""
    meshes = tmp_path / "model" / "meshes"
    textures = tmp_path / "model" / "materials" / "textures"
    meshes.mkdir(parents=True)
    textures.mkdir(parents=True)
    write_textured_dae(meshes, texture="../textures/my%20skin.png", write_texture=False)
    (textures / "my skin.png").write_bytes(png_bytes(quadrant_texture()))
    [part] = load_mesh(str(meshes / "box.dae")).parts
    assert part.texture == str(textures / "my skin.png")


@pytest.mark.parametrize("content, why", [
    (b"GIF89a" + b"\0" * 40, "neither a PNG nor a JPEG file"),
    (None, "8193 x 2 px, more than 8192 px a side"),
    ("fifo", "it is a FIFO, not a regular file"),
])
def test_an_unusable_texture_is_one_line_and_the_colour(tmp_path, content, why):
    write_textured_obj(tmp_path, kd="0 0 1", write_texture=False)
    texture = tmp_path / "tex.png"
    if content == "fifo":
        os.mkfifo(str(texture))
    elif content is None:
        texture.write_bytes(png_bytes(np.zeros((2, 8193, 3), dtype=np.uint8)))
    else:
        texture.write_bytes(content)
    [part] = load_mesh(str(tmp_path / "box.obj")).parts
    assert part.texture is None and part.uvs is None and part.rgba == (0.0, 0.0, 1.0, 1.0)
    assert why in part.texture_problem and "\n" not in part.texture_problem
    assert part.texture_problem.startswith("box.obj: texture tex.png")


def test_a_texture_over_4096_px_a_side_is_drawn_from_a_halved_copy(tmp_path):
    """An 8192 px wide image (a large floor's, say) is drawn halved to 4096, not dropped: its
    size as drawn counts in the texture budget, and the copy drawn is that size."""
    pil = pytest.importorskip("PIL.Image")
    write_textured_obj(tmp_path, kd="0 0 1", write_texture=False)
    image = np.zeros((4, 8192, 3), dtype=np.uint8)
    image[:, 4096:] = (255, 0, 0)
    (tmp_path / "tex.png").write_bytes(png_bytes(image))
    [part] = load_mesh(str(tmp_path / "box.obj")).parts
    assert part.texture == str(tmp_path / "tex.png") and part.texture_problem is None
    info = texture_images.texture_info(part.texture)
    assert (info.width, info.height) == (4096, 4)
    copy = tmp_path / "copies"
    copy.mkdir()
    name = obj_writer.texture_copy(part.texture, str(copy))
    with pil.open(str(copy / name)) as drawn:
        assert drawn.size == (4096, 4)
        assert drawn.getpixel((100, 1)) == (0, 0, 0) and drawn.getpixel((4000, 1)) == (255, 0, 0)
    with pil.open(str(copy / obj_writer.texture_copy(part.texture, str(copy), 1))) as smaller:
        assert smaller.size == (2048, 4)      # the budget's halvings come on top (sides >= 8)


def test_a_texture_larger_than_side_files_is_not_read(tmp_path, monkeypatch):
    write_textured_obj(tmp_path, kd="1 0 0", write_texture=False)
    noise = np.random.default_rng(0).integers(0, 256, (64, 64, 3), dtype=np.uint8)
    (tmp_path / "tex.png").write_bytes(png_bytes(noise))     # about 12 kB
    monkeypatch.setattr(texture_images, "MAX_MESH_SIDE_FILE_BYTES", 4000)
    [part] = load_mesh(str(tmp_path / "box.obj")).parts
    assert part.texture is None and "more than the 4000 allowed" in part.texture_problem
    assert part.rgba == (1.0, 0.0, 0.0, 1.0)


def test_jpeg_textures_are_taken(tmp_path):
    pil = pytest.importorskip("PIL.Image")
    write_textured_obj(tmp_path, texture="tex.jpg", write_texture=False)
    for progressive in (False, True):
        pil.fromarray(quadrant_texture(32)).save(str(tmp_path / "tex.jpg"), "JPEG",
                                                 progressive=progressive)
        assert texture_images.image_problem((tmp_path / "tex.jpg").read_bytes()) is None
        assert texture_images.jpeg_size((tmp_path / "tex.jpg").read_bytes()) == (32, 32)
        cache_clear()
        [part] = load_mesh(str(tmp_path / "box.obj")).parts
        assert part.texture == str(tmp_path / "tex.jpg")


def test_write_obj_parts_writes_uvs_and_a_copy_of_the_texture(tmp_path):
    write_textured_obj(tmp_path)
    out = tmp_path / "out"
    out.mkdir()
    mesh = load_mesh(str(tmp_path / "box.obj"))
    [(path, rgba)] = write_obj_parts(mesh, str(out))
    assert rgba == (1.0, 1.0, 1.0, 1.0)
    text = open(path).read()
    assert text.count("\nvt ") == 36 and text.count("\nf ") == 12
    mtl = next(line.split()[1] for line in text.splitlines() if line.startswith("mtllib"))
    image = next(line.split()[1] for line in (out / mtl).read_text().splitlines()
                 if line.startswith("map_Kd"))
    assert (out / image).read_bytes() == (tmp_path / "tex.png").read_bytes()
    [(plain, _)] = write_obj_parts(mesh, str(out), textures=False)
    assert "vt " not in open(plain).read() and "mtllib" not in open(plain).read()


def test_a_urdf_mesh_is_drawn_textured(tmp_path, renderer):
    """A robot's textured mesh visual is drawn textured (its body built as every model's:
    engine.robot_body), the builder telling the renderer; a URDF <material> colour does not
    change it (Gazebo 11's conversion drops it: the file's own colours are drawn)."""
    from tutorial_turtlebot.sim.engine.movable_bodies import model_body
    from tutorial_turtlebot.sim.engine.robot_body import robot_model
    from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf
    if renderer == "egl" and not rendering.egl_available():
        pytest.skip("EGL does not render on this machine")
    write_textured_obj(tmp_path)
    (tmp_path / "r.urdf").write_text("""<robot name="r"><link name="a">
      <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>\
</inertial>
      <visual><origin xyz="0 0.4 0"/><geometry><mesh filename="box.obj" scale="0.6 0.6 0.6"/>\
</geometry></visual>
      <visual><origin xyz="0 -0.4 0"/><geometry><mesh filename="box.obj" scale="0.6 0.6 0.6"/>\
</geometry>
        <material name="m"><color rgba="1 0 1 1"/></material></visual></link></robot>""")
    client = Client.connect()
    try:
        if renderer == "egl":
            assert rendering.enable_egl(client)
        assert not client.textured
        body = model_body(robot_model(read_urdf(str(tmp_path / "r.urdf")))[0], client)
        assert client.textured
        client.resetBasePositionAndOrientation(body, (CUBE_X + 0.3, 0, 0.3), (0, 0, 0, 1))
        spec = CameraSpec(width=320, height=240, hfov=1.085595, near=0.03, far=100.0, rate=30.0)
        view = CameraRenderer(client, spec, use_egl=renderer == "egl")
        rotation = np.array([[0, 0, 1], [-1, 0, 0], [0, -1, 0]], dtype=float)  # optical, +x
        position = np.array([0.0, 0.0, 0.3])
        rgb, _ = view.render(position, rotation)

        class Fake:   # what pixel() needs
            class robot:
                camera_spec = spec

                @staticmethod
                def camera_pose():
                    return position, rotation
        assert_textured(Fake, rgb, centre_y=0.4)
        assert_textured(Fake, rgb, centre_y=-0.4)
        assert not looks(face_colour(Fake, rgb, -0.4, 0.3), (255, 0, 255))
    finally:
        rendering.disable_egl(client)
        client.disconnect()


def test_a_urdf_robot_names_its_missing_texture_in_one_warning(tmp_path):
    from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf
    from tutorial_turtlebot.sim.files.urdf.urdf_meshes import texture_warnings
    write_textured_obj(tmp_path, texture="gone.png", kd="1 0 0", write_texture=False)
    (tmp_path / "r.urdf").write_text("""<robot name="r"><link name="a">
      <inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/>\
</inertial>
      <visual><geometry><mesh filename="box.obj"/></geometry></visual>
      <visual><origin xyz="1 0 0"/><geometry><mesh filename="box.obj"/></geometry></visual>
      </link></robot>""")
    [line] = texture_warnings(read_urdf(str(tmp_path / "r.urdf")))
    assert line.startswith("box.obj: texture gone.png not drawn (found nowhere")


def test_the_common_gazebo_materials_have_colours():
    """Gazebo 11's common gazebo.material names are drawn in a colour of their own (the
    textured ones in their texture's mean colour), not the grey of an unknown name."""
    from tutorial_turtlebot.sim.files.looks.gazebo_materials import GAZEBO_MATERIALS
    from tutorial_turtlebot.sim.files.world_types import DEFAULT_RGBA
    names = ("White Grey DarkGrey Black FlatBlack Red RedBright Green Blue SkyBlue Yellow "
             "ZincYellow DarkYellow Purple Turquoise Orange Indigo Wood WoodFloor WoodPallet "
             "Bricks Gold Residential Tertiary Road Asphalt Trunk Leaf CeilingTiled LightWood "
             "PaintedWall Chrome BlueLaser Shadow").split()
    for name in names:
        rgba = GAZEBO_MATERIALS["Gazebo/" + name]
        assert len(rgba) == 4 and all(0.0 <= v <= 1.0 for v in rgba), name
        assert name == "Grey" or rgba != DEFAULT_RGBA, name
    assert GAZEBO_MATERIALS["Gazebo/Red"] == (1.0, 0.0, 0.0, 1.0)
