#!/usr/bin/env python3
"""Benchmark helper: spawn Burgers into a running sim and switch its pace, on request.

    multi_robot.py [SPACING]
Reads commands on stdin, one a line, and answers each with one line on stdout:
  ``spawn N``   spawn tb3_k for every k below N not spawned yet (/gazebo/spawn_urdf_model, the
                Burger's URDF, robot_namespace tb3_k) at grid_pose(k): ``spawned N``
  ``fast``      /gazebo/set_physics_properties with max_update_rate 0 (as fast as possible,
                Gazebo's way): ``fast``
  ``realtime``  max_update_rate 1 / time_step (real time): ``realtime``
A failure answers one line starting with ``error`` and exits 1.
"""
import os
import sys

import rospy
from gazebo_msgs.srv import GetPhysicsProperties, SetPhysicsProperties, SpawnModel
from geometry_msgs.msg import Pose

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, os.pardir, "src"))

from tutorial_turtlebot.sim.files.urdf.urdf_file import urdf_path  # noqa: E402

PER_ROW = 4
ROWS = 2
SPACING = 2.0  # m between two robots: each Burger's laser sees its neighbours


def grid_pose(index: int, spacing: float = SPACING) -> Pose:
    """Robot ``index`` on a grid of PER_ROW x ROWS places centred on the origin (index 8 and
    up continue in further rows), facing +x; the place of a robot does not depend on how many
    there are, so robots can be added one by one."""
    pose = Pose()
    pose.position.x = spacing * (index % PER_ROW - (PER_ROW - 1) / 2.0)
    pose.position.y = spacing * (index // PER_ROW - (ROWS - 1) / 2.0)
    pose.orientation.w = 1.0
    return pose


class Spawner:
    def __init__(self, spacing: float):
        self.spacing = spacing
        self.count = 0
        with open(urdf_path("burger"), encoding="utf-8") as f:
            self.xml = f.read()
        rospy.wait_for_service("/gazebo/spawn_urdf_model", timeout=60.0)
        self.spawn_srv = rospy.ServiceProxy("/gazebo/spawn_urdf_model", SpawnModel)
        self.get_physics = rospy.ServiceProxy("/gazebo/get_physics_properties",
                                              GetPhysicsProperties)
        self.set_physics = rospy.ServiceProxy("/gazebo/set_physics_properties",
                                              SetPhysicsProperties)

    def spawn_up_to(self, count: int) -> None:
        while self.count < count:
            name = "tb3_%d" % self.count
            resp = self.spawn_srv(name, self.xml, name, grid_pose(self.count, self.spacing), "")
            if not resp.success:
                raise RuntimeError("%s: %s" % (name, resp.status_message))
            self.count += 1

    def set_rate(self, fast: bool) -> None:
        props = self.get_physics()
        rate = 0.0 if fast else 1.0 / props.time_step
        resp = self.set_physics(props.time_step, rate, props.gravity, props.ode_config)
        if not resp.success:
            raise RuntimeError(resp.status_message)


def main():
    try:
        spacing = float(sys.argv[1]) if len(sys.argv) > 1 else SPACING
    except ValueError:
        print("error: usage: multi_robot.py [SPACING]", flush=True)
        sys.exit(1)
    rospy.init_node("bench_multi_robot", anonymous=True, disable_signals=True)
    try:
        spawner = Spawner(spacing)
        for line in sys.stdin:
            words = line.split()
            if words[:1] == ["spawn"] and len(words) == 2 and words[1].isdigit():
                spawner.spawn_up_to(int(words[1]))
                print("spawned %d" % spawner.count, flush=True)
            elif words in (["fast"], ["realtime"]):
                spawner.set_rate(words[0] == "fast")
                print(words[0], flush=True)
            elif words:
                raise RuntimeError("unknown command %r" % line.strip())
    except (rospy.ROSException, rospy.ServiceException, RuntimeError) as err:
        print("error %s" % err, flush=True)
        sys.exit(1)


if __name__ == "__main__":
    main()
