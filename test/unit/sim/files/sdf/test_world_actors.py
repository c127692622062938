"""<actor>s read as Gazebo 11 reads them (world_actors, through world_sdf): scripts, skins, their
links without collisions, their place in the world's model list. No pybullet, no ROS master.
The fixture world and skin are our own (test/fixtures/worlds/actors.world)."""
import os

import pytest

from tutorial_turtlebot.sim.files.meshes.mesh_file import cache_clear
from tutorial_turtlebot.sim.files.sdf.world_actors import SKIN_BOX, skin_names
from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world

from unit_helpers import world_fault, world_file
import unit_paths

FIXTURES = unit_paths.FIXTURES
ACTORS = os.path.join(FIXTURES, "worlds", "actors.world")


@pytest.fixture(autouse=True)
def model_path(tmp_path, monkeypatch):
    monkeypatch.setenv("GAZEBO_MODEL_PATH", os.path.join(FIXTURES, "gazebo_models"))
    monkeypatch.delenv("GAZEBO_RESOURCE_PATH", raising=False)
    monkeypatch.chdir(tmp_path)
    cache_clear()


def actor(body, name="a", pose="1 2 0 0 0 0"):
    return '<actor name="%s"><pose>%s</pose>%s</actor>' % (name, pose, body)


def script(*trajectories, extra=""):
    return "<script>%s%s</script>" % (extra, "".join(trajectories))


def trajectory(points, ident=0, kind="walk", tension=""):
    waypoints = "".join("<waypoint><time>%s</time><pose>%s</pose></waypoint>" % p for p in points)
    tension = ' tension="%s"' % tension if tension else ""
    return '<trajectory id="%s" type="%s"%s>%s</trajectory>' % (ident, kind, tension, waypoints)


def test_the_fixture_world_loads_with_its_actors_after_its_models():
    """Gazebo's World::LoadEntities loads every model first, then every actor: that is the order
    of /gazebo/model_states."""
    world = load_world(ACTORS)
    assert world.models == ("ground_plane", "curtain_rail", "wall", "walker", "pacer")
    assert [a.name for a in world.actors] == ["walker", "pacer"]
    walker, pacer = world.actors
    assert walker.loop and walker.auto_start and walker.delay_start == 0.0
    assert not pacer.loop and pacer.delay_start == 1.0
    [walk] = walker.trajectories
    assert (walk.id, walk.type, walk.tension, walk.duration) == (0, "walking", 0.0, 20.0)
    assert [w.time for w in walk.waypoints] == [0, 4, 5, 9, 10, 14, 15, 19, 20]
    assert walk.waypoints[2].pose == pytest.approx((2, -2, 0, 0, 0, 1.5707963))
    assert world.model("walker").pose == (0.0, -2.0, 0.0, 0.0, 0.0, 0.0)
    assert world.model("walker").static


def test_a_skin_with_triangles_is_drawn_and_one_without_is_a_box_with_one_warning():
    world = load_world(ACTORS)
    link, visual = skin_names("walker")
    skin = world.shape(visual)
    assert (skin.kind, skin.link, skin.collision) == ("mesh", link, False)
    assert skin.mesh.endswith("actor_person/meshes/person.dae") and skin.mesh_colours
    assert world.actor("walker").skin == skin.mesh
    box = world.shape(skin_names("pacer")[1])
    assert (box.kind, box.size) == ("box", SKIN_BOX)
    assert box.pose[:3] == pytest.approx((-1.0, 1.0, SKIN_BOX[2] / 2))   # standing on it
    assert world.actor("pacer").skin == ""
    skin_warnings = [w for w in world.warnings if "skin walk.dae" in w]
    assert len(skin_warnings) == 1 and "0.5 x 0.5 x 1.8 m box" in skin_warnings[0]
    assert all(len(w) <= 200 and "\n" not in w for w in world.warnings)


SKINNED_ONLY = """<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<library_geometries><geometry id="g"><mesh><source id="p">
<float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array><technique_common>
<accessor source="#pa" count="3" stride="3"><param name="X" type="float"/>
<param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common>
</source><vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
</mesh></geometry></library_geometries>
<library_controllers><controller id="c"><skin source="#g">
<bind_shape_matrix>1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</bind_shape_matrix>
<source id="j"><Name_array id="ja" count="1">root</Name_array><technique_common>
<accessor source="#ja" count="1" stride="1"><param name="JOINT" type="name"/></accessor>
</technique_common></source>
<source id="m"><float_array id="ma" count="16">1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1</float_array>
<technique_common><accessor source="#ma" count="1" stride="16">
<param name="TRANSFORM" type="float4x4"/></accessor></technique_common></source>
<source id="w"><float_array id="wa" count="1">1</float_array><technique_common>
<accessor source="#wa" count="1" stride="1"><param name="WEIGHT" type="float"/></accessor>
</technique_common></source>
<joints><input semantic="JOINT" source="#j"/><input semantic="INV_BIND_MATRIX" source="#m"/>
</joints><vertex_weights count="3"><input semantic="JOINT" source="#j" offset="0"/>
<input semantic="WEIGHT" source="#w" offset="1"/><vcount>1 1 1</vcount><v>0 0 0 0 0 0</v>
</vertex_weights></skin></controller></library_controllers>
<library_visual_scenes><visual_scene id="s"><node id="root" sid="root" type="JOINT"/>
<node id="body"><instance_controller url="#c"><skeleton>#root</skeleton></instance_controller>
</node></visual_scene></library_visual_scenes><scene><instance_visual_scene url="#s"/></scene>
</COLLADA>"""


