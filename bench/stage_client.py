#!/usr/bin/env python3
"""Benchmark helper: a reinforcement-learning client of learning stage 1, written as
turtlebot3_dqn's environment is (one step = publish an action, then wait for the next scan;
reset_simulation and a goal spawned with spawn_sdf_model, found in /gazebo/model_states).

    stage_client.py SECONDS [--steps-only]
Runs episodes of 50 steps for SECONDS of wall time and prints ``steps_per_wall_second``.
``--steps-only``: only the steps (publish an action, wait for the next scan), no services and
no /gazebo/model_states, so it runs against any /scan publisher (bench/scan_source.py).
"""
import math
import sys
import threading
import time

import rospy
from gazebo_msgs.msg import ModelStates
from gazebo_msgs.srv import DeleteModel, SpawnModel
from geometry_msgs.msg import Pose, Twist
from sensor_msgs.msg import LaserScan
from std_srvs.srv import Empty

GOAL = """<sdf version="1.6"><model name="goal"><static>1</static><link name="goal">
<visual name="v"><geometry><box><size>0.5 0.5 0.001</size></box></geometry></visual>
</link></model></sdf>"""
ACTIONS = (1.5, 0.75, 0.0, -0.75, -1.5)  # angular.z of turtlebot3_dqn's five actions


class Stage:
    def __init__(self):
        self.models = []
        self.lock = threading.Lock()
        rospy.Subscriber("gazebo/model_states", ModelStates, self._on_models, queue_size=1)
        self.cmd = rospy.Publisher("cmd_vel", Twist, queue_size=5)
        for name in ("gazebo/reset_simulation", "gazebo/spawn_sdf_model", "gazebo/delete_model"):
            rospy.wait_for_service(name, 60.0)
        self.reset_proxy = rospy.ServiceProxy("gazebo/reset_simulation", Empty)
        self.spawn = rospy.ServiceProxy("gazebo/spawn_sdf_model", SpawnModel)
        self.delete = rospy.ServiceProxy("gazebo/delete_model", DeleteModel)

    def _on_models(self, msg):
        with self.lock:
            self.models = list(msg.name)

    def has(self, name):
        with self.lock:
            return name in self.models

    def respawn_goal(self, x, y):
        if self.has("goal"):
            self.delete("goal")
            while self.has("goal"):
                time.sleep(0.001)
        pose = Pose()
        pose.position.x, pose.position.y = x, y   # all-zero quaternion, as turtlebot3_dqn sends
        self.spawn("goal", GOAL, "robotos_name_space", pose, "world")
        while not self.has("goal"):
            time.sleep(0.001)

    def step(self, action):
        twist = Twist()
        twist.linear.x, twist.angular.z = 0.15, ACTIONS[action]
        self.cmd.publish(twist)
        return rospy.wait_for_message("scan", LaserScan, timeout=5)

    def reset(self):
        self.reset_proxy()
        return rospy.wait_for_message("scan", LaserScan, timeout=5)


def steps_only(seconds):
    """Steps per wall second of Stage.step's publish-and-wait alone, for ``seconds``."""
    cmd = rospy.Publisher("cmd_vel", Twist, queue_size=5)
    rospy.wait_for_message("scan", LaserScan, timeout=30)
    steps, start = 0, time.monotonic()
    while time.monotonic() - start < seconds:
        twist = Twist()
        twist.linear.x, twist.angular.z = 0.15, ACTIONS[steps % len(ACTIONS)]
        cmd.publish(twist)
        rospy.wait_for_message("scan", LaserScan, timeout=5)
        steps += 1
    return steps / (time.monotonic() - start)


def main():
    seconds = float(sys.argv[1])
    rospy.init_node("bench_stage_client", anonymous=True, disable_signals=True)
    if "--steps-only" in sys.argv[2:]:
        print("%.1f" % steps_only(seconds), flush=True)
        return
    stage = Stage()
    stage.reset()
    stage.respawn_goal(0.6, 0.0)
    steps, episode, start = 0, 0, time.monotonic()
    while time.monotonic() - start < seconds:
        stage.reset()
        episode += 1
        for k in range(50):
            scan = stage.step((steps + k) % len(ACTIONS))
            if min(r for r in scan.ranges if not math.isnan(r)) < 0.13:
                break
            steps += 1
        stage.respawn_goal(0.6 * math.cos(episode), 0.6 * math.sin(episode))
    print("%.1f" % (steps / (time.monotonic() - start)), flush=True)


if __name__ == "__main__":
    main()
