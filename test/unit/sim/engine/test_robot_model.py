"""A robot's body is built as every model's is (engine/robot_body.py robot_model, movable_bodies
model_body): its URDF converted into the SDF model Gazebo makes of it, fixed links lumped into
their parent with their inertias, cylinders as true cylinders, the base framed at its centre of
mass; a link without mass left out with one line, and a wheel on such a link refused with one.
No ROS master."""
import os

import pybullet
import pytest

from tutorial_turtlebot.errors import RequestError
from tutorial_turtlebot.sim.engine.bodies import Body
from tutorial_turtlebot.sim.engine.movable_bodies import model_base_frame, model_body
from tutorial_turtlebot.sim.engine.robot_body import robot_model
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf_text
from unit_helpers import ROBOT, at, urdf_body, urdf_text

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


def test_fixed_links_are_lumped_into_their_parent(client):
    body = Body(client, urdf_body(client, WELDED))
    assert [j.name for j in body.joints()] == ["axle"]          # the weld is gone
    assert body.inertial(-1).mass == pytest.approx(3.0)          # base and plate, one link


def test_the_inertia_is_the_files_lumped_about_the_common_centre_of_mass(client):
    """With the plate lumped, the base's moments are the file's and the plate's about the
    common centre of mass (not those of the boxes); the base's frame is that centre of mass."""
    body = Body(client, urdf_body(client, WELDED))
    com_z = 1.0 * 0.1 / 3.0                                      # the plate 0.1 m above
    parallel = 2.0 * com_z ** 2 + 1.0 * (0.1 - com_z) ** 2      # parallel axis, about x and y
    assert body.inertial(-1).moments == pytest.approx(
        (0.5 + 0.01 + parallel, 0.6 + 0.01 + parallel, 0.7 + 0.01), rel=1e-6)
    assert body.inertial(0).moments == pytest.approx((0.01, 0.01, 0.02))
    root, (position, orientation) = model_base_frame(robot_model(
        read_urdf_text(WELDED, "welded"))[0])
    assert root == "welded::base"
    assert position == pytest.approx((0.0, 0.0, com_z)) and orientation == (0, 0, 0, 1)
    assert body.pose()[0] == pytest.approx((0.0, 0.0, com_z))   # built at the origin


def test_a_tilted_inertia_frames_the_base_along_its_principal_axes(client):
    """A base whose inertia has products (the Burger's chassis has small ones): the body's
    frame is along the principal axes, and the tensor about the root link's axes is the
    file's."""
    tilted = WELDED.replace('ixx="0.5" iyy="0.6" izz="0.7" ixy="0"',
                            'ixx="0.5" iyy="0.6" izz="0.7" ixy="0.05"')
    root, (_, orientation) = model_base_frame(robot_model(read_urdf_text(tilted, "t"))[0])
    body = Body(client, urdf_body(client, tilted))
    axes = pybullet.getMatrixFromQuaternion(orientation)
    moments = body.inertial(-1).moments
    tensor = [[sum(axes[3 * i + k] * moments[k] * axes[3 * j + k] for k in range(3))
               for j in range(3)] for i in range(3)]
    com_z = 0.1 / 3.0
    parallel = 2.0 * com_z ** 2 + 1.0 * (0.1 - com_z) ** 2
    assert tensor[0][1] == pytest.approx(0.05) and tensor[2][2] == pytest.approx(0.71)
    assert tensor[0][0] == pytest.approx(0.51 + parallel)


def test_a_cylinder_is_a_true_cylinder(client):
    body = urdf_body(client, WELDED)
    shape = pybullet.getCollisionShapeData(body, 0, physicsClientId=client)[0]
    assert shape[2] == pybullet.GEOM_CYLINDER
    assert shape[3][:2] == pytest.approx((0.04, 0.1))            # length, radius


def test_building_leaves_no_file_behind(client, monkeypatch, tmp_path):
    monkeypatch.setattr("tempfile.tempdir", str(tmp_path))
    assert model_body(robot_model(read_urdf_text(WELDED, "welded"))[0], client) >= 0
    assert os.listdir(str(tmp_path)) == []


def test_a_spawned_plain_urdfs_massless_links_are_not_modelled(empty):
    """A plain URDF spawned is converted to SDF as Gazebo converts it (files/urdf/urdf_to_sdf):
    its link without <inertial> on a joint is no link of the model, as in Gazebo, and the
    frame welded on the base adds nothing to the base's 0.5 kg."""
    sim, wc = empty
    warnings = wc.spawn("bare", BARE, at(1.0, 1.0, 0.05), kind="urdf")
    assert wc.model_properties("bare").body_names == ["base"]
    assert wc.get_link_properties("bare::base").mass == pytest.approx(0.5, abs=1e-9)
    assert any("link flag left out" in w for w in warnings)


def massless(urdf, link):
    """``urdf`` with the <inertial> of link ``link`` taken out."""
    start = urdf.index('<link name="%s">' % link)
    begin = urdf.index("<inertial>", start)
    end = urdf.index("</inertial>", begin) + len("</inertial>")
    return urdf[:begin] + urdf[end:]


def test_a_robots_massless_links_are_left_out_with_one_line_and_its_wheels_must_weigh(empty):
    """A robot is the same model: a massless link on a joint is left out with one warning
    line (the robot's own), as Gazebo leaves it out; a wheel of its drive on such a link
    refuses the spawn with one line."""
    sim, wc = empty
    burger = urdf_text("burger")
    flagged = burger.replace("</robot>", '<link name="flag"><collision><geometry><box size='
                             '"0.02 0.02 0.2"/></geometry></collision></link><joint name="pivot" '
                             'type="continuous"><parent link="base_link"/><child link="flag"/>'
                             '<origin xyz="0 0 0.3"/><axis xyz="0 0 1"/></joint></robot>')
    wc.spawn("flagged", flagged, at(1.0, 1.0), kind="urdf", robot_namespace="flagged")
    robot = sim.robots["flagged"]
    assert [w for w in robot.warnings if "link flag left out" in w] and \
        all("\n" not in w for w in robot.warnings)
    assert wc.model_properties("flagged").body_names == wc.model_properties(ROBOT).body_names
    with pytest.raises(RequestError) as err:
        wc.spawn("limp", massless(burger, "wheel_left_link"), at(-1.0, 1.0), kind="urdf",
                 robot_namespace="limp")
    assert "joint 'wheel_left_joint' is not simulated" in str(err.value)
    assert "\n" not in str(err.value) and "limp" not in wc.models.names()