def test_a_skin_of_skinned_geometry_only_is_a_box_with_one_warning(tmp_path):
    """As Gazebo's stock people are written: the scene holds the geometry only through a
    skin controller, which is not drawn without skinning."""
    (tmp_path / "person.dae").write_text(SKINNED_ONLY)
    world = load_world(world_file(tmp_path, actor(
        "<skin><filename>person.dae</filename></skin>"
        + script(trajectory([(0, "0 0 0 0 0 0"), (2, "1 0 0 0 0 0")])))))
    assert world.shape(skin_names("a")[1]).kind == "box"
    [line] = world.warnings
    assert "actor a: skin person.dae drawn as a 0.5 x 0.5 x 1.8 m box: " in line
    assert "no triangles" in line


def test_an_actors_links_keep_their_visuals_and_lose_their_collisions():
    """Gazebo 11 never initialises an actor's links (Actor::Init): no collision of an actor
    reaches the physics, so lasers and contacts pass through it."""
    world = load_world(ACTORS)
    assert [s.name for s in world.model_shapes("pacer")] == ["pacer::pacer_pose::pacer_visual",
                                                             "pacer::badge::visual"]
    assert not any(s.collision for s in world.model_shapes("pacer") + world.model_shapes("walker"))
    badge = world.shape("pacer::badge::visual")
    assert badge.twin is None and badge.pose[:3] == pytest.approx((-1.0, 1.0, 1.9))
    assert [link.scoped for link in world.model("pacer").links] == ["pacer::pacer_pose",
                                                                    "pacer::badge"]


def test_an_actors_plugin_is_one_warning_and_the_actor_still_loads():
    world = load_world(ACTORS)
    [line] = [w for w in world.warnings if "<plugin>" in w]
    assert ":66: <plugin> of an actor skipped: " in line and "follows its <script>" in line


def test_waypoints_as_gazebo_keeps_them(tmp_path):
    """Actor::LoadScript: waypoints by time, the last of a time winning, the first moved to 0;
    trajectories by id; tension clamped to 0..1."""
    body = actor(script(
        trajectory([(3, "3 0 0 0 0 0"), (1, "1 0 0 0 0 0"), (3, "9 0 0 0 0 0")], ident=5,
                   tension="7"),
        trajectory([(2, "0 2 0 0 0 0"), (4, "0 4 0 0 0 0")], ident=2, kind="run")))
    [a] = load_world(world_file(tmp_path, body)).actors
    assert [t.id for t in a.trajectories] == [2, 5]
    run, walk = a.trajectories
    assert [(w.time, w.pose[:2]) for w in run.waypoints] == [(0.0, (0.0, 2.0)), (4, (0.0, 4.0))]
    assert [(w.time, w.pose[0]) for w in walk.waypoints] == [(0.0, 1.0), (3, 9.0)]
    assert walk.tension == 1.0 and run.duration == 4


def test_an_actor_without_script_skin_or_links_loads_and_stands(tmp_path):
    world = load_world(world_file(tmp_path, actor("")))
    assert world.models == ("a",) and world.model_shapes("a") == ()
    [a] = world.actors
    assert a.trajectories == () and a.pose[:2] == (1.0, 2.0) and world.warnings == ()


def test_an_included_actor_file_is_an_actor(tmp_path, monkeypatch):
    """sdformat 9 includes a file whose top element is an <actor> (readXml's isActor)."""
    folder = tmp_path / "models" / "visitor"
    folder.mkdir(parents=True)
    (folder / "model.config").write_text('<model><sdf version="1.6">a.sdf</sdf></model>')
    (folder / "a.sdf").write_text('<sdf version="1.6">%s</sdf>'
                                  % actor(script(trajectory([(0, "0 0 0 0 0 0")]))))
    monkeypatch.setenv("GAZEBO_MODEL_PATH", str(tmp_path / "models"))
    world = load_world(world_file(tmp_path, '<include><uri>model://visitor</uri><name>v2</name>'
                                            '<pose>5 5 0 0 0 0</pose></include>'))
    assert world.models == ("v2",) and world.actor("v2").pose[:2] == (5.0, 5.0)


@pytest.mark.parametrize("body, words", [
    (script(trajectory([("nan", "0 0 0 0 0 0")])), "<time> nan"),
    (script(trajectory([("-1", "0 0 0 0 0 0")])), "<time> -1 is outside"),
    (script(trajectory([(1, "0 nan 0 0 0 0")])), "<pose>"),
    (script(trajectory([(1, "0 0 0 0 0 0")], ident="x")), "<trajectory id='x'>: must be an "
     "integer"),
    (script(extra="<delay_start>inf</delay_start>"), "<delay_start> inf"),
    ("<skin><filename>x.dae</filename><scale>-1</scale></skin>", "<scale>"),
])
def test_garbage_in_an_actor_is_refused_in_one_line(tmp_path, body, words):
    assert words in world_fault(world_file(tmp_path, actor(body)))
