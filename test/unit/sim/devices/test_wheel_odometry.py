"""Dead reckoning from wheel angles, as the real TurtleBot3 does it. No ROS master."""
import math

import pytest

from tutorial_turtlebot.sim.devices.wheel_odometry import WheelOdometry

RADIUS = 0.033
SEPARATIONS = (0.160, 0.287)
DT = 1.0 / 30.0


@pytest.fixture(params=SEPARATIONS)
def odom(request):
    return WheelOdometry(request.param, RADIUS)


def drive(odom, left_rim, right_rim, seconds, start=(0.0, 0.0), dt=DT):
    """Feed wheel angles for constant rim speeds (m/s), starting from the angles ``start`` (the
    last ones fed, if any); returns the final wheel angles."""
    left, right = start
    odom.update(left, right, dt)
    for _ in range(round(seconds / dt)):
        left += left_rim * dt / RADIUS
        right += right_rim * dt / RADIUS
        odom.update(left, right, dt)
    return left, right


def pose(odom):
    return odom.x, odom.y, odom.yaw


def test_starts_at_zero(odom):
    """Fresh odometry is at (0, 0, 0) and the first update only records the angles."""
    assert pose(odom) == (0.0, 0.0, 0.0)
    odom.update(12.3, -4.5, DT)                # wheels already turned: not a motion
    assert pose(odom) == (0.0, 0.0, 0.0)
    assert (odom.linear, odom.angular) == (0.0, 0.0)


def test_straight_line(odom):
    """Both wheels at 0.2 m/s for 5 s: 1 m along +x, no turn, twist 0.2 m/s."""
    drive(odom, 0.2, 0.2, 5.0)
    assert pose(odom) == pytest.approx((1.0, 0.0, 0.0), abs=1e-9)
    assert odom.linear == pytest.approx(0.2) and odom.angular == pytest.approx(0.0, abs=1e-12)


def test_backwards(odom):
    """Both wheels backwards: -x."""
    drive(odom, -0.1, -0.1, 2.0)
    assert pose(odom) == pytest.approx((-0.2, 0.0, 0.0), abs=1e-9)
    assert odom.linear == pytest.approx(-0.1)


def test_arc_of_known_radius(odom):
    """Rims (R -/+ sep/2) * w trace a circle of radius R: a quarter turn ends at (R, R, pi/2)."""
    radius, rate = 0.5, 0.4                    # m, rad/s
    half = odom.separation / 2.0
    drive(odom, (radius - half) * rate, (radius + half) * rate, (math.pi / 2) / rate,
          dt=(math.pi / 2) / rate / 300)
    assert pose(odom) == pytest.approx((radius, radius, math.pi / 2), abs=1e-5)
    assert odom.linear == pytest.approx(radius * rate)
    assert odom.angular == pytest.approx(rate)


def test_clockwise_arc(odom):
    """The mirror arc (right wheel slower) curves to -y."""
    radius, rate = 1.0, 0.25
    half = odom.separation / 2.0
    drive(odom, (radius + half) * rate, (radius - half) * rate, (math.pi / 2) / rate,
          dt=(math.pi / 2) / rate / 300)
    assert pose(odom) == pytest.approx((radius, -radius, -math.pi / 2), abs=1e-5)


def test_turn_in_place(odom):
    """Opposite rims: yaw grows by 2*rim/sep per second, the position stays put."""
    rim = 0.04
    drive(odom, -rim, rim, 1.0)
    assert odom.yaw == pytest.approx(2 * rim / odom.separation)
    assert (odom.x, odom.y) == pytest.approx((0.0, 0.0), abs=1e-12)
    assert odom.linear == pytest.approx(0.0, abs=1e-12)
    assert odom.angular == pytest.approx(2 * rim / odom.separation)


def test_yaw_wraps(odom):
    """Three quarter turns counter-clockwise read as -pi/2."""
    rate = 1.0
    rim = rate * odom.separation / 2.0
    drive(odom, -rim, rim, 1.5 * math.pi / rate, dt=1.5 * math.pi / 300)
    assert odom.yaw == pytest.approx(-math.pi / 2, abs=1e-9)
    assert -math.pi <= odom.yaw <= math.pi


def test_square_path_returns_home(odom):
    """Forward 1 m, quarter turn left, four times: back at the origin facing +x."""
    angles = (0.0, 0.0)
    quarter = (math.pi / 2) * odom.separation / 2.0        # rim travel for a quarter turn
    for _ in range(4):
        angles = drive(odom, 0.2, 0.2, 5.0, start=angles)
        angles = drive(odom, -quarter, quarter, 1.0, start=angles)
    assert pose(odom) == pytest.approx((0.0, 0.0, 0.0), abs=1e-9)


def test_reset(odom):
    """reset(): back to the origin with zero twist; the next update only records angles."""
    left, right = drive(odom, 0.1, 0.15, 3.0)
    assert odom.x > 0.1
    odom.reset()
    assert pose(odom) == (0.0, 0.0, 0.0)
    assert (odom.linear, odom.angular) == (0.0, 0.0)
    odom.update(left + 5.0, right + 5.0, DT)    # wheels moved since: not integrated
    assert pose(odom) == (0.0, 0.0, 0.0)
    drive(odom, 0.2, 0.2, 1.0, start=(left + 5.0, right + 5.0))
    assert pose(odom) == pytest.approx((0.2, 0.0, 0.0), abs=1e-9)
