"""A tricycle as Gazebo's ``libgazebo_ros_tricycle_drive`` drives it: one steered, driven wheel
(the command's linear.x is its rim speed, m/s; angular.z its steering angle, rad) and two
passive encoder wheels. Units: m, s, rad; joint speeds in rad/s.
"""
import math
from typing import Optional, Tuple

MAX_STEERING = math.pi / 2.0   # rad: the plugin holds the steering angle within +-pi/2


def steering_angle(wheelbase: float, radius: float) -> float:
    """The steering angle (rad, left positive) that turns a tricycle of ``wheelbase`` (m, the
    steered wheel to the rear axle) on a circle of ``radius`` (m, of the rear axle's middle;
    negative: to the right; inf: straight)."""
    return math.atan2(wheelbase, radius) if radius >= 0 else -math.atan2(wheelbase, -radius)


def yaw_rate(speed: float, angle: float, wheelbase: float) -> float:
    """rad/s of a tricycle whose steered wheel rolls at ``speed`` (m/s) turned ``angle``."""
    return speed * math.sin(angle) / wheelbase


class TricycleController:
    """The latest command as the actuated wheel's joint speed and the steering's target, with
    gazebo_ros_tricycle_drive's ramp: in the joint's rad/s, from its measured speed, by at most
    the acceleration (the speed going down) or the deceleration (going up) times dt, left as
    it is within the speed tolerance (the plugin's units and choices)."""

    def __init__(self, radius: float, acceleration: float = 0.0, deceleration: float = 0.0,
                 speed_tolerance: float = 0.01, steering_speed: float = 0.0,
                 angle_tolerance: float = 0.01):
        self.radius = radius
        self.acceleration = acceleration
        self.deceleration = deceleration
        self.speed_tolerance = speed_tolerance
        self.steering_speed = steering_speed
        self.angle_tolerance = angle_tolerance
        self.reset()

    def reset(self) -> None:
        """Stop: zero speed, wheel straight."""
        self.speed = self.angle = 0.0

    def set_command(self, speed: float, angle: float) -> None:
        """linear.x (m/s at the rim), angular.z (the steering angle, rad)."""
        self.speed, self.angle = speed, angle

    @property
    def stopped(self) -> bool:
        return self.speed == 0.0

    def wheel_speed(self, current: float, dt: float) -> float:
        """The actuated wheel's joint speed (rad/s) for this tick, from its ``current`` one."""
        target = self.speed / self.radius
        if self.acceleration <= 0:
            return target
        diff = current - target
        if abs(diff) < self.speed_tolerance:
            return current
        if abs(diff) > self.acceleration * dt:
            return (current - self.acceleration * dt if diff > 0
                    else current + self.deceleration * dt)
        return target

    def steering(self, current: float) -> Tuple[Optional[float], float]:
        """(angle to hold, None for a speed) and the steering joint's speed (rad/s) this tick,
        from its ``current`` angle: with a steering speed, toward the target at it (0 within
        the tolerance); without, the target angle at once."""
        target = max(-MAX_STEERING, min(MAX_STEERING, self.angle))
        if self.steering_speed <= 0:
            return target, 0.0
        diff = target - current
        if abs(diff) < self.angle_tolerance:
            return None, 0.0
        return None, math.copysign(self.steering_speed, diff)
