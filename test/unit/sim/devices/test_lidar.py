"""The LDS-01 model: scan fields, ray geometry and range conversion (doc/turtlebot3.md 2.2, 6)."""
import math

import numpy as np
import pytest

from tutorial_turtlebot.errors import UserError
from tutorial_turtlebot.sim.devices.lidar import (LASER_MODELS, laser_config, ranges_from_distances,
                                                  ray_directions)

GAZEBO = laser_config("gazebo")
LDS01 = laser_config("lds01")


def rng(seed=1):
    return np.random.default_rng(seed)


# --- configs -----------------------------------------------------------------------------------

def test_gazebo_fields():
    """What gazebo_ros_laser publishes for the TurtleBot3 LDS."""
    assert GAZEBO.angle_min == 0.0
    assert GAZEBO.angle_max == 6.28319
    assert GAZEBO.angle_increment == pytest.approx(6.28319 / 359, rel=1e-12)
    assert GAZEBO.angle_increment == pytest.approx(0.0175019, abs=1e-7)
    assert GAZEBO.samples == 360
    assert (GAZEBO.range_min, GAZEBO.range_max) == (0.12, 3.5)
    assert GAZEBO.noise_sigma == 0.01
    assert GAZEBO.no_return == math.inf and GAZEBO.too_close == -math.inf
    assert GAZEBO.rate == 5.0


def test_lds01_fields():
    """What the real hls_lfcd_lds_driver publishes: exact 1 degree steps, 0.0 for no return."""
    assert LDS01.angle_min == 0.0
    assert LDS01.angle_increment == math.radians(1)
    assert LDS01.angle_max == pytest.approx(math.radians(359), rel=1e-12)
    assert LDS01.samples == 360
    assert (LDS01.range_min, LDS01.range_max) == (0.12, 3.5)
    assert LDS01.no_return == 0.0 and LDS01.too_close == 0.0


@pytest.mark.parametrize("cfg", [GAZEBO, LDS01], ids=["gazebo", "lds01"])
def test_last_angle_is_angle_max(cfg):
    """angle_min + increment * (samples - 1) == angle_max, as LaserScan users compute it."""
    assert cfg.angle_min + cfg.angle_increment * (cfg.samples - 1) == pytest.approx(
        cfg.angle_max, abs=1e-9)


@pytest.mark.parametrize("name", [None, "", "lds02", "Gazebo"])
def test_unknown_name_lists_the_valid_ones(name):
    """An unknown lidar_model is a UserError naming gazebo and lds01."""
    with pytest.raises(UserError) as err:
        laser_config(name)
    assert "gazebo" in str(err.value) and "lds01" in str(err.value)
    assert set(LASER_MODELS) == {"gazebo", "lds01"}


# --- ranges_from_distances ---------------------------------------------------------------------

def test_beyond_max_is_no_return():
    """At or beyond range_max (or no hit at all): +inf in gazebo mode, 0.0 in lds01 mode."""
    d = np.array([3.5, 3.6, 10.0, np.inf])
    assert np.all(ranges_from_distances(GAZEBO, d, rng()) == np.inf)
    assert np.all(ranges_from_distances(LDS01, d, rng()) == 0.0)


def test_at_or_under_min_is_too_close():
    """At or under range_min: -inf in gazebo mode, 0.0 in lds01 mode."""
    d = np.array([0.0, 0.05, 0.119, 0.12])
    assert np.all(ranges_from_distances(GAZEBO, d, rng()) == -np.inf)
    assert np.all(ranges_from_distances(LDS01, d, rng()) == 0.0)


@pytest.mark.parametrize("cfg", [GAZEBO, LDS01], ids=["gazebo", "lds01"])
def test_noise_is_gaussian_sigma_001(cfg):
    """Valid hits get zero-mean noise of sigma 0.01 m (statistics of 20000 seeded samples)."""
    out = ranges_from_distances(cfg, np.full(20000, 2.0), rng(7)).astype(np.float64)
    assert out.mean() == pytest.approx(2.0, abs=0.0005)
    assert out.std() == pytest.approx(0.01, rel=0.03)
    assert np.any(out != 2.0)


