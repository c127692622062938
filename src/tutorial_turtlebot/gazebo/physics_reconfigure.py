"""dynamic_reconfigure of the physics on ``/gazebo``, as gazebo_ros has it (doc/turtlebot3.md 2.6).

The server starts from the simulator's physics properties (not the cfg defaults); later
changes are compared with them and pushed as one set_physics_properties, in the simulation loop.
``rosrun dynamic_reconfigure dynparam set /gazebo max_update_rate 0`` runs the sim as fast as
possible. A change the simulator refuses (as set_physics_properties refuses it: a
max_update_rate below a real-time factor of pacing.MIN_REAL_TIME_FACTOR, say) is logged in one
line and answered with the values still in force.
"""
from dataclasses import asdict

import rospy
from dynamic_reconfigure.server import Server

from . import physics_config
from .loop_requests import NotAnswered
from ..errors import RequestError
from ..sim.world.physics_properties import PhysicsProperties, updated


def as_config(props: PhysicsProperties) -> dict:
    """The Physics.cfg parameters of ``props``."""
    config = dict(asdict(props.ode), time_step=props.time_step,
                  max_update_rate=props.max_update_rate)
    config.update(("gravity_" + axis, g) for axis, g in zip("xyz", props.gravity))
    return config


class PhysicsReconfigure:
    """The server; ``api`` is the node's WorldApi (run_in_loop, apply_physics, control)."""

    def __init__(self, api):
        self.api = api
        self._started = False
        self.server = Server(physics_config, self._callback)

    def _callback(self, config, _level):
        current = self.api.control.physics_properties()
        if not self._started:   # the server's first call: report what runs, change nothing
            self._started = True
            config.update(as_config(current))
            return config
        names = as_config(current)
        changes = {k: config[k] for k in names if config[k] != names[k]}
        if changes:
            props = updated(current, **changes)

            def apply():
                try:
                    self.api.apply_physics(props)
                    return None
                except RequestError as err:
                    return str(err)
            try:
                problem = self.api.run_in_loop(apply)
            except NotAnswered:
                problem = "the simulation did not answer; the physics are as they were"
            if problem:
                rospy.logwarn("dynamic_reconfigure: %s", problem)
        config.update(as_config(self.api.control.physics_properties()))
        return config
