"""bullet_shapes: each distinct collision shape is built once per pybullet client and shared;
past the budget a new one is refused in one line, and a spawn refused so leaves no body. The
real pybullet, no ROS master."""

import numpy as np
import pybullet
import pytest

from tutorial_turtlebot.errors import RequestError
from tutorial_turtlebot.sim.engine import bullet_shapes
from tutorial_turtlebot.sim.engine.client import Client
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import rss_kb


@pytest.fixture
def client():
    connected = Client.connect()
    bullet_shapes.track(connected)
    yield connected
    connected.disconnect()
    bullet_shapes.forget_client(connected)


def obj_file(path, points):
    with open(path, "w") as f:
        f.write("".join("v %.6f %.6f %.6f\n" % tuple(p) for p in points))
        f.write("f 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n")
    return str(path)


def test_the_same_shape_is_built_once(client):
    box = bullet_shapes.collision_shape(client, pybullet.GEOM_BOX, halfExtents=[0.1, 0.2, 0.3])
    again = bullet_shapes.collision_shape(client, pybullet.GEOM_BOX,
                                          halfExtents=(0.1, 0.2, 0.3))
    other = bullet_shapes.collision_shape(client, pybullet.GEOM_BOX, halfExtents=[0.1, 0.2, 0.4])
    assert box == again != other
    # two bodies share it, and both collide with it
    a = pybullet.createMultiBody(0, box, physicsClientId=client)
    b = pybullet.createMultiBody(0, again, basePosition=(5, 0, 0), physicsClientId=client)
    hits = pybullet.rayTestBatch([(0, 0, 2), (5, 0, 2)], [(0, 0, -2), (5, 0, -2)],
                                 physicsClientId=client)
    assert [h[0] for h in hits] == [a, b]
    assert [round(h[3][2], 6) for h in hits] == [0.3, 0.3]


def test_mesh_files_are_known_by_their_content(client, tmp_path):
    corners = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    first = obj_file(tmp_path / "a.obj", corners)
    same = obj_file(tmp_path / "b.obj", corners)
    moved = obj_file(tmp_path / "c.obj", [(x + 1, y, z) for x, y, z in corners])

    def shape(path):
        return bullet_shapes.collision_shape(client, pybullet.GEOM_MESH, fileName=path)

    assert shape(first) == shape(same) != shape(moved)
    vertices = np.array(corners, dtype=float)
    arrays = [bullet_shapes.collision_shape(client, pybullet.GEOM_MESH, vertices=v.tolist(),
                                            indices=[0, 1, 2, 0, 2, 3],
                                            flags=pybullet.GEOM_FORCE_CONCAVE_TRIMESH)
              for v in (vertices, vertices.copy(), vertices * 2)]
    assert arrays[0] == arrays[1] != arrays[2]


def test_an_untracked_client_builds_every_shape():
    client = Client.connect()
    try:
        first, second = (bullet_shapes.collision_shape(client, pybullet.GEOM_SPHERE, radius=0.1)
                         for _ in range(2))
        assert first != second
    finally:
        client.disconnect()


def test_past_the_budget_a_new_shape_is_refused_and_old_ones_still_come(client, monkeypatch):
    monkeypatch.setattr(bullet_shapes, "MAX_SHAPE_BYTES", 3 * bullet_shapes.PRIMITIVE_BYTES)
    sizes = [[0.1 * (i + 1)] * 3 for i in range(3)]
    built = [bullet_shapes.collision_shape(client, pybullet.GEOM_BOX, halfExtents=s)
             for s in sizes]
    with pytest.raises(bullet_shapes.ShapeBudgetError) as refused:
        bullet_shapes.collision_shape(client, pybullet.GEOM_BOX, halfExtents=[0.9] * 3)
    assert "\n" not in str(refused.value) and "frees none" in str(refused.value)
    assert bullet_shapes.collision_shape(client, pybullet.GEOM_BOX,
                                         halfExtents=sizes[1]) == built[1]


def box_model(size, count=1):
    links = "".join(
        "<link name='l%d'><pose>%d 0 0 0 0 0</pose><inertial><mass>1</mass></inertial>"
        "<collision name='c'><geometry><box><size>%g %g %g</size></box></geometry></collision>"
        "</link>" % (i, 2 * i, size + i, size, size) for i in range(count))
    return "<sdf version='1.6'><model name='m'>%s</model></sdf>" % links


def test_a_spawn_over_the_budget_is_refused_and_leaves_no_body(monkeypatch):
    sim = Simulation(SimConfig(world="empty", spawn_robot=False))
    try:
        wc = WorldControl(sim)
        cid = sim.physics.client
        pose = ((0.0, 0.0, 1.0), (0.0, 0.0, 0.0, 1.0))
        wc.spawn("first", box_model(0.2), pose)
        held = bullet_shapes.shape_bytes(cid)
        # room for one more shape: the model's first link is built, its second is refused
        monkeypatch.setattr(bullet_shapes, "MAX_SHAPE_BYTES",
                            held + bullet_shapes.PRIMITIVE_BYTES)
        bodies = pybullet.getNumBodies(physicsClientId=cid)
        with pytest.raises(RequestError) as refused:
            wc.spawn("second", box_model(0.5, count=2), pose)
        assert str(refused.value).startswith("SpawnModel: Failure - this simulation holds")
        assert pybullet.getNumBodies(physicsClientId=cid) == bodies
        assert "second" not in wc.models
        # the first model's text again: its shape exists, nothing new is needed
        wc.delete("first")
        wc.spawn("first", box_model(0.2), pose)
        assert "first" in wc.models
    finally:
        sim.close()


def mesh_model(path):
    mesh = "<geometry><mesh><uri>file://%s</uri></mesh></geometry>" % path
    return ("<sdf version='1.6'><model name='m'><static>true</static><link name='l'>"
            "<collision name='c'>%s</collision></link></model></sdf>" % mesh)


def test_meshes_spawned_again_after_their_bodies_were_removed_cost_no_memory(tmp_path):
    """40 static meshes (more than the parked bodies kept) spawned and deleted in turn, three
    times: each round after the first rebuilds every body, from the shapes built in the first.
    Without the sharing each rebuilt 1,000-triangle mesh kept about 0.85 MB."""
    rng = np.random.default_rng(7)
    paths = []
    for i in range(40):
        points = rng.normal(size=(3000, 3)) * 0.2 + (0.0, 0.0, 0.5)
        path = tmp_path / ("m%d.obj" % i)
        with open(path, "w") as f:
            f.write("".join("v %.6f %.6f %.6f\n" % tuple(p) for p in points))
            f.write("".join("f %d %d %d\n" % (j + 1, j + 2, j + 3) for j in range(0, 3000, 3)))
        paths.append(str(path))
    sim = Simulation(SimConfig(world="empty"))
    try:
        wc = WorldControl(sim)
        pose = ((3.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))

        def round_of_spawns():
            for i, path in enumerate(paths):
                wc.spawn("mesh%d" % i, mesh_model(path), pose)
                sim.step()
                wc.delete("mesh%d" % i)
        round_of_spawns()
        start = rss_kb()
        round_of_spawns()
        round_of_spawns()
        grown = rss_kb() - start
        assert grown < 8 * 1024, "80 rebuilt meshes grew RSS by %d KB" % grown
    finally:
        sim.close()