def test_noise_is_reproducible_with_the_seed():
    """The same seed gives the same scan; another seed another one."""
    d = np.linspace(0.5, 3.0, 360)
    a = ranges_from_distances(GAZEBO, d, rng(3))
    assert np.array_equal(a, ranges_from_distances(GAZEBO, d, rng(3)))
    assert not np.array_equal(a, ranges_from_distances(GAZEBO, d, rng(4)))


@pytest.mark.parametrize("cfg", [GAZEBO, LDS01], ids=["gazebo", "lds01"])
def test_noisy_values_are_clamped_into_the_range(cfg):
    """Hits just inside the limits never leave [range_min, range_max] after noise."""
    d = np.concatenate([np.full(5000, 0.121), np.full(5000, 3.499)])
    out = ranges_from_distances(cfg, d, rng(11))
    assert out.min() >= np.float32(cfg.range_min)
    assert out.max() <= np.float32(cfg.range_max)
    # Noise pushed about half of them onto the limits.
    assert np.count_nonzero(out == np.float32(cfg.range_min)) > 1000
    assert np.count_nonzero(out == np.float32(cfg.range_max)) > 1000


def test_output_is_float32_of_the_input_shape():
    """LaserScan.ranges is float32[]; one value per distance."""
    out = ranges_from_distances(GAZEBO, np.linspace(0.0, 5.0, 360), rng())
    assert out.dtype == np.float32 and out.shape == (360,)


def test_input_is_not_modified():
    """The caller's array of true distances is left alone."""
    d = np.array([0.05, 1.0, 4.0])
    ranges_from_distances(GAZEBO, d, rng())
    assert d.tolist() == [0.05, 1.0, 4.0]


# --- ray geometry ------------------------------------------------------------------------------

@pytest.mark.parametrize("cfg", [GAZEBO, LDS01], ids=["gazebo", "lds01"])
def test_rays_are_unit_and_planar(cfg):
    """360 unit vectors in the scan plane."""
    rays = ray_directions(cfg)
    assert rays.shape == (360, 3)
    assert np.allclose(np.linalg.norm(rays, axis=1), 1.0)
    assert np.all(rays[:, 2] == 0.0)


@pytest.mark.parametrize("cfg", [GAZEBO, LDS01], ids=["gazebo", "lds01"])
def test_index_0_is_straight_ahead(cfg):
    """Index 0 points along +x of base_scan (the front on both)."""
    assert ray_directions(cfg)[0] == pytest.approx((1.0, 0.0, 0.0))


def test_lds01_index_90_is_left():
    """Counter-clockwise in exact degrees: 90 = +y, 180 = -x, 270 = -y, 359 = -1 degree."""
    rays = ray_directions(LDS01)
    assert rays[90] == pytest.approx((0.0, 1.0, 0.0), abs=1e-12)
    assert rays[180] == pytest.approx((-1.0, 0.0, 0.0), abs=1e-12)
    assert rays[270] == pytest.approx((0.0, -1.0, 0.0), abs=1e-12)
    assert math.degrees(math.atan2(rays[359, 1], rays[359, 0])) == pytest.approx(-1.0)


def test_gazebo_index_90_is_90_25_degrees():
    """Gazebo's 6.28319/359 step: index 90 is 90.25 degrees, 359 repeats index 0."""
    rays = ray_directions(GAZEBO)

    def bearing(i):
        return math.degrees(math.atan2(rays[i, 1], rays[i, 0])) % 360.0

    assert bearing(90) == pytest.approx(90.25, abs=0.01)
    assert bearing(180) == pytest.approx(180.5, abs=0.01)
    assert bearing(270) == pytest.approx(270.75, abs=0.01)
    assert rays[359] == pytest.approx(rays[0], abs=1e-5)
