"""Body's joint settings (engine/bodies.py: set_joint_properties' damping, stops and motor):
the damping simulated held to what one longest step can take out, what was set read back,
put back as built, and forgotten with the body. No ROS master."""
import pytest

from tutorial_turtlebot.sim.engine.bodies import NO_STOP, Body
from unit_helpers import urdf_body

# A base too heavy to move (1000 kg, 1000 kg m^2) with a rod on a revolute joint about y:
# 0.5 kg, its centre 0.2 m up the rod, 0.005 kg m^2 about it, so 0.005 + 0.5 x 0.2^2 =
# 0.025 kg m^2 about the joint; a continuous joint about z turns a 0.1 kg cube beside it.
ROD = """<robot name="rod"><link name="base"><inertial><mass value="1000"/>
<inertia ixx="1000" iyy="1000" izz="1000" ixy="0" ixz="0" iyz="0"/></inertial></link>
<link name="rod"><inertial><origin xyz="0 0 0.2"/><mass value="0.5"/>
<inertia ixx="0.005" iyy="0.005" izz="0.0001" ixy="0" ixz="0" iyz="0"/></inertial></link>
<joint name="pivot" type="revolute"><parent link="base"/><child link="rod"/>
<axis xyz="0 1 0"/><limit lower="-1" upper="2" effort="10" velocity="5"/>
<dynamics damping="0.3" friction="0.05"/></joint>
<link name="cube"><inertial><mass value="0.1"/>
<inertia ixx="0.0001" iyy="0.0001" izz="0.0001" ixy="0" ixz="0" iyz="0"/></inertial></link>
<joint name="spin" type="continuous"><parent link="base"/><child link="cube"/>
<origin xyz="1 0 0"/><axis xyz="0 0 1"/></joint></robot>"""


@pytest.fixture
def rod(client):
    return Body(client, urdf_body(client, ROD))


def test_as_built_the_joints_read_their_urdf(rod):
    assert rod.joint_damping(0) == pytest.approx(0.3)
    assert rod.joint_stops(0) == (-1.0, 2.0)
    assert rod.joint_motor(0) == (0.0, pytest.approx(0.05))
    assert rod.joint_stops(1) == (-NO_STOP, NO_STOP)      # continuous: no stops


def test_the_damping_simulated_is_what_stops_the_joint_in_the_longest_step(rod):
    assert rod.set_joint_damping(0, 1.0, 0.01) == 1.0
    # 1 / (0.01 s x 1 / 0.025 kg m^2) = 2.5 N m s/rad stops the rod in one 0.01 s step
    assert rod.set_joint_damping(0, 100.0, 0.01) == pytest.approx(2.5, rel=1e-3)
    assert rod.joint_damping(0) == 100.0                   # what was asked is read back


def test_what_was_set_is_put_back_as_built_and_forgotten_with_the_body(rod, client):
    rod.set_joint_damping(0, 0.7, 0.01)
    rod.set_joint_stops(0, -0.2, 0.4)
    rod.set_joint_motor(1, 1.5, 2.0)
    assert (rod.joint_damping(0), rod.joint_stops(0), rod.joint_motor(1)) == (
        0.7, (-0.2, 0.4), (1.5, 2.0))
    rod.restore_joints()
    assert client.joints_set == {}
    assert rod.joint_stops(0) == (-1.0, 2.0) and rod.joint_motor(1) == (0.0, 0.0)
    for _ in range(200):                                   # the cube coasts: no motor left
        client.stepSimulation()
    assert rod.joint_state(1)[1] == pytest.approx(0.0, abs=1e-6)
    rod.set_joint_stops(1, -1.0, 1.0)
    rod.remove()
    assert client.joints_set == {}
