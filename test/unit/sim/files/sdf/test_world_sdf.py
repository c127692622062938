"""The world files and their loader (world_sdf): no ROS master, no pybullet."""
import glob
import math
import os
import shutil
import subprocess

import pytest

from tutorial_turtlebot.errors import WorldError
from tutorial_turtlebot.sim.files.sdf.world_catalogue import WORLD_DIR, WORLDS, resolve_world
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world
from tutorial_turtlebot.sim.files.world_types import DEFAULT_RGBA

from unit_helpers import world_fault, world_file

WORLD_FILES = sorted(glob.glob(os.path.join(WORLD_DIR, "*.world")))
SYMBOL = "ros_symbol::symbol::"
GREEN, WHITE = (0.0, 1.0, 0.0, 1.0), (1.0, 1.0, 1.0, 1.0)


@pytest.fixture(scope="module")
def tb3_world():
    return load_world(resolve_world("turtlebot3_world")[0])


def model(geometry, pose="0 0 0 0 0 0", name="m"):
    return ('<model name="%s"><static>true</static><link name="l">'
            '<collision name="c"><pose>%s</pose><geometry>%s</geometry></collision>'
            '</link></model>' % (name, pose, geometry))


# --- the files ----------------------------------------------------------------------------------

def test_catalogue_names_spawns_and_files():
    assert WORLDS["empty"].spawn == (0.0, 0.0, 0.0)
    assert WORLDS["turtlebot3_world"].spawn == (-2.0, -0.5, 0.0)
    for name, entry in WORLDS.items():
        path, spawn = resolve_world(name)
        assert os.path.isfile(path) and spawn == entry.spawn
    assert {os.path.basename(p) for p in WORLD_FILES} >= {e.file for e in WORLDS.values()}


