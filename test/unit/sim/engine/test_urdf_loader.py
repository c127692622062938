"""The one way a URDF becomes a pybullet body (engine/urdf_loader.py): load_urdf's flags (fixed
links merged, the file's inertia, true cylinders), its one-line error for a bad file, the set-up
of a spawned movable model (load_movable), one held in place (a fixed base, its meshes as
triangles), and the mass of a bare link once spawned. No ROS master."""
import os
from xml.etree import ElementTree

import pybullet
import pytest

from tutorial_turtlebot.errors import UserError
from tutorial_turtlebot.sim.engine import collision_filters
from tutorial_turtlebot.sim.engine.bodies import Body
from tutorial_turtlebot.sim.engine.urdf_loader import load_movable, load_urdf
from tutorial_turtlebot.sim.engine.collision_groups import (ALL_COLLISION_GROUPS,
                                                            MOVABLE_COLLISION_GROUP,
                                                            WORLD_COLLISION_GROUP,
                                                            WORLD_COLLISION_MASK)
from tutorial_turtlebot.sim.files.urdf import urdf_meshes
from tutorial_turtlebot.sim.files.urdf.urdf_meshes import BARE_LINK_MASS
from unit_helpers import WHEEL, at
import unit_paths

ANCHORS = os.path.normpath(os.path.join(unit_paths.UNIT, os.pardir, "fixtures", "urdf_anchors"))

# A 2 kg base whose inertia (not a box's: a 0.4 x 0.2 x 0.1 box of 2 kg has 0.0083 0.0283
# 0.0333) is the file's; a 1 kg plate welded on it (fixed joint); a wheel on a continuous joint.
WELDED = """<robot name="welded">
<link name="base"><inertial><mass value="2.0"/>
<inertia ixx="0.5" iyy="0.6" izz="0.7" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><geometry><box size="0.4 0.2 0.1"/></geometry></collision></link>
<link name="plate"><inertial><mass value="1.0"/>
<inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><geometry><box size="0.2 0.2 0.01"/></geometry></collision></link>
<joint name="weld" type="fixed"><parent link="base"/><child link="plate"/>
<origin xyz="0 0 0.1"/></joint>
<link name="wheel"><inertial><mass value="0.5"/>
<inertia ixx="0.01" iyy="0.01" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><geometry><cylinder radius="0.1" length="0.04"/></geometry></collision></link>
<joint name="axle" type="continuous"><parent link="base"/><child link="wheel"/>
<origin xyz="0.3 0 0"/><axis xyz="0 0 1"/></joint>
</robot>
"""
# A plain URDF (no plugins): a 0.5 kg base, a frame welded on it and a flag on a revolute joint,
# neither of them with an <inertial>.
BARE = """<robot name="bare">
<link name="base"><inertial><mass value="0.5"/>
<inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
<link name="tag"/>
<joint name="weld" type="fixed"><parent link="base"/><child link="tag"/>
<origin xyz="0 0 0.1"/></joint>
<link name="flag"><collision><geometry><box size="0.02 0.02 0.2"/></geometry></collision></link>
<joint name="pivot" type="revolute"><parent link="base"/><child link="flag"/>
<origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
</joint>
</robot>
"""


def plain_load(client, tmp_path, urdf):
    """The body pybullet makes of ``urdf`` without load_urdf's flags (for contrast)."""
    path = tmp_path / "plain.urdf"
    path.write_text(urdf)
    return pybullet.loadURDF(str(path), physicsClientId=client)


def test_fixed_links_are_merged_into_their_parent(client, tmp_path):
    body = Body(client, load_urdf(client, WELDED))
    assert [j.name for j in body.joints()] == ["axle"]          # the weld is gone
    assert body.inertial(-1).mass == pytest.approx(3.0)          # base and plate, one link
    assert pybullet.getNumJoints(plain_load(client, tmp_path, WELDED),
                                 physicsClientId=client) == 2


