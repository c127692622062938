"""A world file's <gravity> is the physics' from the start (Simulation), as Gazebo applies it,
and the world API reports it."""
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
from tutorial_turtlebot.sim.world.world_control import WorldControl

from unit_helpers import world_file

BOX = ('<model name="box"><pose>0 0 2 0 0 0</pose><link name="l"><collision name="c">'
       '<geometry><box><size>0.2 0.2 0.2</size></box></geometry></collision></link></model>')


def run(tmp_path, gravity):
    """The box's height (m) after 1 s in a world of ``gravity`` (None: none written), and the
    gravity get_physics_properties reports."""
    sim = Simulation(SimConfig(world=world_file(tmp_path, (gravity or "") + BOX),
                               spawn_robot=False))
    for _ in range(400):
        sim.step()
    [(_, pose, _)] = sim.models.get("box").link_states()
    reported = tuple(WorldControl(sim).physics_properties().gravity)
    sim.close()
    return pose[0][2], reported


def test_zero_gravity_floats_a_box(tmp_path):
    """The peer's range test world floats its boxes in 0 0 0."""
    z, reported = run(tmp_path, "<gravity>0 0 0</gravity>")
    assert abs(z - 2.0) < 1e-9 and reported == (0.0, 0.0, 0.0)


def test_moon_gravity_and_the_default(tmp_path):
    moon, reported = run(tmp_path, "<gravity>0 0 -1.6</gravity>")
    earth, default = run(tmp_path, None)
    assert reported == (0.0, 0.0, -1.6) and default == (0.0, 0.0, -9.8)
    # fallen for 1 s (no ground here): 0.8 m on the moon, 4.9 m on the earth
    assert abs((2.0 - moon) - 0.8) < 0.01 and earth < 0.2
