"""Body (engine/bodies.py), the handle of one pybullet body: its pose and twist, joints, link
frames, masses, and finite(). Each method is checked against known values of a small URDF of
its own (built as a robot's body is: unit_helpers.urdf_body) and against pybullet's own
answers. No ROS master."""
import math

import pybullet
import pytest

from tutorial_turtlebot.sim.engine.bodies import Body, Inertial, Joint
from tutorial_turtlebot.sim.engine.client import Client
from unit_helpers import urdf_body

# A 2 kg base (its centre of mass 0.1 m ahead of its frame) with an arm on a revolute joint about
# y (damping 0.3) and a slider on a prismatic joint along x; the three inertias are diagonal.
ARM = """<robot name="arm">
<link name="base">
<inertial><origin xyz="0.1 0 0"/><mass value="2.0"/>
<inertia ixx="0.01" iyy="0.02" izz="0.03" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><geometry><box size="0.4 0.2 0.1"/></geometry></collision>
</link>
<link name="arm_link">
<inertial><origin xyz="0 0 0.2"/><mass value="0.5"/>
<inertia ixx="0.004" iyy="0.005" izz="0.006" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.02" length="0.4"/></geometry>
</collision>
</link>
<link name="slider_link">
<inertial><mass value="0.25"/>
<inertia ixx="0.001" iyy="0.002" izz="0.003" ixy="0" ixz="0" iyz="0"/></inertial>
<collision><geometry><box size="0.05 0.05 0.05"/></geometry></collision>
</link>
<joint name="hinge" type="revolute"><parent link="base"/><child link="arm_link"/>
<origin xyz="0.2 0 0.05"/><axis xyz="0 1 0"/>
<limit lower="-3" upper="3" effort="10" velocity="5"/><dynamics damping="0.3"/></joint>
<joint name="slide" type="prismatic"><parent link="base"/><child link="slider_link"/>
<origin xyz="-0.2 0 0.05"/><axis xyz="1 0 0"/>
<limit lower="-0.1" upper="0.1" effort="10" velocity="1"/></joint>
</robot>
"""
IDENTITY = (0.0, 0.0, 0.0, 1.0)


@pytest.fixture
def arm(client):
    return Body(client, urdf_body(client, ARM))


def about_y(angle):
    return (0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2))


def test_equal_handles_name_the_same_body():
    a, b, c = Client(0), Client(1), Client(2)          # never connected: no call is made
    assert Body(a, 3) == Body(a, 3) and hash(Body(a, 3)) == hash(Body(a, 3))
    assert Body(a, 3) != Body(a, 4) and Body(a, 3) != Body(b, 3)
    assert Body(a, 3) != (a, 3)                        # a tuple is no Body
    assert len({Body(a, 3), Body(a, 3), Body(b, 3)}) == 2
    assert {Body(c, 5): "x"}[Body(c, 5)] == "x"
    assert repr(Body(c, 5)) == "Body(2, 5)"


def test_the_base_frame_is_the_centre_of_mass(arm):
    # The base's frame is its centre of mass: 0.1 m ahead of the root link, axes unturned.
    pos, orn = arm.pose()
    assert pos == pytest.approx((0.1, 0.0, 0.0)) and orn == pytest.approx(IDENTITY)


def test_set_pose_and_twist_are_read_back(arm):
    pose = ((1.0, -2.0, 3.0), about_y(0.4))
    arm.set_pose(pose)
    pos, orn = arm.pose()
    assert pos == pytest.approx(pose[0]) and orn == pytest.approx(pose[1])
    raw = pybullet.getBasePositionAndOrientation(arm.uid, physicsClientId=arm.client)
    assert pos == pytest.approx(raw[0]) and orn == pytest.approx(raw[1])
    twist = ((0.5, -0.25, 0.125), (0.0, 0.0, 1.5))
    arm.set_twist(twist)
    lin, ang = arm.twist()
    assert lin == pytest.approx(twist[0]) and ang == pytest.approx(twist[1])
    raw = pybullet.getBaseVelocity(arm.uid, physicsClientId=arm.client)
    assert lin == pytest.approx(raw[0]) and ang == pytest.approx(raw[1])


def test_joints_in_index_order(arm):
    assert arm.joint_count() == 2
    assert arm.joints() == [Joint(0, "hinge", "revolute", 0.3, "arm_link"),
                            Joint(1, "slide", "prismatic", 0.0, "slider_link")]
    assert all(j.movable for j in arm.joints())
    assert not Joint(0, "weld", "fixed", 0.0, "x").movable


def test_set_joint_and_zero_joints(arm):
    arm.set_joint(0, 0.5, 1.5)
    arm.set_joint(1, -0.05)                            # rate 0 by default
    assert arm.joint_state(0) == pytest.approx((0.5, 1.5))
    assert arm.joint_state(1) == pytest.approx((-0.05, 0.0))
    assert pybullet.getJointState(arm.uid, 0, physicsClientId=arm.client)[:2] == \
        pytest.approx((0.5, 1.5))
    arm.zero_joints()
    assert arm.joint_state(0) == (0.0, 0.0) and arm.joint_state(1) == (0.0, 0.0)


