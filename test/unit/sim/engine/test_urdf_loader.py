"""The one way a URDF robot becomes a pybullet body (engine/urdf_loader.py): load_urdf's flags
(fixed links merged, the file's inertia, true cylinders), its one-line error for a bad file; a
plain URDF spawned is not loaded here (it is converted to SDF) and leaves its massless links
out. No ROS master."""
import os

import pybullet
import pytest

from tutorial_turtlebot.errors import UserError
from tutorial_turtlebot.sim.engine.bodies import Body
from tutorial_turtlebot.sim.engine.urdf_loader import load_urdf
from tutorial_turtlebot.sim.files.urdf.urdf_meshes import BARE_LINK_MASS
from unit_helpers import WHEEL, at

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


def test_a_spawned_plain_urdfs_massless_links_are_not_modelled(empty):
    """A plain URDF spawned is converted to SDF as Gazebo converts it (files/urdf/urdf_to_sdf),
    not loaded here: its link without <inertial> on a joint is no link of the model, as in
    Gazebo, and the frame welded on the base adds nothing to the base's 0.5 kg. (A robot's
    bare links, loaded here, weigh BARE_LINK_MASS.)"""
    sim, wc = empty
    warnings = wc.spawn("bare", BARE, at(1.0, 1.0, 0.05), kind="urdf")
    assert BARE_LINK_MASS == 1e-6
    assert wc.model_properties("bare").body_names == ["base"]
    assert wc.get_link_properties("bare::base").mass == pytest.approx(0.5, abs=1e-5)
    assert any("link flag left out" in w for w in warnings)
