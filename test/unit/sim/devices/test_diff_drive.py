"""Differential drive as Gazebo's diff-drive plugin does it (doc/turtlebot3.md 2.1); no master."""
import math

import pytest

from tutorial_turtlebot.sim.devices.diff_drive import (SAFE_ANGULAR, SAFE_LINEAR, SNAP_TOLERANCE,
                                                       DiffDriveController, body_twist,
                                                       sanitize_command, wheel_rim_speeds)
from tutorial_turtlebot.robot_models import MODEL_NAMES
from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, urdf_path

SEPARATIONS = (0.160, 0.287)   # burger, waffle / waffle_pi
RADIUS = 0.033
TICK = 1.0 / 30.0              # the plugin's updateRate
ACCEL = 1.0                    # m/s^2 at the rim
EPS = 1e-12


def rims(controller, dt=TICK):
    """One control tick; the (left, right) rim speeds in m/s it commands."""
    left, right = controller.update(dt)
    return left * controller.radius, right * controller.radius


# --- kinematics ---------------------------------------------------------------------------------

def test_model_separations_are_the_plugin_values():
    """The controller geometry comes from the URDFs' diff-drive plugins: 0.160 burger, 0.287
    the waffles, wheel radius 0.033 for all."""
    drives = {m: read_urdf(urdf_path(m)).plugins.drive for m in MODEL_NAMES}
    assert drives["burger"].wheel_separation == 0.160
    assert drives["waffle"].wheel_separation == drives["waffle_pi"].wheel_separation == 0.287
    assert all(d.wheel_radius == pytest.approx(RADIUS) for d in drives.values())


@pytest.mark.parametrize("separation", SEPARATIONS)
def test_rim_speeds_are_v_minus_plus_half_w_sep(separation):
    """Left = v - w*sep/2, right = v + w*sep/2: a positive yaw rate speeds up the right wheel."""
    left, right = wheel_rim_speeds(0.2, 0.5, separation)
    assert left == pytest.approx(0.2 - 0.25 * separation)
    assert right == pytest.approx(0.2 + 0.25 * separation)
    assert wheel_rim_speeds(0.1, 0.0, separation) == (0.1, 0.1)
    left, right = wheel_rim_speeds(0.0, 1.0, separation)
    assert left == pytest.approx(-separation / 2) and right == pytest.approx(separation / 2)


@pytest.mark.parametrize("separation", SEPARATIONS)
@pytest.mark.parametrize("v, w", [(0.0, 0.0), (0.22, 0.0), (0.0, 2.84), (-0.1, 1.82),
                                  (0.26, -1.0), (-0.05, -0.3)])
def test_body_twist_round_trip(separation, v, w):
    """body_twist undoes wheel_rim_speeds."""
    assert body_twist(*wheel_rim_speeds(v, w, separation), separation) == pytest.approx((v, w))


@pytest.mark.parametrize("separation", SEPARATIONS)
def test_body_twist_of_known_rim_speeds(separation):
    """Equal rims: straight; opposite rims: turn in place at 2*rim/sep."""
    assert body_twist(0.1, 0.1, separation) == pytest.approx((0.1, 0.0))
    assert body_twist(-0.05, 0.05, separation) == pytest.approx((0.0, 0.1 / separation))


# --- sanitize_command --------------------------------------------------------------------------

@pytest.mark.parametrize("linear, angular", [(math.nan, 0.0), (0.0, math.nan), (math.inf, 0.0),
                                             (0.0, -math.inf), (math.nan, math.inf)])
def test_sanitize_rejects_non_finite(linear, angular):
    """NaN or infinite fields raise ValueError."""
    with pytest.raises(ValueError, match="NaN or infinite"):
        sanitize_command(linear, angular, 0.22, 2.84)


def test_sanitize_passes_values_within_limits():
    """In range (limits included): unchanged, no problems."""
    assert sanitize_command(0.1, -1.0, 0.22, 2.84) == (0.1, -1.0, [])
    assert sanitize_command(-0.22, 2.84, 0.22, 2.84) == (-0.22, 2.84, [])


def test_sanitize_clamps_linear_only():
    """Too fast forward or backward: clamped with its sign kept, named in problems."""
    linear, angular, problems = sanitize_command(0.5, 1.0, 0.22, 2.84)
    assert (linear, angular) == (0.22, 1.0)
    assert len(problems) == 1 and "linear.x" in problems[0]
    linear, _, problems = sanitize_command(-3.0, 0.0, 0.26, 1.82)
    assert linear == -0.26
    assert len(problems) == 1 and "linear.x" in problems[0]


