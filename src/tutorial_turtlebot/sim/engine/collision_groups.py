"""The collision groups of the world's bodies and the surface every world body has. Plain
numbers, shared by the engine's builders (world_bullet, movable_bodies, robot_body).
"""

# World bodies are in collision group 4. A laser that must see the world only casts rays with
# collisionFilterMask=WORLD_COLLISION_GROUP, and other bodies (the robot) use another group.
# Bullet also tests the ray's own group (1) against a body's mask, so the mask keeps bit 1; it
# drops the world's own bit, so that static bodies never test each other (wasted work every step).
# Robots (robot_body.RobotBody) take one bit each of the higher ones, up to
# ALL_COLLISION_GROUPS.
WORLD_COLLISION_GROUP = 4
ALL_COLLISION_GROUPS = (1 << 28) - 1
WORLD_COLLISION_MASK = ALL_COLLISION_GROUPS & ~WORLD_COLLISION_GROUP
# Movable bodies: in the world's group (the laser sees them) and one of their own, which the
# static bodies' mask keeps, so that they rest on the floor and hit walls.
MOVABLE_COLLISION_GROUP = WORLD_COLLISION_GROUP | 8
MOVABLE_COLLISION_MASK = ALL_COLLISION_GROUPS
MOVABLE_KINDS = ("box", "cylinder", "sphere", "mesh")

WORLD_FRICTION = 1.0        # lateral friction coefficient of every world surface
WORLD_RESTITUTION = 0.0
