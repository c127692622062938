"""Physics properties: factor, validation, Physics.cfg names (sim/physics_properties). No ROS."""
import pytest

from tutorial_turtlebot.sim.world.physics_properties import (OdeConfig, PhysicsProperties,
                                                             bullet_parameters, updated, validate)


def test_real_time_factor_is_step_times_rate():
    props = PhysicsProperties.for_factor(0.0025, 1.0, OdeConfig())
    assert props.max_update_rate == pytest.approx(400.0)
    assert props.real_time_factor == pytest.approx(1.0)
    assert PhysicsProperties(0.001, 1000.0).real_time_factor == pytest.approx(1.0)
    assert PhysicsProperties(0.001, 0.0).real_time_factor == 0.0     # as fast as possible


def test_round_trip_of_every_field():
    props = PhysicsProperties(0.002, 250.0, (0.0, 0.1, -9.81),
                              OdeConfig(True, 3, 50, 1.3, 0.0, 0.001, 100.0, 1e-5, 0.3, 10))
    again = updated(PhysicsProperties(), time_step=0.002, max_update_rate=250.0, gravity_y=0.1,
                    gravity_z=-9.81, auto_disable_bodies=True, sor_pgs_precon_iters=3,
                    sor_pgs_iters=50, sor_pgs_w=1.3, contact_surface_layer=0.001,
                    contact_max_correcting_vel=100.0, cfm=1e-5, erp=0.3, max_contacts=10)
    assert again == props


@pytest.mark.parametrize("bad", [
    PhysicsProperties(time_step=0.0), PhysicsProperties(time_step=0.5),
    PhysicsProperties(time_step=float("nan")), PhysicsProperties(max_update_rate=-1.0),
    PhysicsProperties(gravity=(0.0, 0.0, float("inf"))),
    PhysicsProperties(ode=OdeConfig(sor_pgs_iters=0)),
    PhysicsProperties(ode=OdeConfig(erp=float("nan")))])
def test_refused(bad):
    with pytest.raises(ValueError):
        validate(bad)


def test_bullet_counterparts():
    params = bullet_parameters(OdeConfig(sor_pgs_iters=50, erp=0.3, cfm=1e-5))
    assert params == {"numSolverIterations": 50, "erp": 0.3, "contactERP": 0.3, "globalCFM": 1e-5}


def test_a_rate_whose_product_with_the_step_underflows_is_too_slow_not_as_fast_as_possible():
    subnormal = PhysicsProperties(0.0025, 5e-324)
    assert subnormal.real_time_factor == 0.0               # the product underflows
    with pytest.raises(ValueError, match="below"):
        validate(subnormal)
    validate(PhysicsProperties(0.0025, 0.0))               # 0 is still "as fast as possible"


def test_cfm_is_held_to_what_keeps_bodies_on_the_floor():
    """Past 0.1 Bullet's constraint force mixing lets a Waffle sink (6 cm at 1) and from 2 every
    body falls through the world: refused, one line."""
    validate(updated(PhysicsProperties(), cfm=0.1))
    for cfm in (0.11, 1.0, 1e6):
        with pytest.raises(ValueError, match=r"ode_config.cfm .* is outside \[0, 0.1\]"):
            validate(updated(PhysicsProperties(), cfm=cfm))