def test_sanitize_clamps_angular_only():
    """Too fast a turn: clamped with its sign kept, named in problems."""
    linear, angular, problems = sanitize_command(0.1, -5.0, 0.22, 2.84)
    assert (linear, angular) == (0.1, -2.84)
    assert len(problems) == 1 and "angular.z" in problems[0]


def test_sanitize_lists_both_problems():
    """Both out of range: both clamped, both listed."""
    linear, angular, problems = sanitize_command(1e9, 1e9, SAFE_LINEAR, SAFE_ANGULAR)
    assert (linear, angular) == (SAFE_LINEAR, SAFE_ANGULAR)
    assert len(problems) == 2
    assert any("linear.x" in p for p in problems) and any("angular.z" in p for p in problems)


# --- the controller ramp -----------------------------------------------------------------------

@pytest.fixture(params=SEPARATIONS)
def controller(request):
    return DiffDriveController(request.param, RADIUS, ACCEL)


def test_starts_stopped(controller):
    """Before any command the wheels are held at 0."""
    assert controller.update(TICK) == (0.0, 0.0)


def test_ramp_limits_each_tick(controller):
    """At 1 m/s^2 and 30 Hz a rim speed moves by at most 1/30 m/s per tick, forward and back.

    The commands change both wheels by the same amount, so neither reaches its target first
    (see test_either_wheel_near_its_target_snaps_both for what happens then)."""
    previous = (0.0, 0.0)
    for command in ((0.22, 0.0), (-0.22, 0.0), (0.0, 0.0), (0.0, 1.5), (0.0, -1.8),
                    (0.0, 0.0)):
        controller.set_command(*command)
        for _ in range(40):
            now = rims(controller)
            for a, b in zip(previous, now):
                assert abs(b - a) <= ACCEL * TICK + EPS
            previous = now


def test_ramp_reaches_the_target(controller):
    """0 -> 0.2 m/s takes 6 ticks of 1/30 m/s, then stays there (no command timeout)."""
    controller.set_command(0.2, 0.0)
    speeds = [rims(controller)[0] for _ in range(6)]
    assert speeds == pytest.approx([i / 30.0 for i in range(1, 7)])
    for _ in range(300):
        assert rims(controller) == pytest.approx((0.2, 0.2), abs=EPS)


def test_ramp_reaches_a_turn_target(controller):
    """A combined command ends at its exact rim speeds, v -/+ w*sep/2."""
    controller.set_command(0.15, 1.2)
    for _ in range(30):
        last = rims(controller)
    assert last == pytest.approx(wheel_rim_speeds(0.15, 1.2, controller.separation), abs=EPS)


def test_snaps_within_tolerance(controller):
    """Within 0.01 m/s of the target the rim jumps to it; further away it ramps."""
    slow = DiffDriveController(controller.separation, RADIUS, 0.03)   # 0.001 m/s per tick
    slow.set_command(0.9 * SNAP_TOLERANCE, 0.0)
    assert rims(slow) == pytest.approx((0.009, 0.009), abs=EPS)
    slow.reset()
    slow.set_command(1.1 * SNAP_TOLERANCE, 0.0)
    assert rims(slow) == pytest.approx((0.001, 0.001), abs=EPS)


def test_either_wheel_near_its_target_snaps_both(controller):
    """Gazebo's rule: once either wheel is within 0.01 m/s, both jump to their targets."""
    controller.set_command(0.2, 0.0)
    for _ in range(6):
        rims(controller)
    sep = controller.separation
    left, right = 0.205, 0.5           # left is close, right is 0.3 m/s away
    controller.set_command(*body_twist(left, right, sep))
    assert rims(controller) == pytest.approx((left, right), abs=1e-9)


def test_no_snap_when_both_are_far(controller):
    """Both wheels further than 0.01 m/s away: one ramp step only."""
    controller.set_command(0.2, 0.0)
    assert rims(controller) == pytest.approx((TICK, TICK))


def test_wheel_rad_per_s_is_rim_over_radius(controller):
    """update() returns joint velocities in rad/s: rim speed / 0.033."""
    unlimited = DiffDriveController(controller.separation, RADIUS, 0.0)
    unlimited.set_command(0.2, 0.5)
    left, right = wheel_rim_speeds(0.2, 0.5, controller.separation)
    assert unlimited.update(TICK) == pytest.approx((left / RADIUS, right / RADIUS))
    controller.set_command(0.2, 0.0)
    assert controller.update(TICK) == pytest.approx((TICK / RADIUS, TICK / RADIUS))


def test_reset_zeroes_command_and_speed(controller):
    """reset(): wheels at 0 at once and the old command forgotten."""
    controller.set_command(0.2, 1.0)
    for _ in range(10):
        rims(controller)
    controller.reset()
    for _ in range(5):
        assert controller.update(TICK) == (0.0, 0.0)
