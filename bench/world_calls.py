#!/usr/bin/env python3
"""Benchmark helper: the world API's latency as a client sees it (a process apart from the sim).

    world_calls.py N        spawn a 0.2 m box N times and delete it again
Prints one line: ``spawn_ms delete_ms`` (median wall milliseconds per service round trip).
"""
import statistics
import sys
import time

import rospy
from gazebo_msgs.srv import DeleteModel, SpawnModel
from geometry_msgs.msg import Pose

BOX = """<sdf version="1.6"><model name="box"><link name="link"><collision name="c"><geometry>
<box><size>0.2 0.2 0.2</size></box></geometry></collision><visual name="v"><geometry>
<box><size>0.2 0.2 0.2</size></box></geometry></visual></link></model></sdf>"""


def main():
    count = int(sys.argv[1])
    rospy.init_node("bench_world_calls", anonymous=True, disable_signals=True)
    for name in ("/gazebo/spawn_sdf_model", "/gazebo/delete_model"):
        rospy.wait_for_service(name, 60.0)
    spawn = rospy.ServiceProxy("/gazebo/spawn_sdf_model", SpawnModel, persistent=True)
    delete = rospy.ServiceProxy("/gazebo/delete_model", DeleteModel, persistent=True)
    pose = Pose()
    pose.position.x, pose.position.y, pose.orientation.w = 1.0, 1.0, 1.0
    spawns, deletes = [], []
    for _ in range(count):
        t0 = time.perf_counter()
        ok = spawn("bench_box", BOX, "", pose, "world").success
        t1 = time.perf_counter()
        ok = delete("bench_box").success and ok
        t2 = time.perf_counter()
        if not ok:
            print("nan nan", flush=True)
            return
        spawns.append(1000 * (t1 - t0))
        deletes.append(1000 * (t2 - t1))
    print("%.1f %.1f" % (statistics.median(spawns), statistics.median(deletes)), flush=True)


if __name__ == "__main__":
    main()
