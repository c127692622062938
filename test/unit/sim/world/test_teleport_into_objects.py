"""set_model_state into or onto a thin object (world_control): the robot is put exactly where
asked, as Gazebo puts it, and the contacts push it out; it never ends under the floor, on a
box ground or on a floor that is a mesh of no thickness. Real pybullet, no ROS master."""
import math

import pytest

from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

AT_REST = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))


def box_obj(path, sx, sy, sz):
    """A closed box mesh, its bottom at z 0 (m)."""
    corners = [(x * sx / 2, y * sy / 2, (z + 1) * sz / 2)
               for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    quads = [(1, 3, 7, 5), (2, 6, 8, 4), (1, 5, 6, 2), (3, 4, 8, 7), (1, 2, 4, 3), (5, 7, 8, 6)]
    with open(path, "w") as f:
        f.write("".join("v %g %g %g\n" % c for c in corners))
        f.write("".join("f %d %d %d\nf %d %d %d\n" % (a, b, c, a, c, d) for a, b, c, d in quads))


def static_mesh(name, path, pose):
    geometry = "<geometry><mesh><uri>file://%s</uri></mesh></geometry>" % path
    return ("<model name='%s'><static>true</static><pose>%s</pose><link name='l'>"
            "<collision name='c'>%s</collision><visual name='v'>%s</visual></link></model>"
            % (name, pose, geometry, geometry))


@pytest.mark.parametrize("floor", ["box ground", "mesh floor"])
def test_a_robot_teleported_into_a_thin_object_never_ends_under_the_floor(tmp_path, floor):
    box_obj(str(tmp_path / "frame.obj"), 0.3, 0.02, 0.24)   # a picture frame standing
    box_obj(str(tmp_path / "flat.obj"), 0.3, 0.24, 0.02)    # and one lying on the floor
    (tmp_path / "floor.obj").write_text("v -5 -5 0\nv 5 -5 0\nv 5 5 0\nv -5 5 0\n"
                                        "f 1 2 3\nf 1 3 4\n")
    ground = ("<include><uri>model://ground_plane</uri></include>" if floor == "box ground"
              else static_mesh("floor", tmp_path / "floor.obj", "0 0 0 0 0 0"))
    world = tmp_path / "frames.world"
    world.write_text("<sdf version='1.6'><world name='w'>%s%s%s</world></sdf>"
                     % (ground, static_mesh("frame", tmp_path / "frame.obj", "0 0 0 0 0 0"),
                        static_mesh("flat", tmp_path / "flat.obj", "0 1 0 0 0 0")))
    sim = Simulation(SimConfig(world=str(world), x=-1.0, y=0.0))
    try:
        wc = WorldControl(sim)
        name = sim.robot_name
        for x, y in ((0.0, 0.0), (0.0, 1.0)):
            for z in (0.0, 0.1):
                for yaw in (0.0, 1.0):
                    wc.set_model_state(name, ((x, y, z), (0.0, 0.0, math.sin(yaw / 2),
                                                          math.cos(yaw / 2))), AT_REST)
                    lowest = math.inf
                    for _ in range(800):      # 2 s
                        sim.step()
                        lowest = min(lowest, wc.get_model_state(name)[0][0][2])
                    final = wc.get_model_state(name)[0][0][2]
                    where = "into (%g, %g, %g) yaw %g" % (x, y, z, yaw)
                    assert lowest > -0.06, "%s: sank to z %.3f" % (where, lowest)
                    assert final > -0.005, "%s: rests at z %.3f" % (where, final)
    finally:
        sim.close()
