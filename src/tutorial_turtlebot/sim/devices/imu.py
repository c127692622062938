"""What an IMU link reads, from the link's motion: the acceleration from the change of its
world velocity between two readings, gravity's reaction added (at rest +9.8 m/s^2 along the
world's up, as Gazebo's ImuSensor reports it), rates and acceleration in the sensor frame, and
Gazebo's per-axis noise (a bias drawn once, white noise at each reading). No pybullet.
Units: m/s, m/s^2, rad/s, s; world frame z up (REP 103).
"""
from typing import Optional, Sequence, Tuple

import numpy as np

from .. import kinematics

Vec = Tuple[float, float, float]


class Accelerometer:
    """The mean world acceleration of a link between its readings (velocity differences)."""

    def __init__(self):
        self._last: Optional[Tuple[float, np.ndarray]] = None   # (time s, world velocity)

    def reset(self) -> None:
        self._last = None

    def acceleration(self, now: float, velocity: Sequence[float]) -> np.ndarray:
        """m/s^2, world: the change of ``velocity`` (m/s, world) since the last call at an
        earlier time ``now`` (s); zero at the first."""
        velocity = np.asarray(velocity, dtype=float)
        last, self._last = self._last, (now, velocity)
        if last is None or now <= last[0]:
            return np.zeros(3)
        return (velocity - last[1]) / (now - last[0])


def imu_axes(orientation: Sequence[float], angular: Sequence[float],
             acceleration: Sequence[float], gravity: Sequence[float]) -> Tuple[Vec, Vec]:
    """(angular velocity rad/s, linear acceleration m/s^2), both in the frame of the world
    ``orientation`` (x, y, z, w): the world ``angular`` velocity and ``acceleration`` less
    ``gravity`` (m/s^2, world), as an accelerometer feels them."""
    felt = np.asarray(acceleration, dtype=float) - np.asarray(gravity, dtype=float)
    return kinematics.to_body(orientation, angular), kinematics.to_body(orientation, felt)


class AxisNoises:
    """Gazebo's gaussian noise on three axes: each a bias N(bias_mean, bias_stddev) drawn once
    with a random sign, and N(mean, stddev) added at every reading. ``noises``: three objects
    with mean, stddev, bias_mean, bias_stddev."""

    def __init__(self, noises, rng: np.random.Generator):
        self.rng = rng
        self.mean = np.array([n.mean for n in noises], dtype=float)
        self.stddev = np.array([n.stddev for n in noises], dtype=float)
        bias = np.array([rng.normal(n.bias_mean, n.bias_stddev) if n.bias_stddev > 0
                         else n.bias_mean for n in noises], dtype=float)
        self.bias = np.where(rng.random(3) < 0.5, -bias, bias) if bias.any() else bias

    def applied(self, values: Sequence[float]) -> np.ndarray:
        out = np.asarray(values, dtype=float) + self.bias + self.mean
        if self.stddev.any():
            out = out + self.rng.normal(0.0, 1.0, 3) * self.stddev
        return out
