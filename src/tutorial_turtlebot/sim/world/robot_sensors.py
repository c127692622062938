"""A URDF robot's sensors that SimRobot does not make itself (RobotPlugins.sensors: range,
block laser, bumper, depth, multi- and triggered cameras, imu sensor), made into what
world_sensors runs: each on the robot's model (world_models.RobotModel) where Gazebo's URDF
conversion puts it. Knows nothing of ROS or pybullet.

Gazebo lumps a link fixed to its parent into that parent (sdformat's parser_urdf), and its
sensors with it: a sensor of a lumped link sits on the first link up that is not lumped, at
the lumped link's pose there composed with the sensor's <pose>. Its frame stays the link it
was written on (frames are the URDF's link names; the ROS side adds the robot's prefix). A
bumper's <collision>s are the holding link's collisions as Gazebo names them
(RobotDescription.collision_names: a lumped one "base_footprint_fixed_joint_lump__..."). Topics
resolve in the plugin's <robotNamespace>, else in the spawn's namespace (gazebo_ros' spawn
writes it into every <plugin> that has none), else gazebo_ros_imu_sensor's "/<model>".
Units: m, rad.
"""
from dataclasses import replace
from typing import List, Tuple

import numpy as np

from .. import kinematics
from ..files.plugins.camera_types import WorldCamera
from ..files.plugins.gazebo_ros_bumper import BumperSensor
from ..files.plugins.gazebo_ros_imu_sensor import ImuSensorPlugin
from ..files.plugins.robot_plugin_types import CameraSensor


def holding_link(description, link: str) -> Tuple[str, np.ndarray]:
    """(the link of Gazebo's model that holds URDF ``link``: itself, or the first parent up
    that is not lumped; 4x4 pose of ``link`` in it)."""
    kept = set(description.model_links())
    holder = link
    while holder not in kept and description.parent_joint(holder) is not None:
        holder = description.parent_joint(holder).parent
    return holder, description.transform(holder, link)


def _in_holder(spec, model: str, holder: str, offset: np.ndarray, namespace: str):
    """``spec`` on ``model``'s link ``holder`` (scoped), at ``offset`` (4x4) there, its topics
    in ``namespace`` unless its plugin names its own."""
    in_holder = tuple(float(v) for v in offset[:3, 3]) + kinematics.rpy_from_matrix(
        offset[:3, :3])
    fields = dict(link="%s::%s" % (model, holder),
                  pose=kinematics.compose_xyz_rpy(in_holder, spec.pose),
                  robot_namespace=spec.robot_namespace or namespace)
    if isinstance(spec, ImuSensorPlugin) and not fields["robot_namespace"]:
        fields["robot_namespace"] = "/" + model
    if isinstance(spec, BumperSensor):
        fields["collisions"] = tuple("%s::%s::%s" % (model, holder, c[len(spec.link) + 2:])
                                     for c in spec.collisions)
    if isinstance(spec, WorldCamera) and spec.cameras:
        fields["cameras"] = tuple(_in_holder(c, model, holder, offset, namespace)
                                  for c in spec.cameras)
    return replace(spec, **fields)


def robot_sensor_specs(model: str, namespace: str, description,
                       cameras: bool = True) -> List[object]:
    """The world sensors (world_sensors.runner_for's specs) of the robot model ``model``
    spawned in ``namespace`` (normalize_namespace's form) from ``description`` (its
    RobotDescription): one a sensor of ``description.plugins.sensors``, in file order; without
    its cameras unless ``cameras`` (RobotOptions.camera: the launch's camera:=false)."""
    out = []
    for spec in description.plugins.sensors:
        if isinstance(spec, CameraSensor) and not cameras:
            continue
        holder, offset = holding_link(description, spec.link)
        out.append(_in_holder(spec, model, holder, offset, namespace))
    return out