def test_the_inertia_is_the_files(client, tmp_path):
    """With the plate merged, the base's moments are the file's and the plate's about the
    common centre of mass, not those pybullet would work out from the boxes."""
    body = Body(client, load_urdf(client, WELDED))
    com_z = 1.0 * 0.1 / 3.0                                      # the plate 0.1 m above
    parallel = 2.0 * com_z ** 2 + 1.0 * (0.1 - com_z) ** 2      # parallel axis, about x and y
    assert body.inertial(-1).moments == pytest.approx(
        (0.5 + 0.01 + parallel, 0.6 + 0.01 + parallel, 0.7 + 0.01), rel=1e-4)
    assert body.inertial(0).moments == pytest.approx((0.01, 0.01, 0.02))
    plain = pybullet.getDynamicsInfo(plain_load(client, tmp_path, WELDED), -1,
                                     physicsClientId=client)
    assert plain[2][0] < 0.1                                     # the box's, not the file's


def test_a_cylinder_is_a_true_cylinder(client, tmp_path):
    body = load_urdf(client, WELDED)
    shape = pybullet.getCollisionShapeData(body, 0, physicsClientId=client)[0]
    assert shape[2] == pybullet.GEOM_CYLINDER
    assert shape[3][:2] == pytest.approx((0.04, 0.1))            # length, radius
    plain = plain_load(client, tmp_path, WELDED)
    flags_off = pybullet.getCollisionShapeData(plain, 1, physicsClientId=client)[0]
    assert flags_off[2] == pybullet.GEOM_MESH                    # what pybullet would make


@pytest.mark.parametrize("urdf", [
    "<robot name='x'><link name='a'>",                          # cut short
    "this is no URDF",
    "<robot name='x'><joint name='j' type='revolute'><parent link='a'/><child link='b'/>"
    "</joint></robot>",                                         # links that are not there
])
def test_a_bad_urdf_is_one_quiet_line(client, capfd, monkeypatch, tmp_path, urdf):
    monkeypatch.setattr("tempfile.tempdir", str(tmp_path))      # where the text is written
    with pytest.raises(UserError) as err:
        load_urdf(client, urdf)
    message = str(err.value)
    assert "\n" not in message and message.startswith("pybullet could not load the URDF")
    out, err_text = capfd.readouterr()
    assert out == "" and err_text == ""                          # pybullet's notes silenced
    assert os.listdir(str(tmp_path)) == []                       # its file removed
    assert pybullet.getNumBodies(physicsClientId=client) == 0


def test_load_urdf_writes_no_file_it_leaves_behind(client, monkeypatch, tmp_path):
    monkeypatch.setattr("tempfile.tempdir", str(tmp_path))
    assert load_urdf(client, WHEEL) >= 0
    assert os.listdir(str(tmp_path)) == []


def spin(client, body, seconds=1.0):
    """The wheel's rate after it was set turning at 2 rad/s and ``seconds`` of steps (gravity
    0, the client's 240 Hz step)."""
    pybullet.setGravity(0, 0, 0, physicsClientId=client)
    body.set_joint(0, 0.0, 2.0)
    for _ in range(round(seconds * 240)):
        pybullet.stepSimulation(physicsClientId=client)
    return body.joint_state(0)[1]


def test_a_movable_models_joints_turn_freely(client):
    movable = load_movable(client, WHEEL)
    assert isinstance(movable, Body) and movable.client == client
    assert spin(client, movable) == pytest.approx(2.0, rel=1e-3)
    # Loaded plainly, pybullet's default velocity motor brakes the joint to a stop.
    braked = Body(client, load_urdf(client, WHEEL))
    braked.set_pose(((5.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)))
    assert abs(spin(client, braked)) < 0.01


def test_a_movable_model_is_in_the_movable_collision_group(client):
    """Rays with a mask of the movable group hit it (every link), rays with a mask of every
    other group miss it."""
    movable = load_movable(client, WHEEL)
    others = ALL_COLLISION_GROUPS & ~MOVABLE_COLLISION_GROUP

    def hit(start, end, mask):
        return pybullet.rayTestBatch([start], [end], collisionFilterMask=mask,
                                     physicsClientId=client)[0][0:2]
    for start, end, link in (((1, 0, 0), (-1, 0, 0), -1),            # through the base
                             ((0, 0, 1), (0, 0, 0.21), 0)):           # down onto the disc
        assert hit(start, end, MOVABLE_COLLISION_GROUP) == (movable.uid, link)
        assert hit(start, end, MOVABLE_COLLISION_GROUP & ~WORLD_COLLISION_GROUP) \
            == (movable.uid, link)
        assert hit(start, end, others)[0] == -1


def test_a_movable_models_base_slides_with_friction_1(client):
    movable = load_movable(client, WHEEL)
    assert pybullet.getDynamicsInfo(movable.uid, -1, physicsClientId=client)[1] == 1.0


