"""Reading a planar laser scan the right way for a TurtleBot3 (doc/turtlebot3.md 2.2 and 6).

A scan is anything with the LaserScan fields ``ranges`` (m), ``angle_min`` and
``angle_increment`` (rad), ``range_min`` and ``range_max`` (m): a sensor_msgs/LaserScan or a
:class:`Scan`. Bearings are in the scan's frame (``base_scan``), REP 103: radians,
counter-clockwise from +x (straight ahead), so +pi/2 is left and -pi/2 right.

Ray i points at ``angle_min + i * angle_increment``. That covers Gazebo's TurtleBot3 scan
(0 to 6.28319 in 359 steps, so ray 359 repeats ray 0), the real LDS-01 (exact 1 degree steps)
and a Hokuyo-style -pi to pi scan alike: nothing here assumes which ray is "ahead".

A reading is valid when it is finite and within [range_min, range_max]. inf, -inf, NaN, 0.0
(the LDS-01's "no return") and values outside the limits are "no reading" (None here).
"""
import math
from typing import List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

# The five bearings the handout prints (msg.ranges[0], [90], [180], [270], [359]), in degrees.
HANDOUT_DEGREES = (0, 90, 180, 270, 359)

# Slack when comparing bearings, rad: scan angles arrive as float32 (about 1e-7 rad of error).
ANGLE_TOLERANCE = 1e-6


class Scan(NamedTuple):
    """The fields of a sensor_msgs/LaserScan that the lab's logic reads."""

    ranges: Sequence[float]   # m, one per ray
    angle_min: float          # rad, bearing of ray 0
    angle_increment: float    # rad between consecutive rays (negative: clockwise)
    range_min: float          # m
    range_max: float          # m


def wrap_angle(angle):
    """Angle(s) in rad wrapped to [-pi, pi); NaN where not finite."""
    with np.errstate(invalid="ignore"):
        return (np.asarray(angle, dtype=float) + math.pi) % (2.0 * math.pi) - math.pi


def is_valid(r: float, range_min: float, range_max: float) -> bool:
    """True when ``r`` (m) is a real measurement: finite, above 0 and within the scan's limits."""
    return math.isfinite(r) and r > 0.0 and range_min <= r <= range_max


def ranges_of(scan) -> np.ndarray:
    """The scan's ranges as a float array (m), as published (inf, NaN and 0.0 included)."""
    return np.asarray(scan.ranges, dtype=float).reshape(-1)


def valid_mask(scan) -> np.ndarray:
    """One bool per ray: True where the reading is valid (see :func:`is_valid`)."""
    ranges = ranges_of(scan)
    with np.errstate(invalid="ignore"):
        return (np.isfinite(ranges) & (ranges > 0.0)
                & (ranges >= scan.range_min) & (ranges <= scan.range_max))


def bearings(scan) -> np.ndarray:
    """Bearing of every ray in rad, wrapped to [-pi, pi); all NaN when the scan's angles make
    no sense (a zero or non-finite increment, a non-finite angle_min)."""
    count = len(ranges_of(scan))
    if not (math.isfinite(scan.angle_increment) and scan.angle_increment != 0.0):
        return np.full(count, np.nan)
    return wrap_angle(scan.angle_min + scan.angle_increment * np.arange(count))


def index_at(scan, bearing: float) -> Optional[int]:
    """Index of the ray closest to ``bearing`` (rad), or None when the scan does not look that
    way (no rays, a zero or non-finite increment, or a bearing outside its field of view)."""
    rays = bearings(scan)
    if rays.size == 0 or not math.isfinite(bearing):
        return None
    off = np.abs(wrap_angle(rays - bearing))
    best = int(np.argmin(off))
    if not off[best] <= abs(scan.angle_increment) / 2.0 + ANGLE_TOLERANCE:  # NaN fails too
        return None
    return best


def reading(scan, index: Optional[int]) -> Optional[float]:
    """The range (m) of ray ``index`` if it is valid, else None."""
    if index is None:
        return None
    r = float(ranges_of(scan)[index])
    return r if is_valid(r, scan.range_min, scan.range_max) else None


def range_at(scan, bearing: float) -> Optional[float]:
    """The valid range (m) of the ray closest to ``bearing`` (rad), else None."""
    return reading(scan, index_at(scan, bearing))


