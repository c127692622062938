"""scan_reading on synthetic scans in three angle conventions (Gazebo's TurtleBot3 scan, the real
LDS-01, a Hokuyo-style -pi..pi scan) full of inf, -inf, NaN and 0.0. No ROS master needed.
Units: m, rad (degrees where named)."""
import math

import numpy as np
import pytest

from tutorial_turtlebot.lab.scan_reading import (
    Scan, bearings, closest, handout_readings, index_at, is_valid, more_open_side,
    nearest_in_sector, range_ahead, range_at, report)

from unit_helpers import CONVENTIONS, INF, NAN, f32, make_scan


def blob(center_deg, half_width_deg, distance, fill=INF):
    """World: ``distance`` at bearings within +-half_width of center (degrees), else ``fill``."""
    def world(b):
        off = (math.degrees(b) - center_deg + 180.0) % 360.0 - 180.0
        return distance if abs(off) <= half_width_deg else fill
    return world


def ray_bearing_deg(scan, index):
    return math.degrees(scan.angle_min + index * scan.angle_increment) % 360.0


# --- validity ------------------------------------------------------------------------------------

@pytest.mark.parametrize("r, valid", [
    (1.0, True), (0.12, True), (3.5, True),
    (INF, False), (-INF, False), (NAN, False), (0.0, False),
    (0.05, False), (3.6, False), (65.535, False), (-1.0, False)])
def test_is_valid(r, valid):
    assert is_valid(r, 0.12, 3.5) is valid


def test_zero_is_no_reading_even_when_range_min_is_zero():
    assert not is_valid(0.0, 0.0, 3.5)


# --- which ray looks where -----------------------------------------------------------------------

@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("degrees", [0, 1, 45, 90, 135, 179.6, 180, 270, 300, 359, 359.9, -90])
def test_index_at_picks_the_closest_ray(convention, degrees):
    scan = make_scan(convention, lambda b: 1.0)
    index = index_at(scan, math.radians(degrees))
    rays = bearings(scan)
    error = np.abs((rays - math.radians(degrees) + math.pi) % (2 * math.pi) - math.pi)
    assert error[index] == pytest.approx(error.min(), abs=1e-9)
    assert error[index] <= abs(scan.angle_increment) / 2 + 1e-6


def test_index_at_known_rays():
    lds = make_scan("lds01", lambda b: 1.0)
    assert [index_at(lds, math.radians(d)) for d in (0, 90, 180, 270, 359)] == [0, 90, 180, 270,
                                                                                359]
    gazebo = make_scan("gazebo", lambda b: 1.0)
    # Gazebo's rays are 1.0028 degrees apart: 359 degrees is ray 358, not ray 359 (= 360.0).
    assert [index_at(gazebo, math.radians(d)) for d in (0, 90, 359)] == [0, 90, 358]
    hokuyo = make_scan("hokuyo", lambda b: 1.0)
    assert [index_at(hokuyo, math.radians(d)) for d in (0, 90, -90)] == [360, 540, 180]


def test_index_at_outside_the_field_of_view_is_none():
    # A 270-degree scanner (-135..135 degrees, 0.25 degree steps) does not look behind.
    scan = Scan([1.0] * 1081, f32(math.radians(-135)), f32(math.radians(0.25)), 0.02, 30.0)
    assert index_at(scan, math.radians(100)) == 540 + 400
    assert index_at(scan, math.pi) is None
    assert range_at(scan, math.pi) is None


def test_clockwise_scan():
    # Rays listed clockwise (negative increment), as some drivers do.
    ranges = [1.0 + i / 100.0 for i in range(360)]
    scan = Scan(ranges, 0.0, -math.radians(1.0), 0.12, 3.5)
    assert index_at(scan, math.radians(90)) == 270
    assert range_at(scan, math.radians(-10)) == pytest.approx(1.10)


@pytest.mark.parametrize("scan", [
    Scan([], 0.0, 0.0175, 0.12, 3.5),
    Scan([1.0, 1.0], 0.0, 0.0, 0.12, 3.5),
    Scan([1.0, 1.0], 0.0, NAN, 0.12, 3.5),
    Scan([1.0, 1.0], NAN, 0.0175, 0.12, 3.5),
    Scan([1.0, 1.0], INF, 0.0175, 0.12, 3.5)])
def test_degenerate_scans_give_no_reading(scan):
    assert range_ahead(scan) is None
    assert closest(scan) is None
    assert nearest_in_sector(scan, math.radians(15)) is None
    assert [r for _, _, r in handout_readings(scan)] == [None] * 5
    assert "no reading" in report(scan)


# --- straight ahead ------------------------------------------------------------------------------

@pytest.mark.parametrize("convention", CONVENTIONS)
def test_range_ahead_is_at_bearing_zero_not_the_middle_ray(convention):
    # 1.5 m ahead, 0.3 m behind; the handout's ranges[len/2] would say 0.3 on a TurtleBot3.
    scan = make_scan(convention, lambda b: 1.5 if abs(b) < 0.02 else 0.3 if abs(b) > 3.12
                     else 2.5)
    assert range_ahead(scan) == pytest.approx(1.5)


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("bad", [INF, -INF, NAN, 0.0, 0.05, 3.7, 65.5])
def test_invalid_ahead_is_no_reading(convention, bad):
    scan = make_scan(convention, blob(0, 3, bad, fill=1.0))
    assert range_ahead(scan) is None


# --- the handout's five readings -----------------------------------------------------------------

