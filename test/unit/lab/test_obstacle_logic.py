"""stop_at_obstacle's and wander's decisions on synthetic scans (Gazebo's 0..2pi TurtleBot3 scan,
the real LDS-01, a Hokuyo-style -pi..pi scan). No ROS master needed. Units: m, rad, m/s, rad/s."""
import math
import random

import pytest

from tutorial_turtlebot.lab.obstacle_logic import (
    FORWARD, TURN_LEFT, TURN_RIGHT, StopAtObstacle, Wander)
from tutorial_turtlebot.robot_models import MODELS

from unit_helpers import CONVENTIONS, INF, NAN, make_scan


def points_world(points, fill=INF, radius=0.05):
    """World of round posts of ``radius`` at (x, y) in the lidar frame; ``fill`` elsewhere."""
    def world(b):
        hits = []
        for x, y in points:
            along = x * math.cos(b) + y * math.sin(b)       # post centre along the ray
            miss = abs(-x * math.sin(b) + y * math.cos(b))  # and off it
            if along > 0 and miss < radius:
                hits.append(along - math.sqrt(radius ** 2 - miss ** 2))
        return min(hits) if hits else fill
    return world


def wall_ahead(distance, fill=INF):
    """A wall across the way at x = ``distance``."""
    return lambda b: distance / math.cos(b) if math.cos(b) > 1e-6 else fill


# --- stop_at_obstacle ----------------------------------------------------------------------------

@pytest.mark.parametrize("convention", CONVENTIONS)
def test_stop_goes_stops_and_goes_on(convention):
    logic = StopAtObstacle(speed=0.15, stop_distance=0.5)
    assert logic.update(make_scan(convention, wall_ahead(1.0))) == (0.15, 0.0)
    assert logic.update(make_scan(convention, wall_ahead(0.51))) == (0.15, 0.0)
    assert logic.update(make_scan(convention, wall_ahead(0.49))) == (0.0, 0.0)
    assert logic.stopped
    # Noise lifting it just over 0.5 m does not make it creep on (clear margin 0.05 m) ...
    assert logic.update(make_scan(convention, wall_ahead(0.53))) == (0.0, 0.0)
    # ... the way clearing does.
    assert logic.update(make_scan(convention, wall_ahead(0.56))) == (0.15, 0.0)
    assert logic.update(make_scan(convention, lambda b: INF)) == (0.15, 0.0)


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_stop_looks_at_the_front_sector_only(convention):
    logic = StopAtObstacle(stop_distance=0.5, sector=math.radians(15))
    # Close things beside and behind the robot do not stop it.
    beside = points_world([(0.0, 0.3), (0.0, -0.3), (-0.3, 0.0), (0.25, 0.25)])
    assert logic.update(make_scan(convention, beside))[0] > 0
    # A post 0.45 m away at 10 degrees does.
    post = points_world([(0.45 * math.cos(0.17), 0.45 * math.sin(0.17))])
    assert logic.update(make_scan(convention, post)) == (0.0, 0.0)


@pytest.mark.parametrize("convention", CONVENTIONS)
@pytest.mark.parametrize("junk", [INF, NAN, 0.0, 5.0])
def test_stop_ignores_junk(convention, junk):
    logic = StopAtObstacle()
    assert logic.update(make_scan(convention, lambda b: junk)) == (0.15, 0.0)
    assert logic.front is None


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_stop_treats_too_close_as_an_obstacle(convention):
    logic = StopAtObstacle()
    assert logic.update(make_scan(convention, lambda b: -INF if abs(b) < 0.1 else 2.0)) == \
        (0.0, 0.0)


def test_stop_on_the_handouts_middle_ray_bug():
    # Something 0.3 m behind: ranges[len/2] would stop the robot; the front is clear.
    logic = StopAtObstacle()
    scan = make_scan("gazebo", lambda b: 0.3 if abs(b) > 3.0 else 2.0)
    assert logic.update(scan) == (0.15, 0.0)


# --- wander --------------------------------------------------------------------------------------

