"""make bench's nav group: the sim at real time feeding the SLAM and Navigation chapters' clients.

``measure(kind)`` launches, on a master of its own, ``turtlebot3_slam.launch sim:=true`` (the
sim and gmapping with ROBOTIS' parameters) or ``turtlebot3_navigation.launch sim:=true``
(the sim, map_server on a map of turtlebot3_world's shapes, amcl and move_base), both
headless (``rviz:=false``), the Burger in turtlebot3_world turning in place at 0.5 rad/s so
that gmapping and amcl do their work; and reads the sim's CPU (% of one core) and the achieved
real-time factor over a window of wall time. The clients run in the navigation extra's
environment (tools/install_extra.sh nav); without the extra ``nav_env()`` is None and the rows
say how to install it.
"""
import os
import signal
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, os.pardir, "test", "rostest"))
from nav_support import nav_env, write_world_map  # noqa: E402
from process_helpers import (cpu_seconds, free_port, node_on_master,  # noqa: E402
                             signal_process, stop_process, wait_for)

__all__ = ["measure", "nav_env"]   # nav_env: None where the extra is not installed

MAP_BOX = (-3.3, -3.3, 3.3, 3.3)    # m: turtlebot3_world's arena with a margin
SPAWN = ("-2.0", "-0.5", "0.0")     # the world's spawn: amcl starts there


def _sim_time(env):
    """(wall s, sim s): the sim time from /gazebo/get_world_properties, and the wall time
    halfway through the call (rosservice's own start-up is most of it)."""
    before = time.time()
    done = subprocess.run(
        ["rosservice", "call", "/gazebo/get_world_properties"], env=env, capture_output=True,
        text=True, timeout=20)
    for line in done.stdout.splitlines():
        if line.startswith("sim_time:"):
            return (before + time.time()) / 2.0, float(line.split(":", 1)[1])
    raise RuntimeError("no sim_time from /gazebo/get_world_properties")


def measure(kind: str, env: dict, seconds: float = 10.0, warmup: float = 10.0):
    """(achieved factor, sim CPU % of one core) with ``kind`` "slam" or "nav" running."""
    port = free_port()
    env = dict(env, ROS_MASTER_URI="http://localhost:%d" % port)
    args = ["sim:=true", "rviz:=false", "model:=burger", "world:=turtlebot3_world"]
    folder = tempfile.mkdtemp(prefix="bench_nav_")
    if kind == "slam":
        launch = "turtlebot3_slam.launch"
    else:
        launch = "turtlebot3_navigation.launch"
        map_file = write_world_map("turtlebot3_world", os.path.join(folder, "map"), MAP_BOX)
        args += ["map_file:=%s" % map_file, "initial_pose_x:=%s" % SPAWN[0],
                 "initial_pose_y:=%s" % SPAWN[1], "initial_pose_a:=%s" % SPAWN[2]]
    procs = [subprocess.Popen(["roslaunch", "-p", str(port), "tutorial_turtlebot", launch] + args,
                              env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                              start_new_session=True)]
    try:
        pid = wait_for(lambda: node_on_master("gazebo", port), 60.0, 0.2)
        if pid is None:
            raise RuntimeError("%s: the sim did not start" % launch)
        procs.append(subprocess.Popen(
            ["rostopic", "pub", "-r", "10", "/cmd_vel", "geometry_msgs/Twist",
             "{angular: {z: 0.5}}"], env=env, stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL, start_new_session=True))
        time.sleep(warmup)             # the clients are up, subscribed and working
        (wall0, sim0), cpu0, cpu_wall0 = _sim_time(env), cpu_seconds(pid), time.time()
        time.sleep(seconds)
        (wall1, sim1), cpu1, cpu_wall1 = _sim_time(env), cpu_seconds(pid), time.time()
        return ((sim1 - sim0) / (wall1 - wall0),
                100.0 * (cpu1 - cpu0) / (cpu_wall1 - cpu_wall0))
    finally:
        for proc in reversed(procs):
            signal_process(proc, signal.SIGINT)
        for proc in reversed(procs):
            stop_process(proc, 15.0, sig=None)
