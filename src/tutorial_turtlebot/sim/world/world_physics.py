"""Physics properties of Gazebo's world API: get/set_physics_properties, checked by
physics_properties.validate and applied by the Simulation."""
from ...errors import RequestError
from .physics_properties import PhysicsProperties, validate


class PhysicsRequests:
    """The physics requests of the world API.

    A part of ``WorldControl`` (world_control), which gives it ``sim``, ``models`` and the
    shared look-ups (``_model``, ``_frame``, ``_scoped_link``, ``_joint``)."""

    def physics_properties(self) -> PhysicsProperties:
        return self.sim.physics_properties

    def set_physics_properties(self, props: PhysicsProperties) -> None:
        """Apply ``props``: step, real-time factor (the caller paces), gravity, Bullet's
        counterparts of the ODE fields."""
        try:
            validate(props)
        except ValueError as err:
            raise RequestError("SetPhysicsProperties: %s" % err) from None
        self.sim.set_physics_properties(props)
