"""The bounds of the drive plugins' numbers (limits.outside's arguments, as sensor_reader's
``Bounds``: low, high, unit, low_open), shared by the drive plugin modules
(gazebo_ros_skid_steer_drive, gazebo_ros_planar_move, ...). Plain tuples: this module is
imported by robot_plugin_types, below sensor_reader. Units: m, N*m, m/s^2, rad/s, s."""
from .. import limits

WHEEL = (limits.MIN_WHEEL_SIZE, limits.MAX_SIZE, "m")   # a diameter, a separation
TORQUE = (0.0, limits.MAX_FORCE, "N m", True)
ACCELERATION = (0.0, limits.MAX_ACCELERATION, "m/s^2")
COVARIANCE = (0.0, limits.MAX_NOISE ** 2)
TOLERANCE = (0.0, limits.MAX_SIZE)                       # m/s, rad
STEERING_SPEED = (0.0, limits.MAX_ANGULAR_SPEED, "rad/s")
TIMEOUT = (-limits.MAX_DURATION_NS / 1e9, limits.MAX_DURATION_NS / 1e9, "s")  # < 0: none
