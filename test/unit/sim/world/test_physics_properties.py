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
    PhysicsProperties(ode=OdeConfig(sor_pgs_iters=0)), PhysicsProperties(ode=OdeConfig(erp=float("nan")))])
def test_refused(bad):
    with pytest.raises(ValueError):
        validate(bad)


def test_bullet_counterparts():
    params = bullet_parameters(OdeConfig(sor_pgs_iters=50, erp=0.3, cfm=1e-5))
    assert params == {"numSolverIterations": 50, "erp": 0.3, "contactERP": 0.3, "globalCFM": 1e-5}