def test_handout_readings_lds01_are_rays_0_90_180_270_359():
    ranges = [1.0 + i / 1000.0 for i in range(360)]
    ranges[180] = INF
    scan = Scan(ranges, 0.0, f32(math.radians(1.0)), 0.12, 3.5)
    rows = handout_readings(scan)
    assert [(d, i) for d, i, _ in rows] == [(0, 0), (90, 90), (180, 180), (270, 270), (359, 359)]
    readings = [r for _, _, r in rows]
    assert readings[2] is None
    assert readings[:2] + readings[3:] == pytest.approx([1.0, 1.09, 1.27, 1.359])


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_handout_readings_are_bearings_in_every_convention(convention):
    # Each ray reads its own bearing in degrees / 100, so the reading tells where it looks.
    scan = make_scan(convention, lambda b: 0.5 + (math.degrees(b) % 360.0) / 120.0)
    for degrees, index, r in handout_readings(scan):
        assert abs((ray_bearing_deg(scan, index) - degrees + 180) % 360 - 180) < 0.51
        expected = 0.5 + ray_bearing_deg(scan, index) / 120.0
        if expected > 3.5:
            assert r is None
        else:
            assert r == pytest.approx(expected, abs=1e-5)


# --- closest valid reading -----------------------------------------------------------------------

@pytest.mark.parametrize("convention", CONVENTIONS)
def test_closest_skips_invalid_values(convention):
    def world(b):
        d = math.degrees(b)
        if abs(d - 10) < 3:
            return -INF   # too close: no reading
        if abs(d - 60) < 3:
            return 0.0    # LDS no return
        if abs(d + 30) < 3:
            return NAN
        if abs(d - 120) < 2.4:
            return 0.8    # the real closest, on the left behind
        return 2.0
    scan = make_scan(convention, world)
    r, bearing = closest(scan)
    assert r == pytest.approx(0.8)
    assert math.degrees(bearing) == pytest.approx(120, abs=3)


def test_closest_none_when_nothing_valid():
    scan = make_scan("gazebo", lambda b: INF)
    assert closest(scan) is None
    assert "closest: no reading" in report(scan)


# --- front sector --------------------------------------------------------------------------------

@pytest.mark.parametrize("convention", CONVENTIONS)
def test_nearest_in_sector_sees_only_the_sector(convention):
    half = math.radians(15)
    left_in = make_scan(convention, blob(13.5, 0.6, 0.4))
    right_in = make_scan(convention, blob(-13.5, 0.6, 0.4))
    left_out = make_scan(convention, blob(17, 0.6, 0.4))
    right_out = make_scan(convention, blob(-17, 0.6, 0.4))
    assert nearest_in_sector(left_in, half) == pytest.approx(0.4)
    assert nearest_in_sector(right_in, half) == pytest.approx(0.4)
    assert nearest_in_sector(left_out, half) is None
    assert nearest_in_sector(right_out, half) is None


def test_sector_is_symmetric_on_the_lds01():
    # Rays -15 (345) and +15 degrees both belong to a +-15 degree sector despite float32 angles.
    ranges = [2.0] * 360
    ranges[15] = 0.9
    assert nearest_in_sector(make_lds(ranges), math.radians(15)) == pytest.approx(0.9)
    ranges[15] = 2.0
    ranges[345] = 0.8
    assert nearest_in_sector(make_lds(ranges), math.radians(15)) == pytest.approx(0.8)
    ranges[345] = 2.0
    ranges[344] = 0.7
    assert nearest_in_sector(make_lds(ranges), math.radians(15)) == pytest.approx(2.0)


def make_lds(ranges):
    return Scan(ranges, 0.0, f32(math.radians(1.0)), f32(0.12), f32(3.5))


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_nearest_in_sector_ignores_no_reading_but_not_too_close(convention):
    half = math.radians(15)
    for bad in (INF, NAN, 0.0, 4.0):
        assert nearest_in_sector(make_scan(convention, blob(0, 5, bad, fill=3.0)), half) == \
            pytest.approx(3.0)
    # -inf: something closer than range_min, the nearest thing there can be.
    assert nearest_in_sector(make_scan(convention, blob(0, 2, -INF, fill=3.0)), half) == \
        pytest.approx(0.12)
    assert nearest_in_sector(make_scan(convention, lambda b: INF), half) is None


# --- which side is more open ---------------------------------------------------------------------

@pytest.mark.parametrize("convention", CONVENTIONS)
def test_more_open_side(convention):
    wall_right = make_scan(convention, lambda b: 0.4 if b < 0 else 2.0)
    wall_left = make_scan(convention, lambda b: 0.4 if b > 0 else 2.0)
    assert more_open_side(wall_right) == "left"
    assert more_open_side(wall_left) == "right"


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_no_return_counts_as_open_and_junk_as_nothing(convention):
    # Right: a wall at 1 m. Left: no return at all (+inf) except one post at 0.3 m.
    scan = make_scan(convention, lambda b: 1.0 if b < 0 else 0.3 if abs(b - 1.0) < 0.05
                     else INF)
    assert more_open_side(scan) == "left"
    # Left: NaN and 0.0 tell nothing, the few real readings there are close.
    scan = make_scan(convention, lambda b: 1.0 if b < 0 else 0.5 if abs(b - 1.0) < 0.1
                     else NAN if b < 0.8 else 0.0)
    assert more_open_side(scan) == "right"


# --- the laser_data line -------------------------------------------------------------------------

def test_report_line():
    ranges = [2.0] * 360
    ranges[0] = 1.234
    ranges[90] = INF
    ranges[180] = NAN
    ranges[270] = 0.0
    ranges[359] = -INF
    ranges[100] = 0.5
    line = report(make_lds(ranges))
    assert line.startswith("ahead: 1.23 m | 0 deg: 1.23 m  90 deg: no reading  180 deg: no "
                           "reading  270 deg: no reading  359 deg: no reading | ")
    assert line.endswith("closest: 0.50 m at 100 deg")
    assert "\n" not in line
