"""The gazebo_ros drive plugins besides the diff drive (robot_plugins reads that one), one
module each, by the library file they are loaded from. Each module has ``read(reader, plugin,
name)`` (its dataclass, with the plugin's defaults) and ``PARAMS`` (the parameters it reads).
Every drive's dataclass has ``command_topic``, ``odometry_topic``, ``odometry_frame``,
``robot_base_frame``, ``robot_namespace``, ``publish_odom_tf`` and ``pose_covariance`` (the
odometry's pose covariance diagonal). Adding a drive is one module and one line of ``MODULES``.
No ROS, no pybullet.
"""
from . import (gazebo_ros_force_based_move, gazebo_ros_planar_move, gazebo_ros_skid_steer_drive,
               gazebo_ros_tricycle_drive)

MODULES = {
    gazebo_ros_skid_steer_drive.SKID_STEER: gazebo_ros_skid_steer_drive,
    gazebo_ros_planar_move.PLANAR_MOVE: gazebo_ros_planar_move,
    gazebo_ros_tricycle_drive.TRICYCLE: gazebo_ros_tricycle_drive,
    gazebo_ros_force_based_move.FORCE_BASED_MOVE: gazebo_ros_force_based_move,
}
