"""Actors moved along their scripts in sim time (sim/world/actors.py), as Gazebo 11's Actor.cc
moves them: the spline between waypoints, the 30 Hz frames, delay, loop, auto_start, reset; in
the simulation, seen by the camera, not by the laser, listed as models. No ROS master."""
import math
import os

import numpy as np
import pytest

from tutorial_turtlebot.sim.engine import physics as physics_module
from tutorial_turtlebot.sim.files.world_types import Actor, Trajectory, Waypoint
from tutorial_turtlebot.sim.kinematics import yaw_from_quat
from tutorial_turtlebot.sim.world.actors import FRAME_PERIOD_S, ActorMotion, PoseCurve
from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation

from texture_fixtures import pixel
import unit_paths

FIXTURES = unit_paths.FIXTURES
ACTORS = os.path.join(FIXTURES, "worlds", "actors.world")
STEP_NS = 2_500_000


def curve(points, tension=0.0):
    """A PoseCurve through (time, x, yaw) waypoints on the x axis."""
    return PoseCurve(Trajectory(0, "walk", tension, tuple(
        Waypoint(t, (x, 0.0, 0.0, 0.0, 0.0, yaw)) for t, x, yaw in points)))


# --- the curve between waypoints: gz::math::Spline and RotationSpline ------------------------

def test_between_two_waypoints_the_position_is_catmull_rom_hermite():
    """Open ends: both tangents are half the step times (1 - tension). At a quarter of the way
    the Hermite basis gives 0.15625 of the step plus 0.09375 of a tangent: 0.203125 of the step
    at tension 0; with tension 1 (no tangents) 0.15625."""
    assert curve([(0, 0.0, 0.0), (4, 4.0, 0.0)]).at(1.0)[0][0] == pytest.approx(4 * 0.203125)
    assert curve([(0, 0.0, 0.0), (4, 4.0, 0.0)], 1.0).at(1.0)[0][0] == pytest.approx(4 * 0.15625)
    assert curve([(0, 0.0, 0.0), (4, 4.0, 0.0)]).at(2.0)[0][0] == pytest.approx(2.0)


def test_between_two_waypoints_the_heading_is_squad_with_shoemake_tangents():
    """Yaw 0 to 1 rad: the tangents turn 0.25 rad beyond each end, so a quarter of the way
    the heading is 0.25 + 0.375 * (0.125 - 0.25) = 0.203125 rad, halfway 0.5 rad."""
    c = curve([(0, 0.0, 0.0), (1, 0.0, 1.0)])
    assert yaw_from_quat(c.at(0.25)[1]) == pytest.approx(0.203125, abs=1e-9)
    assert yaw_from_quat(c.at(0.5)[1]) == pytest.approx(0.5, abs=1e-9)


def test_at_a_waypoint_time_the_pose_is_the_waypoint_and_the_ends_hold():
    c = curve([(0, 0.0, 0.0), (1, 1.0, 0.5), (3, 5.0, 1.0)])
    for t, x, yaw in [(0, 0.0, 0.0), (1, 1.0, 0.5), (3, 5.0, 1.0), (-2, 0.0, 0.0), (9, 5.0, 1.0)]:
        (px, py, pz), q = c.at(t)
        assert (px, py, pz) == pytest.approx((x, 0.0, 0.0))
        assert yaw_from_quat(q) == pytest.approx(yaw)


def test_a_closed_path_takes_its_end_tangents_across_the_join():
    """First point == last point: the tangent at both is half of (second - second to last), as
    gz::math::Spline makes a closed curve smooth through its start."""
    square = [(0, 0.0, 0.0), (1, 1.0, 0.0), (2, 2.0, 0.0), (3, 0.0, 0.0)]
    c = curve(square)
    assert c.tangents[0] == pytest.approx((0.5 * (1.0 - 2.0), 0.0, 0.0))
    assert c.tangents[-1] == c.tangents[0]
    assert c.tangents[1] == pytest.approx((1.0, 0.0, 0.0))     # 0.5 * (2 - 0)


# --- the script in sim time: Actor::Update -----------------------------------------------------

class FakeModel:
    """A WorldModel stand-in that keeps the poses set."""

    def __init__(self):
        self.parts = [object()]
        self.poses = []

    def set_state(self, pose, twist):
        self.poses.append(pose)


def actor(points=((0, 0.0), (2, 2.0)), **script):
    return Actor("a", (0.0, 0.0, 0.0, 0.0, 0.0, 0.0), (Trajectory(0, "walk", 0.0, tuple(
        Waypoint(t, (x, 0.0, 0.0, 0.0, 0.0, 0.0)) for t, x in points)),), **script)


def play(motion, seconds, start_ns=0):
    """Step ``motion`` as Simulation.step does, 2.5 ms a step; (time s, x) of each frame."""
    frames = []
    for k in range(1, int(round(seconds * 1e9 / STEP_NS)) + 1):
        now = start_ns + k * STEP_NS
        pose = motion.update(now)
        if pose is not None:
            frames.append((now / 1e9, pose[0][0]))
    return frames


def test_frames_come_at_most_every_thirtieth_of_a_second():
    model = FakeModel()
    frames = play(ActorMotion(actor(), model), 1.0)
    times = [t for t, _ in frames]
    assert times[0] == pytest.approx(0.035)          # the first step 1/30 s after the start
    assert all(b - a >= FRAME_PERIOD_S - 1e-12 for a, b in zip(times, times[1:]))
    assert len(frames) == 28                         # 35 ms apart at a 2.5 ms step
    assert all(x == pytest.approx(curve([(0, 0.0, 0), (2, 2.0, 0)]).at(t)[0][0])
               for t, x in frames)