@pytest.mark.parametrize("path", WORLD_FILES, ids=os.path.basename)
def test_gazebo_accepts_world_file(path):
    """Gazebo's own SDF checker passes every file (make test installs it)."""
    if shutil.which("ign") is None:
        pytest.skip("'ign' not found: Gazebo's SDF checker is not installed here (Debian: "
                    "ignition-tools and libsdformat-dev, which tools/setup.sh installs)")
    run = subprocess.run(["ign", "sdf", "-k", path], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0 and "Valid" in run.stdout, run.stdout + run.stderr


@pytest.mark.parametrize("path", WORLD_FILES, ids=os.path.basename)
def test_world_file_loads(path):
    world = load_world(path)
    assert any(s.kind == "plane" for s in world.collisions)  # a floor to stand on
    # every collision is seen (AutoRace's lane lines are visual-only, as in the original)
    assert world.collisions and all(s.twin for s in world.collisions)


def test_empty_world_is_the_ground_plane():
    world = load_world(resolve_world("empty")[0])
    assert world.models == ("ground_plane",)
    (plane,) = world.collisions
    assert plane.name == "ground_plane::link::collision" and plane.kind == "plane"
    assert plane.size == (100.0, 100.0) and plane.pose == pytest.approx((0,) * 6)
    assert plane.static and plane.rgba == (0.7, 0.7, 0.7, 1.0)


def test_turtlebot3_world_models(tb3_world):
    assert tb3_world.models == ("ground_plane", "ros_symbol")
    assert len(tb3_world.collisions) == 1 + 6 + 5 + 9
    assert all(s.static for s in tb3_world.shapes)


def test_nine_white_pillars(tb3_world):
    names = ("one", "two", "three")
    for i, x in enumerate((-1.1, 0.0, 1.1)):
        for j, y in enumerate((-1.1, 0.0, 1.1)):
            pillar = tb3_world.shape(SYMBOL + names[i] + "_" + names[j])
            assert pillar.kind == "cylinder" and pillar.size == (0.15, 0.5)
            assert pillar.pose == pytest.approx((x, y, 0.25, 0, 0, 0))
            assert pillar.rgba == WHITE


def hexagon_checks(shape, centre, circumradius, height):
    assert shape.kind == "polyline" and shape.rgba == GREEN
    assert shape.pose == pytest.approx(centre + (0, 0, 0), abs=1e-9)
    assert shape.size == pytest.approx((height,))
    assert len(shape.points) == 6
    assert max(math.hypot(x, y) for x, y in shape.points) == pytest.approx(circumradius, abs=1e-4)
    assert (circumradius, 0.0) in shape.points and (-circumradius, 0.0) in shape.points
    assert max(abs(y) for _, y in shape.points) == pytest.approx(circumradius * math.sqrt(3) / 2,
                                                                 abs=1e-4)


def test_green_head_and_hexagons(tb3_world):
    head = tb3_world.shape(SYMBOL + "head")
    hexagon_checks(head, (3.5, 0.0, -0.5), 1.173, 2.032)
    assert head.pose[0] - 1.173 == pytest.approx(2.327)      # reaches into the arena
    for name, x, y in (("left_hand", 1.8, 2.7), ("right_hand", 1.8, -2.7),
                       ("left_foot", -1.8, 2.7), ("right_foot", -1.8, -2.7)):
        hexagon_checks(tb3_world.shape(SYMBOL + name), (x, y, 0.0), 0.807, 1.397)


def test_outer_wall_is_the_hexagonal_ring(tb3_world):
    """Six boxes whose inner faces lie on the hexagon of circumradius 2.933 (flats at 2.540),
    0.3175 thick, z -0.30..0.97, with outer faces at 2.858 and ends meeting at the corners."""
    walls = [s for s in tb3_world.collisions if s.name.startswith(SYMBOL + "body_")]
    assert len(walls) == 6
    normals = []
    for wall in walls:
        x, y, z, roll, pitch, yaw = wall.pose
        length, thickness, height = wall.size
        assert wall.kind == "box" and wall.rgba == (0.1, 0.1, 0.1, 1.0)
        assert (roll, pitch) == pytest.approx((0, 0))
        assert (z - height / 2, z + height / 2) == pytest.approx((-0.30, 0.97))
        assert thickness == pytest.approx(0.3175)
        normal = math.atan2(y, x)                 # the box's thin axis (its y) points radially
        assert abs(math.cos(normal - (yaw + math.pi / 2))) == pytest.approx(1.0, abs=1e-9)
        centre = math.hypot(x, y)
        assert centre - thickness / 2 == pytest.approx(2.540, abs=1e-3)
        assert centre + thickness / 2 == pytest.approx(2.858, abs=1e-3)
        assert length >= 2 * 2.858 * math.tan(math.pi / 6) - 1e-3   # the outer side: no gaps
        normals.append(round(math.degrees(normal)) % 360)
    assert sorted(normals) == [30, 90, 150, 210, 270, 330]        # so corners on the x axis,
    assert 2.540 / math.cos(math.pi / 6) == pytest.approx(2.933, abs=1e-3)   # at r 2.933 inside


def test_the_spawn_is_inside_the_arena_and_clear(tb3_world):
    x, y = WORLDS["turtlebot3_world"].spawn[:2]
    for pillar in (s for s in tb3_world.collisions if s.kind == "cylinder"):
        assert math.hypot(pillar.pose[0] - x, pillar.pose[1] - y) > pillar.size[0] + 0.3
    nearest = min(math.hypot(px - x, py - y) for px in (-1.1, 0, 1.1) for py in (-1.1, 0, 1.1))
    assert nearest == pytest.approx(1.03, abs=0.005)      # centre of the pillar at (-1.1, 0)


# --- the loader ---------------------------------------------------------------------------------

def test_poses_compose_through_nested_models_links_and_elements(tmp_path):
    path = world_file(tmp_path, '''
      <model name="outer"><pose>1 2 0 0 0 1.5707963267948966</pose><static>true</static>
        <model name="inner"><pose>1 0 0 0 0 0</pose>
          <link name="l"><pose>0 0 1 0 0 0</pose>
            <collision name="c"><pose degrees="true">0.5 0 0 0 0 90</pose>
              <geometry><box><size>1 2 3</size></box></geometry></collision>
          </link>
        </model>
      </model>''')
    world = load_world(path)
    (box,) = world.collisions
    assert box.name == "outer::inner::l::c" and box.static
    assert box.pose[:5] == pytest.approx((1.0, 3.5, 1.0, 0.0, 0.0), abs=1e-9)
    assert math.cos(box.pose[5]) == pytest.approx(-1.0)                  # yaw 90 + 90 degrees
    assert box.size == (1.0, 2.0, 3.0)
    assert world.models == ("outer",)


def test_shapes_sizes_and_plane_normal(tmp_path):
    path = world_file(tmp_path, model("<sphere><radius>0.4</radius></sphere>", name="ball")
                      + model("<plane><normal>0 -1 0</normal><size>4 2</size></plane>",
                              name="wall")
                      + model("<cylinder><radius>0.1</radius><length>2</length></cylinder>",
                              pose="0 0 0 1.5707963 0 0", name="rod"))
    world = load_world(path)
    assert world.shape("ball::l::c").size == (0.4,)
    wall = world.shape("wall::l::c")
    assert wall.kind == "plane" and wall.size == (4.0, 2.0)
    assert wall.pose[3:] == pytest.approx((math.pi / 2, 0, 0), abs=1e-9)   # z turned onto -y
    assert world.shape("rod::l::c").size == (0.1, 2.0)


def test_polyline_is_closed_counter_clockwise_and_deduplicated(tmp_path):
    points = "".join("<point>%s</point>" % p for p in ("0 0", "0 1", "1 1", "1 0.5", "1 0", "0 0"))
    path = world_file(tmp_path, model("<polyline>%s<height>0.3</height></polyline>" % points))
    world = load_world(path)
    shape = world.shape("m::l::c")
    assert shape.points == ((0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0))
    assert shape.size == (0.3,)


def test_colours_from_material_script_and_twin(tmp_path):
    def link(name, material):
        return ('<link name="%s"><collision name="c"><geometry><box><size>1 1 1</size></box>'
                '</geometry></collision><visual name="v"><geometry><box><size>1 1 1</size></box>'
                '</geometry>%s</visual></link>' % (name, material))
    script = '<material><script><name>Gazebo/%s</name></script>%s</material>'
    path = world_file(tmp_path, '<model name="m"><static>1</static>%s%s%s%s</model>' % (
        link("green", script % ("Green", "")),
        link("diffuse", script % ("Green", "<diffuse>0.2 0.4 0.6 1</diffuse>")),
        link("ambient", "<material><ambient>0.5 0.5 0.5 0.5</ambient></material>"),
        link("plain", "")))
    world = load_world(path)
    assert world.shape("m::green::v").rgba == (0.0, 1.0, 0.0, 1.0)
    assert world.shape("m::diffuse::v").rgba == (0.2, 0.4, 0.6, 1.0)
    assert world.shape("m::ambient::v").rgba == (0.5, 0.5, 0.5, 0.5)
    assert world.shape("m::plain::v").rgba == DEFAULT_RGBA
    green = world.shape("m::green::c")
    assert green.rgba == (0.0, 1.0, 0.0, 1.0) and green.twin == "m::green::v"
    assert world.shape("m::green::v").twin == "m::green::c"


def test_visual_only_and_dynamic_models(tmp_path):
    path = world_file(tmp_path, '''
      <model name="crate"><link name="l">
        <inertial><mass>2</mass></inertial>
        <collision name="c"><geometry><box><size>1 1 1</size></box></geometry></collision>
        <visual name="v"><pose>0 0 1 0 0 0</pose>
          <geometry><sphere><radius>0.1</radius></sphere></geometry></visual>
      </link></model>''')
    world = load_world(path)
    crate, ball = world.shape("crate::l::c"), world.shape("crate::l::v")
    assert not crate.static and crate.twin is None and not ball.collision and ball.twin is None
    assert crate.rgba == ball.rgba                 # no twin: the link's first visual colours it


def test_includes_and_non_geometry_elements(tmp_path):
    path = world_file(tmp_path, '''
      <include><uri>model://sun</uri></include>
      <include><uri>model://ground_plane</uri></include>
      <physics type="ode"><max_step_size>0.001</max_step_size></physics>
      <scene><ambient>0.4 0.4 0.4 1</ambient></scene>
      <light type="point" name="lamp"><pose>0 0 3 0 0 0</pose></light>
      <plugin name="p" filename="libp.so"/>
      <gui><camera name="c"/></gui>''')
    world = load_world(path)
    assert world.models == ("ground_plane",)
    assert world.shape("ground_plane::link::collision").size == (100.0, 100.0)


def test_a_bare_model_file_loads(tmp_path):
    path = tmp_path / "thing.sdf"
    path.write_text('<sdf version="1.6">%s</sdf>' % model("<box><size>1 1 1</size></box>"))
    world = load_world(str(path))
    assert world.name == "thing" and world.models == ("m",)


# --- bad input ----------------------------------------------------------------------------------


def test_malformed_xml_names_file_and_line(tmp_path):
    path = tmp_path / "broken.world"
    path.write_text('<sdf version="1.6">\n<world name="w">\n<model name="m">\n</world>\n</sdf>\n')
    message = world_fault(str(path))
    assert ":4:" in message and "malformed XML" in message and "mismatched tag" in message


def test_a_geometry_gazebo_11_does_not_know_names_element_file_and_line(tmp_path):
    # (a missing mesh is a warning: test_world_tolerance.py; a heightmap: test_world_elements.py)
    message = world_fault(world_file(tmp_path, model("<capsule><radius>1</radius></capsule>")))
    assert ":4:" in message and "<capsule>" in message and "m::l::c" in message
    assert "box, cylinder, sphere, plane, polyline, mesh, heightmap, image" in message


@pytest.mark.parametrize("geometry, element", [
    ("<box><size>1 one 1</size></box>", "<size>"),
    ("<box><size>1 1</size></box>", "<size>"),
    ("<cylinder><radius>-0.1</radius><length>1</length></cylinder>", "<radius>"),
    ("<sphere><radius>nan</radius></sphere>", "<radius>"),
    ("<polyline><point>0 0</point><point>1 x</point><height>1</height></polyline>", "<point>"),
])
def test_bad_numbers_name_the_element(tmp_path, geometry, element):
    message = world_fault(world_file(tmp_path, model(geometry)))
    assert ":4:" in message and element in message


def test_bad_pose_and_flag(tmp_path):
    assert "<pose>" in world_fault(world_file(tmp_path, model("<sphere/>", pose="0 0 zero 0 0 0")))
    message = world_fault(world_file(tmp_path, '<model name="m"><static>maybe</static></model>'))
    assert "<static>" in message and "maybe" in message


def test_self_crossing_polyline_is_refused(tmp_path):
    points = "".join("<point>%s</point>" % p for p in ("0 0", "1 1", "1 0", "0 1"))
    polyline = "<polyline>%s<height>1</height></polyline>" % points
    message = world_fault(world_file(tmp_path, model(polyline)))
    assert "<polyline>" in message and "simple polygon" in message


@pytest.mark.parametrize("body, words", [
    ('<model name="m"><pose relative_to="x">0 0 0 0 0 0</pose></model>', "relative_to='x'"),
])
def test_garbage_content_is_refused(tmp_path, body, words):
    assert words in world_fault(world_file(tmp_path, body))


def test_a_visual_named_as_another_geometrys_collision_loads_under_a_name_of_its_own(tmp_path):
    # SDF's names are unique per kind (Gazebo loads this); the sim keys shapes by name alone
    world = load_world(world_file(tmp_path, (
        '<model name="m"><static>true</static><link name="l"><collision name="c"><geometry>'
        '<box><size>1 1 1</size></box></geometry></collision><visual name="c"><geometry>'
        '<sphere><radius>1</radius></sphere></geometry></visual></link></model>')))
    assert sorted((s.name, s.collision) for s in world.shapes) == [
        ("m::l::c", True), ("m::l::c~2", False)]
    assert len(world.warnings) == 1 and "m::l::c~2" in world.warnings[0]


def test_not_an_sdf_file(tmp_path):
    path = tmp_path / "robot.sdf"
    path.write_text('<robot name="r"/>')
    assert "<robot>" in world_fault(str(path))


def test_missing_file_is_named(tmp_path):
    missing = str(tmp_path / "nowhere.world")
    assert "cannot read world file: No such file" in world_fault(missing)
    with pytest.raises(WorldError, match="nowhere.world"):
        resolve_world(missing)


def test_unknown_world_name_lists_the_valid_ones():
    with pytest.raises(WorldError) as err:
        resolve_world("turtlebot3_moon")
    message = str(err.value)
    assert "turtlebot3_moon" in message and all(name in message for name in WORLDS)


def test_paths_resolve_with_and_without_spawn(tmp_path):
    path, spawn = resolve_world(os.path.join(WORLD_DIR, "turtlebot3_world.world"))
    assert spawn == (-2.0, -0.5, 0.0)
    mine = world_file(tmp_path, model("<sphere/>"), name="mine.sdf")
    assert resolve_world(mine) == (mine, None)


def test_a_world_file_named_model_loads_as_gazebo_loads_it(tmp_path):
    """Published worlds are named room.model and started with `gazebo room.model`."""
    from tutorial_turtlebot.sim.files.sdf.world_catalogue import resolve_world

    source = resolve_world("turtlebot3_world")[0]
    path = tmp_path / "room.model"
    path.write_text(open(source).read())
    resolved, spawn = resolve_world(str(path))
    assert resolved == str(path) and spawn is None
    assert load_world(resolved).model_specs
