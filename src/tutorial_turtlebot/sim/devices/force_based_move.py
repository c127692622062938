"""A force-based move as hector_gazebo_plugins' ``libgazebo_ros_force_based_move`` does it:
at every physics step, a force on the base in its own frame proportional to the error of its
velocity (command minus measured, linear.x and linear.y) and a torque about z proportional to
the error of its yaw rate. Units: m, s, rad, kg, N, N*m.
"""
from typing import Tuple


def push(command: Tuple[float, float, float], linear: Tuple[float, float], yaw_rate: float,
         gains: Tuple[float, float, float], mass: float, inertia: float,
         dt: float) -> Tuple[float, float, float]:
    """(force x, force y in the base frame, N; torque about z, N*m) toward ``command`` (x,
    y m/s in the base frame, yaw rate rad/s) from the measured base-frame ``linear`` velocity
    and ``yaw_rate``, with ``gains`` (x, y: N per m/s; yaw: N*m per rad/s). A gain is held to
    what closes the error in one step of ``dt`` s on ``mass`` kg (``inertia`` kg m^2 about
    z): beyond it the explicit step would overshoot and grow (Gazebo's 1 ms step lets heavier
    robots keep the full gain)."""
    kx, ky, kyaw = (min(gains[0], mass / dt), min(gains[1], mass / dt),
                    min(gains[2], inertia / dt))
    return ((command[0] - linear[0]) * kx, (command[1] - linear[1]) * ky,
            (command[2] - yaw_rate) * kyaw)
