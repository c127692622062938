"""What one URDF may cost (sim/files/limits: MAX_URDF_LINKS, MAX_URDF_DEPTH, MAX_MOVING_JOINTS)
and its joints' <dynamics>: a chain is loaded or refused in one line, quickly, never a freeze;
friction is used and checked, damping checked and simulated. No ROS master."""
import math
import time

import pytest

from tutorial_turtlebot.errors import RequestError
from tutorial_turtlebot.sim.files import limits
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf_text

from unit_helpers import at, run

INERTIAL = ('<inertial><mass value="0.1"/><inertia ixx="0.001" iyy="0.001" izz="0.001" '
            'ixy="0" ixz="0" iyz="0"/></inertial>')


def chain(links, joint="revolute", dynamics=""):
    """A URDF chain of ``links`` links, each 1 cm above the last, joined by ``joint`` joints."""
    text = "".join('<link name="l%d">%s</link>' % (i, INERTIAL) for i in range(links))
    limit = '<limit lower="-1" upper="1" effort="1" velocity="1"/>' if joint == "revolute" else ""
    text += "".join('<joint name="j%d" type="%s"><parent link="l%d"/><child link="l%d"/>'
                    '<origin xyz="0 0 0.01"/><axis xyz="0 0 1"/>%s%s</joint>'
                    % (i, joint, i - 1, i, limit, dynamics) for i in range(1, links))
    return '<robot name="chain">%s</robot>' % text


@pytest.mark.parametrize("links, joint, refusal", [
    (150, "revolute", "149 joints that move: pybullet builds at most 127 in one body"),
    (400, "fixed", None),
    (1000, "fixed", "is 501 joints from root link 'l0': a chain may be at most 500 deep"),
    (1000, "revolute", "is 501 joints from root link 'l0': a chain may be at most 500 deep")])
def test_chains_load_or_are_refused_in_one_line_and_quickly(empty, links, joint, refusal):
    """A 400-link chain froze the sim for good (pybullet's importer printed 80 KB into a pipe
    whose reader needed the GIL), and chains of 150 to 300 links failed inside pybullet."""
    sim, wc = empty
    start = time.monotonic()
    if refusal is None:
        wc.spawn("chain", chain(links, joint), at(1, 1, 0.5), kind="urdf")
        run(sim, 0.05)
        assert "chain" in sim.models
    else:
        with pytest.raises(RequestError) as caught:
            wc.spawn("chain", chain(links, joint), at(1, 1, 0.5), kind="urdf")
        assert refusal in str(caught.value) and "\n" not in str(caught.value)
        assert "chain" not in sim.models
    assert time.monotonic() - start < 2.0


def test_the_longest_chain_pybullet_builds_loads(empty):
    sim, wc = empty
    wc.spawn("chain", chain(limits.MAX_MOVING_JOINTS + 1), at(1, 1, 0.5), kind="urdf")
    assert "chain" in sim.models


def test_too_many_links_are_refused_by_the_reader():
    wide = ('<robot name="wide"><link name="root"/>%s%s</robot>'
            % ("".join('<link name="l%d"/>' % i for i in range(limits.MAX_URDF_LINKS)),
               "".join('<joint name="j%d" type="fixed"><parent link="root"/><child link="l%d"/>'
                       '</joint>' % (i, i) for i in range(limits.MAX_URDF_LINKS))))
    with pytest.raises(Exception, match="has 1001 links, more than the 1000 one URDF may have"):
        read_urdf_text(wide, "wide")


@pytest.mark.parametrize("dynamics, problem", [
    ('<dynamics damping="1e308"/>', "dynamics damping 1e+308 is outside [0, 1e+06]"),
    ('<dynamics friction="-1"/>', "dynamics friction -1 is outside [0, 1e+06]"),
    ('<dynamics damping="nan"/>', "damping='nan' is not a number"),
    ('<dynamics friction="1e999"/>', "friction='1e999' is not a number")])
def test_bad_dynamics_are_refused_in_one_line(dynamics, problem):
    with pytest.raises(Exception) as caught:
        read_urdf_text(chain(3, dynamics=dynamics), "dyn")
    assert problem in str(caught.value) and "\n" not in str(caught.value)


WHEEL = ('<robot name="w"><link name="base"><inertial><mass value="10"/><inertia ixx="1" iyy="1" '
         'izz="1" ixy="0" ixz="0" iyz="0"/></inertial><collision><geometry><box size="0.3 0.3 '
         '0.1"/></geometry></collision></link><link name="disc"><inertial><mass value="1"/>'
         '<inertia ixx="0.02" iyy="0.02" izz="0.02" ixy="0" ixz="0" iyz="0"/></inertial></link>'
         '<joint name="spin" type="continuous"><parent link="base"/><child link="disc"/>'
         '<origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>%s</joint></robot>')


def spin_after(empty, dynamics):
    """The disc's rate (rad/s) 0.5 s after a 0.02 N m effort of 0.5 s spun it up."""
    sim, wc = empty
    wc.spawn("w", WHEEL % dynamics, at(1, 1, 0.05), kind="urdf")
    run(sim, 0.2)
    wc.apply_joint_effort("spin", 0.02, sim.time_ns, int(0.5e9))
    run(sim, 1.0)
    pose, twist, _ = wc.get_model_state("w")
    rate = wc.models.get("w").link_states()[1][2][1][2]
    assert all(abs(v) < 1e3 for v in pose[0])
    return rate


def test_joint_friction_holds_and_damping_adds_no_energy(empty):
    """friction 0.05 N m holds the disc against 0.02 N m (pybullet's joint friction motor);
    damping 0.02 N m s/rad slows it as in Gazebo (a plain URDF is an SDF model: its joints'
    damping is simulated, held so that it adds no energy): 1 - e^-0.5 rad/s after the 0.5 s
    push, e^-0.5 of that 0.5 s later."""
    free = spin_after(empty, "")
    empty[1].delete("w")
    assert 0.3 < free < 0.6                           # 0.02 N m / 0.02 kg m^2 for 0.5 s
    held = spin_after(empty, '<dynamics friction="0.05"/>')
    empty[1].delete("w")
    assert abs(held) < 0.01
    damped = spin_after(empty, '<dynamics damping="0.02"/>')
    assert damped == pytest.approx((1 - math.exp(-0.5)) * math.exp(-0.5), abs=0.02)