def range_ahead(scan) -> Optional[float]:
    """The valid range (m) straight ahead (bearing 0), else None."""
    return range_at(scan, 0.0)


def handout_readings(scan) -> List[Tuple[int, Optional[int], Optional[float]]]:
    """(degrees, ray index or None, valid range in m or None) at the handout's five bearings.

    These are bearings, not indices: on Gazebo's scan 359 degrees is ray 358, since its rays are
    1.0028 degrees apart; on the real LDS-01 it is ray 359.
    """
    rows = []
    for degrees in HANDOUT_DEGREES:
        index = index_at(scan, math.radians(degrees))
        rows.append((degrees, index, reading(scan, index)))
    return rows


def closest(scan) -> Optional[Tuple[float, float]]:
    """(range m, bearing rad in [-pi, pi)) of the closest valid reading, or None if none (or
    the scan's angles are not numbers)."""
    rays = bearings(scan)
    mask = valid_mask(scan) & np.isfinite(rays)
    if not mask.any():
        return None
    ranges = np.where(mask, ranges_of(scan), np.inf)
    best = int(np.argmin(ranges))
    return float(ranges[best]), float(rays[best])


def in_sector(scan, half_angle: float) -> np.ndarray:
    """One bool per ray: True where the ray's bearing is within +-``half_angle`` rad of ahead."""
    return np.abs(bearings(scan)) <= half_angle + ANGLE_TOLERANCE


def obstacle_ranges(scan) -> np.ndarray:
    """What each ray says about obstacles, m: a valid reading as is, -inf (REP 117: something
    too close to measure) as range_min, +inf (no return within range_max) as +inf, and NaN
    where the ray tells nothing (NaN, 0.0 and other out-of-range values)."""
    ranges = ranges_of(scan)
    valid = valid_mask(scan)
    out = np.full(ranges.shape, np.nan)
    out[valid] = ranges[valid]
    out[ranges == -np.inf] = scan.range_min
    out[ranges == np.inf] = np.inf
    return out


def nearest_in_sector(scan, half_angle: float) -> Optional[float]:
    """The nearest obstacle (m) among rays within +-``half_angle`` rad of ahead, or None.

    That is the nearest valid reading there, except that a -inf counts as range_min: it means
    something is closer than the sensor can measure, the last thing to drive into.
    """
    near = obstacle_ranges(scan)[in_sector(scan, half_angle)]
    near = near[np.isfinite(near)]
    return float(near.min()) if near.size else None


def openness(scan, low: float, high: float) -> Optional[float]:
    """Mean free distance (m) over rays with bearings in [low, high] rad (low <= high, both in
    [-pi, pi]); a ray with no return counts as range_max. None when no ray there tells anything."""
    free = np.minimum(obstacle_ranges(scan), scan.range_max)
    rays = bearings(scan)
    mask = (rays >= low - ANGLE_TOLERANCE) & (rays <= high + ANGLE_TOLERANCE) & ~np.isnan(free)
    if not mask.any():
        return None
    return float(free[mask].mean())


def more_open_side(scan) -> str:
    """'left' or 'right': the side (the quarter circles 0 to +90 and 0 to -90 degrees) with the
    larger mean free distance. Left on a tie, and where neither side tells anything."""
    left = openness(scan, 0.0, math.pi / 2.0)
    right = openness(scan, -math.pi / 2.0, 0.0)
    if right is not None and (left is None or right > left):
        return "right"
    return "left"


def _degrees(bearing: float) -> int:
    """A bearing in rad as whole degrees counter-clockwise in [0, 360), as the handout counts."""
    return round(math.degrees(bearing)) % 360


def _metres(r: Optional[float]) -> str:
    return "no reading" if r is None else "%.2f m" % r


def report(scan) -> str:
    """One line for laser_data: the range ahead, the handout's five readings and the closest
    valid reading with its bearing (degrees counter-clockwise from ahead: 90 left, 270 right)."""
    five = "  ".join("%d deg: %s" % (degrees, _metres(r))
                     for degrees, _, r in handout_readings(scan))
    near = closest(scan)
    if near is None:
        nearest = "closest: no reading"
    else:
        nearest = "closest: %.2f m at %d deg" % (near[0], _degrees(near[1]))
    return "ahead: %s | %s | %s" % (_metres(range_ahead(scan)), five, nearest)