def test_a_movable_models_links_slide_with_friction_1(client):
    movable = load_movable(client, WHEEL)
    assert pybullet.getDynamicsInfo(movable.uid, 0, physicsClientId=client)[1] == 1.0


def test_a_spawned_bare_link_weighs_next_to_nothing(empty):
    """A link without <inertial> in a spawned plain URDF gets BARE_LINK_MASS, not pybullet's
    default 1 kg: the flag on its joint weighs 1e-6 kg, and the frame welded on the base adds
    nothing to the base's 0.5 kg."""
    sim, wc = empty
    wc.spawn("bare", BARE, at(1.0, 1.0, 0.05), kind="urdf")
    assert BARE_LINK_MASS == 1e-6
    assert wc.get_link_properties("bare::flag").mass == pytest.approx(BARE_LINK_MASS)
    assert wc.get_link_properties("bare::base").mass == pytest.approx(0.5, abs=1e-5)
    cid = sim.physics.client
    uid = next(pybullet.getBodyUniqueId(i, physicsClientId=cid)
               for i in range(pybullet.getNumBodies(physicsClientId=cid))
               if pybullet.getBodyInfo(pybullet.getBodyUniqueId(i, physicsClientId=cid),
                                       physicsClientId=cid)[1] == b"bare")
    assert pybullet.getDynamicsInfo(uid, 0, physicsClientId=cid)[0] == pytest.approx(1e-6)
    assert pybullet.getDynamicsInfo(uid, -1, physicsClientId=cid)[0] == pytest.approx(
        0.5, abs=1e-5)


# --- a model held in place (a static URDF, a root link "world"): a fixed base ------------------

def test_a_fixed_base_stays_where_it_is_put_and_collides_as_a_world_body(client):
    """load_movable with fixed_base: gravity and a falling box move nothing; its base is in
    the world's collision group (a laser's rays see it), its turning links in the movable
    one; set_pose still moves it."""
    collision_filters.track(client)
    pybullet.setGravity(0, 0, -9.8, physicsClientId=client)
    held = load_movable(client, WHEEL, fixed_base=True)
    falling = load_movable(client, WHEEL)
    held.set_pose(((0.0, 0.0, 1.0), (0.0, 0.0, 0.0, 1.0)))
    falling.set_pose(((0.0, 0.0, 2.0), (0.0, 0.0, 0.0, 1.0)))   # lands on the held one
    for _ in range(480):
        pybullet.stepSimulation(physicsClientId=client)
    assert held.pose() == ((0.0, 0.0, 1.0), (0.0, 0.0, 0.0, 1.0))
    assert 1.0 < falling.pose()[0][2] < 1.9                     # resting on it, above it
    filters = collision_filters.colliders(client)
    assert filters[(held.uid, -1)] == (WORLD_COLLISION_GROUP, WORLD_COLLISION_MASK)
    assert filters[(held.uid, 0)] == (MOVABLE_COLLISION_GROUP, ALL_COLLISION_GROUPS)
    assert filters[(falling.uid, -1)] == (MOVABLE_COLLISION_GROUP, ALL_COLLISION_GROUPS)
    held.set_pose(((3.0, 0.0, 1.0), (0.0, 0.0, 0.0, 1.0)))
    pybullet.stepSimulation(physicsClientId=client)
    assert held.pose()[0] == (3.0, 0.0, 1.0)


def test_a_concave_mesh_collides_as_triangles_on_a_fixed_base(client, tmp_path):
    """The text bullet_urdf_text writes for a held link (its collision mesh as triangles,
    concave="yes"): a ray down into the open trough meets its floor, not the hull's top."""
    trough = os.path.join(ANCHORS, "meshes", "trough.obj")
    text = ('<robot name="t"><link name="base"><collision><geometry><mesh filename="%s"/>'
            '</geometry></collision></link></robot>' % trough)
    root = ElementTree.fromstring(text)
    for held, top in ((("base",), 0.0), ((), 1.0)):
        body = load_movable(client, urdf_meshes.bullet_urdf_text(root, str(tmp_path), False,
                                                                 held), fixed_base=True)
        hit = pybullet.rayTest((0, 0, 3), (0, 0, -1), physicsClientId=client)[0]
        assert hit[0] == body.uid and hit[3][2] == pytest.approx(top, abs=0.01)
        body.remove()