def test_link_frame_is_the_joint_frame_turned_by_the_joint(arm):
    arm.set_joint(0, 0.5, 1.5)
    (pos, orn), (lin, ang) = arm.link_frame(0)
    # The root link at the origin: the hinge frame at (0.2, 0, 0.05), turned 0.5 rad about y.
    assert pos == pytest.approx((0.2, 0.0, 0.05), abs=1e-6)
    assert orn == pytest.approx(about_y(0.5), abs=1e-6)
    assert ang == pytest.approx((0.0, 1.5, 0.0), abs=1e-6)
    state = pybullet.getLinkState(arm.uid, 0, computeLinkVelocity=1, physicsClientId=arm.client)
    assert lin == pytest.approx(state[6]) and ang == pytest.approx(state[7])
    # The slider moves its frame along x.
    arm.set_joint(1, 0.07)
    (pos, orn), _ = arm.link_frame(1)
    assert pos == pytest.approx((-0.13, 0.0, 0.05), abs=1e-6) and orn == pytest.approx(IDENTITY)


def test_link_com(arm):
    # The arm's centre of mass: 0.2 m along its frame's z, which the hinge turns about y.
    assert arm.link_com(0) == pytest.approx((0.2, 0.0, 0.25), abs=1e-6)
    arm.set_joint(0, math.pi / 2)
    assert arm.link_com(0) == pytest.approx((0.4, 0.0, 0.05), abs=1e-6)
    assert arm.link_com(-1) == pytest.approx((0.1, 0.0, 0.0))      # the base: its pose
    arm.set_pose(((1.0, 1.0, 1.0), IDENTITY))
    assert arm.link_com(-1) == pytest.approx((1.0, 1.0, 1.0))


def test_inertials_are_the_files(arm):
    base = arm.inertial(-1)
    assert isinstance(base, Inertial)
    assert base.mass == 2.0 and base.com == ((0.0, 0.0, 0.0), IDENTITY)
    assert base.moments == pytest.approx((0.01, 0.02, 0.03))
    link = arm.inertial(0)
    assert link.mass == 0.5 and link.moments == pytest.approx((0.004, 0.005, 0.006))
    assert link.com[0] == pytest.approx((0.0, 0.0, 0.2)) and link.com[1] == pytest.approx(IDENTITY)
    assert arm.inertial(1).mass == 0.25


def test_set_inertial(arm):
    arm.set_inertial(1, 0.75, (0.002, 0.003, 0.004))
    assert arm.inertial(1).mass == 0.75
    assert arm.inertial(1).moments == pytest.approx((0.002, 0.003, 0.004))
    info = pybullet.getDynamicsInfo(arm.uid, 1, physicsClientId=arm.client)
    assert info[0] == 0.75 and info[2] == pytest.approx((0.002, 0.003, 0.004))
    assert arm.inertial(0).mass == 0.5                 # the other links keep theirs


def test_limit_joint_rate(client, arm):
    """A joint set turning at 5 rad/s turns at no more than the limit after a step (gravity 0,
    the default motors off)."""
    for j in (0, 1):
        pybullet.setJointMotorControl2(arm.uid, j, pybullet.VELOCITY_CONTROL, force=0.0,
                                       physicsClientId=client)
    arm.set_pose(((0.0, 0.0, 0.0), IDENTITY))
    arm.limit_joint_rate(0, 0.7)
    arm.set_joint(0, 0.0, 5.0)
    pybullet.stepSimulation(physicsClientId=client)
    assert abs(arm.joint_state(0)[1]) == pytest.approx(0.7, rel=1e-6)
    arm.limit_joint_rate(0, 100.0)
    arm.set_joint(0, 0.0, 5.0)
    pybullet.stepSimulation(physicsClientId=client)
    assert abs(arm.joint_state(0)[1]) > 4.0            # damping 0.3 slows it a little only


@pytest.mark.parametrize("poison", ["position", "orientation", "velocity", "joint"])
def test_finite_is_false_after_a_nan(arm, poison):
    assert arm.finite()
    cid, uid, nan = arm.client, arm.uid, math.nan
    if poison == "position":
        pybullet.resetBasePositionAndOrientation(uid, (0, nan, 0), IDENTITY, physicsClientId=cid)
    elif poison == "orientation":
        pybullet.resetBasePositionAndOrientation(uid, (0, 0, 0), (nan, 0, 0, 1),
                                                 physicsClientId=cid)
    elif poison == "velocity":
        pybullet.resetBaseVelocity(uid, (0, 0, 0), (0, 0, nan), physicsClientId=cid)
    else:
        pybullet.resetJointState(uid, 1, 0.0, nan, physicsClientId=cid)
    assert not arm.finite()


def test_remove(client, arm):
    other = Body(client, urdf_body(client, ARM))
    assert pybullet.getNumBodies(physicsClientId=client) == 2
    arm.remove()
    assert pybullet.getNumBodies(physicsClientId=client) == 1
    assert pybullet.getBodyUniqueId(0, physicsClientId=client) == other.uid