@pytest.mark.parametrize("convention", CONVENTIONS)
def test_wander_forward_when_clear(convention):
    logic = Wander()
    assert logic.update(make_scan(convention, lambda b: INF)) == (0.2, 0.0)
    assert logic.update(make_scan(convention, wall_ahead(0.6))) == (0.2, 0.0)
    assert logic.state == FORWARD


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_wander_turns_toward_the_more_open_side(convention):
    # A wall ahead and a wall close on the right: turn left (positive angular.z).
    def right_closed(b):
        return 0.45 / math.cos(b) if abs(b) < 0.5 else 0.5 if b < 0 else 3.0
    logic = Wander(turn_speed=1.0)
    assert logic.update(make_scan(convention, right_closed)) == (0.0, 1.0)
    assert logic.state == TURN_LEFT
    logic = Wander(turn_speed=1.0)
    assert logic.update(make_scan(convention, lambda b: right_closed(-b))) == (0.0, -1.0)
    assert logic.state == TURN_RIGHT


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_wander_keeps_turning_one_way_until_clear_with_hysteresis(convention):
    logic = Wander(stop_distance=0.5, clear_margin=0.1)

    def left_open(b):
        return 0.4 if b <= 0.3 else 3.0

    assert logic.update(make_scan(convention, left_open)) == (0.0, 1.0)

    # Halfway through the turn the right looks more open: it keeps turning left (no dithering).
    def right_open(b):
        return 0.4 if b >= -0.3 else 3.0

    assert logic.update(make_scan(convention, right_open)) == (0.0, 1.0)
    # Just past stop_distance is not clear enough ...
    assert logic.update(make_scan(convention, wall_ahead(0.55))) == (0.0, 1.0)
    # ... stop_distance + clear_margin is.
    assert logic.update(make_scan(convention, wall_ahead(0.61))) == (0.2, 0.0)
    assert logic.state == FORWARD


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_wander_keeps_its_corridor_clear(convention):
    # A post 0.35 m ahead and 0.13 m to the left: at 20 degrees, outside the +-15 degree sector,
    # but in the burger's path (radius 0.15 m).
    post = points_world([(0.35, 0.13)], radius=0.01)
    logic = Wander(robot_radius=MODELS["burger"].turn_radius)
    assert logic.update(make_scan(convention, post))[0] == 0.0
    # The same post 0.2 m to the left is out of the burger's way ...
    wide = points_world([(0.35, 0.2)], radius=0.01)
    burger = MODELS["burger"].turn_radius
    assert Wander(robot_radius=burger).update(make_scan(convention, wide))[0] > 0
    # ... but not out of the waffle's.
    waffle = MODELS["waffle"].turn_radius
    assert Wander(robot_radius=waffle).update(make_scan(convention, wide))[0] == 0


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_wander_ignores_junk_and_stops_for_too_close(convention):
    for junk in (INF, NAN, 0.0, 9.0):
        assert Wander().update(make_scan(convention, lambda b: junk)) == (0.2, 0.0)

    def too_close(b):
        return -INF if abs(b) < 0.05 else INF

    assert Wander().update(make_scan(convention, too_close))[0] == 0.0


def blocked_ahead(scan, stop_distance, sector, radius):
    """Brute force, one ray at a time: is anything nearer than stop_distance in the front sector,
    or in the corridor of half-width radius ahead? (-inf counts as range_min.)"""
    for i, r in enumerate(scan.ranges):
        if r == -INF:
            r = scan.range_min
        elif not (math.isfinite(r) and scan.range_min <= r <= scan.range_max and r > 0):
            continue
        b = scan.angle_min + i * scan.angle_increment
        b = math.atan2(math.sin(b), math.cos(b))
        if abs(b) <= sector + 1e-6 and r < stop_distance:
            return True
        x, y = r * math.cos(b), r * math.sin(b)
        if 0 < x < stop_distance and abs(y) < radius:
            return True
    return False


@pytest.mark.parametrize("convention", CONVENTIONS)
def test_wander_never_drives_forward_when_blocked(convention):
    rng = random.Random(4)
    logic = Wander(robot_radius=0.26)
    count = CONVENTIONS[convention][2]
    moves = 0
    for _ in range(400):
        # Random clutter: a few posts near the robot, junk values sprinkled over the ring.
        posts = [(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)) for _ in range(rng.randint(0, 4))]
        scan = make_scan(convention, points_world(posts, radius=rng.uniform(0.02, 0.2)))
        ranges = list(scan.ranges)
        for _ in range(rng.randint(0, 40)):
            ranges[rng.randrange(count)] = rng.choice([INF, -INF, NAN, 0.0, 60.0])
        scan = scan._replace(ranges=ranges)
        linear, angular = logic.update(scan)
        blocked = blocked_ahead(scan, 0.5, math.radians(15), 0.26)
        assert linear >= 0.0
        assert linear == 0.0 or angular == 0.0
        if blocked:
            assert linear == 0.0
        moves += linear > 0
    assert moves > 50  # it did not just sit there
