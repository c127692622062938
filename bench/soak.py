#!/usr/bin/env python3
"""Soak: the real sim as fast as possible under churn, its RSS printed over time.

    soak.py [--sim-minutes 30] [--robots 4] [--every 10]

Starts the sim node alone in the empty world (roslaunch on a free port, as run_bench's
SimRun), spawns ``--robots`` Burgers, subscribes to every topic it publishes, and until that
much sim time has run (resets put the clock back; the time run is counted across them):
spawns and deletes a box, deletes and respawns the last robot, sends every robot NaN, 1e9 and
normal cmd_vel, resets the world and the simulation, pauses and unpauses. Every ``--every``
wall seconds it prints ``wall_s sim_s rss_mb spawns robot_respawns resets``; the last line says
whether RSS stayed flat: its growth over the last third of the run under 2 MB.
Run from a shell where ``source catkin_ws/devel/setup.bash`` was done.
"""
import argparse
import os
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, os.pardir, "src"))

from run_bench import EMPTY_SIM_LAUNCH, SimRun, rss_mb  # noqa: E402

FLAT_MB = 2.0
BOX = ("<sdf version='1.6'><model name='soak_box'><link name='link'><inertial><mass>0.1</mass>"
       "<inertia><ixx>0.0004</ixx><iyy>0.0004</iyy><izz>0.0004</izz></inertia></inertial>"
       "<collision name='c'><geometry><box><size>0.15 0.15 0.15</size></box></geometry>"
       "</collision><visual name='v'><geometry><box><size>0.15 0.15 0.15</size></box>"
       "</geometry></visual></link></model></sdf>")


def soak(sim_minutes: float, robots: int, every: float) -> bool:
    with tempfile.NamedTemporaryFile("w", suffix=".launch", prefix="soak_sim_",
                                     delete=False) as f:
        f.write(EMPTY_SIM_LAUNCH)
    run = SimRun(["real_time_factor:=0"], launch=f.name)
    try:
        run.start()
        pid = run.sim_pid()
        os.environ["ROS_MASTER_URI"] = run.env["ROS_MASTER_URI"]
        return _churn(pid, sim_minutes * 60.0, robots, every)
    finally:
        run.stop()
        os.unlink(f.name)


def _churn(pid: int, sim_seconds: float, robots: int, every: float) -> bool:
    import rospy
    from gazebo_msgs.srv import DeleteModel, SpawnModel
    from geometry_msgs.msg import Pose, Twist
    from rosgraph_msgs.msg import Clock
    from std_srvs.srv import Empty
    from multi_robot import grid_pose
    from tutorial_turtlebot.sim.files.urdf.urdf_file import urdf_path

    rospy.init_node("soak", anonymous=True, disable_signals=True)
    names = ["spawn_urdf_model", "spawn_sdf_model", "delete_model", "reset_world",
             "reset_simulation", "pause_physics", "unpause_physics"]
    for name in names:
        rospy.wait_for_service("/gazebo/" + name, timeout=60)
    spawn_urdf = rospy.ServiceProxy("/gazebo/spawn_urdf_model", SpawnModel)
    spawn_sdf = rospy.ServiceProxy("/gazebo/spawn_sdf_model", SpawnModel)
    delete = rospy.ServiceProxy("/gazebo/delete_model", DeleteModel)
    empties = {n: rospy.ServiceProxy("/gazebo/" + n, Empty) for n in names[3:]}
    with open(urdf_path("burger", False)) as f:
        urdf = f.read()

    clock = {"last": 0.0, "run": 0.0}

    def on_clock(msg):
        t = msg.clock.to_sec()
        clock["run"] += t - clock["last"] if t >= clock["last"] else t   # a reset: from 0
        clock["last"] = t

    rospy.Subscriber("/clock", Clock, on_clock, queue_size=10)
    robot_names = ["tb3_%d" % i for i in range(robots)]
    for i, name in enumerate(robot_names):
        if not spawn_urdf(name, urdf, name, grid_pose(i), "world").success:
            raise RuntimeError("could not spawn %s" % name)
    cmd = {n: rospy.Publisher("/%s/cmd_vel" % n, Twist, queue_size=1) for n in robot_names}
    subscribed = {}

    def subscribe_all():
        for topic, _ in rospy.get_published_topics():
            if topic not in subscribed and topic != "/rosout":
                subscribed[topic] = rospy.Subscriber(topic, rospy.AnyMsg, lambda _m: None,
                                                     queue_size=1)

    def twist(v, w):
        t = Twist()
        t.linear.x, t.angular.z = v, w
        return t

    box_pose = Pose()
    box_pose.position.z, box_pose.orientation.w = 0.5, 1.0
    box_pose.position.y = -4.0
    samples = []   # (wall s, sim s run, RSS MB)
    counts = {"spawns": 0, "respawns": 0, "resets": 0}
    start = next_sample = time.time()
    i = 0
    print("wall_s sim_s rss_mb spawns robot_respawns resets", flush=True)
    while True:
        now = time.time()
        if now >= next_sample:
            subscribe_all()
            samples.append((now - start, clock["run"], rss_mb(pid)))
            print("%6.0f %7.0f %7.1f %6d %4d %4d" % (samples[-1] + (
                counts["spawns"], counts["respawns"], counts["resets"])), flush=True)
            next_sample = now + every
            if clock["run"] >= sim_seconds:
                break
        i += 1
        spawn_sdf("soak_box", BOX, "", box_pose, "world")
        delete("soak_box")
        counts["spawns"] += 1
        for name in robot_names:
            for v in (float("nan"), 1e9, 0.1):
                cmd[name].publish(twist(v, 0.3 if v == 0.1 else v))
        if i % 10 == 0:
            last = robot_names[-1]
            delete(last)
            spawn_urdf(last, urdf, last, grid_pose(len(robot_names) - 1), "world")
            counts["respawns"] += 1
        if i % 25 == 0:
            empties["reset_world" if i % 50 else "reset_simulation"]()
            counts["resets"] += 1
        if i % 30 == 0:
            empties["pause_physics"]()
            time.sleep(0.05)
            empties["unpause_physics"]()
    third = [s for s in samples if s[0] >= samples[-1][0] * 2 / 3]
    growth = third[-1][2] - third[0][2]
    print("RSS %.1f MB at the first sample, %.1f MB at the end; over the last third "
          "(%.0f..%.0f wall s) it grew %.2f MB: %s" % (
              samples[0][2], samples[-1][2], third[0][0], third[-1][0], growth,
              "flat" if growth < FLAT_MB else "NOT flat (>= %g MB)" % FLAT_MB), flush=True)
    rospy.signal_shutdown("soak done")
    return growth < FLAT_MB


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sim-minutes", type=float, default=30.0)
    parser.add_argument("--robots", type=int, default=4)
    parser.add_argument("--every", type=float, default=10.0, help="wall s between samples")
    args = parser.parse_args()
    sys.exit(0 if soak(args.sim_minutes, args.robots, args.every) else 1)


if __name__ == "__main__":
    main()