def test_the_delay_is_waited_at_the_start_and_before_each_loop():
    model = FakeModel()
    frames = play(ActorMotion(actor(delay_start=1.0), model), 4.5)
    first = frames[0][0]
    assert 1.0 <= first < 1.0 + FRAME_PERIOD_S + 0.003
    # the script ends at 3 s: the next frame starts it again, then it waits 1 s once more
    times = [t for t, _ in frames]
    restart = next(t for t, x in frames if t > 3.0)
    after = [t for t in times if t > restart]
    assert after[0] - restart >= 1.0


def test_a_script_that_does_not_loop_stops_at_its_last_frame():
    model = FakeModel()
    motion = ActorMotion(actor(loop=False), model)
    frames = play(motion, 3.0)
    assert frames[-1][0] < 2.0 + FRAME_PERIOD_S and not motion.active
    assert frames[-1][1] == pytest.approx(2.0, abs=0.05)


def test_a_script_that_does_not_auto_start_never_moves():
    model = FakeModel()
    assert play(ActorMotion(actor(auto_start=False), model), 2.0) == [] and model.poses == []


def test_a_restart_plays_the_script_from_its_beginning():
    model = FakeModel()
    motion = ActorMotion(actor(), model)
    play(motion, 1.5)
    motion.restart(int(1.5e9))
    frames = play(motion, 0.5, start_ns=int(1.5e9))
    assert frames[0][1] == pytest.approx(curve([(0, 0.0, 0), (2, 2.0, 0)]).at(0.035)[0][0])


# --- in the simulation ------------------------------------------------------------------------

@pytest.fixture
def sim(monkeypatch):
    """The fixture world of actors with a Waffle Pi at (-2, -2) facing +x, towards "walker"
    (at x 0 at first), its camera drawn by TinyRenderer."""
    monkeypatch.setenv("GAZEBO_MODEL_PATH", os.path.join(FIXTURES, "gazebo_models"))
    monkeypatch.setattr(physics_module, "enable_egl", lambda cid: False)
    simulation = Simulation(SimConfig(model="waffle_pi", world=ACTORS, x=-2.0, y=-2.0, yaw=0.0))
    yield simulation
    simulation.close()


def run(sim, seconds):
    for _ in range(int(round(seconds / sim.config.time_step))):
        sim.step()


def coat(sim, rgb, point):
    """Whether the image shows the walker's coat (0.1 0.6 0.5: green and blue over red) at
    world ``point``."""
    col, row = pixel(sim, point)
    r, g, b = np.median(rgb[row - 2:row + 3, col - 2:col + 3].reshape(-1, 3), axis=0)
    return g > r + 40 and b > r + 30


def test_actors_are_listed_after_the_models_and_move_in_sim_time(sim):
    assert sim.models.names() == ["ground_plane", "curtain_rail", "wall", "walker", "pacer",
                                  "turtlebot3_waffle_pi"]
    walker = sim.models.get("walker")
    run(sim, 2.0)
    (x, y, _), q = walker.pose()
    frame_time = sim.actors[0].previous_frame
    expected = sim.actors[0].curves[0].at(frame_time)
    assert (x, y) == pytest.approx(expected[0][:2]) and 0.9 < x < 1.1
    assert walker.twist() == ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0))
    assert dict((n, p) for n, p, _ in walker.link_states())["walker::walker_pose"][0][0] \
        == pytest.approx(x)


def test_the_camera_sees_the_actor_where_its_script_puts_it(sim):
    """At first the walker's face is at x -0.2 straight ahead; at 7 s it walks north along x 2
    (turned: its face 0.125 m before x 2), left of where it was."""
    rgb, _ = sim.robot.camera_image()
    assert coat(sim, rgb, (-0.2, -2.0, 0.5))
    run(sim, 7.0)
    rgb, _ = sim.robot.camera_image()
    (x, y, _), _ = sim.models.get("walker").pose()
    assert x == pytest.approx(2.0, abs=0.05) and -1.6 < y < -0.4
    assert coat(sim, rgb, (x - 0.125, y, 0.5)) and not coat(sim, rgb, (-0.2, -2.0, 0.5))


def test_the_laser_passes_through_an_actor_as_gazebos_cpu_ray_does(sim):
    """The walker stands 1.8 m ahead of the laser (its range is 3.5 m), the wall 5.9 m: the
    ray straight ahead returns nothing."""
    scan = sim.robot.scan()
    assert math.isinf(scan[0]) or scan[0] > 3.5


def test_reset_world_starts_every_script_again(sim):
    run(sim, 3.0)
    sim.reset_world()
    assert sim.models.get("walker").pose()[0][:2] == pytest.approx((0.0, -2.0))
    start = sim.time_ns
    run(sim, 1.0)
    frame = sim.actors[0].previous_frame - start / 1e9
    assert sim.models.get("walker").pose()[0][0] == pytest.approx(
        sim.actors[0].curves[0].at(frame)[0][0])
    assert sim.models.get("pacer").pose()[0][:2] == pytest.approx((-1.0, 1.0))   # waiting 1 s


def test_advance_moves_the_actors_as_step_does(monkeypatch):
    monkeypatch.setenv("GAZEBO_MODEL_PATH", os.path.join(FIXTURES, "gazebo_models"))
    sims = [Simulation(SimConfig(world=ACTORS, x=-2.0, y=-2.0)) for _ in range(2)]
    try:
        run(sims[0], 1.5)
        sims[1].advance(int(round(1.5 / sims[1].config.time_step)))
        assert sims[0].models.get("walker").pose() == sims[1].models.get("walker").pose()
    finally:
        for s in sims:
            s.close()
