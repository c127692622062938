#!/usr/bin/env python3
"""Hostile soak: the hostile requests that once killed, froze or choked the sim, replayed in a
loop against one sim for ``--minutes`` wall minutes, beside a /clock watcher.

    hostile_soak.py [--minutes 10]

The sim: sim.launch with a Burger in the empty world at real time, on a master of its own (as
run_bench's SimRun). Each round sends, through the real /gazebo services: robots whose plugin
numbers are beyond the limits (laser <max> 1e39, IMU noise 1e200, 16385 samples, a 1e-300 m
wheel), includes of /dev/zero, /dev/stdin and a FIFO, a polyline of 3,000 corners, 2,000
ground planes, a 100 x 100 fan-out of includes, a 10 MB model name, meshes whose vertices are
1e12 m or become infinite when scaled, a spawn and delete of 20 boxes of distinct sizes and of
a 20,000-triangle mesh, NaN and 1e308 teleports, pause and unpause, reset_world. The /clock
watcher notes the longest wall time between two messages.

It prints one line a round, then ``RESULT clock_gap_s rss_start_mb rss_end_mb cpu_start
cpu_end alive rss_idle_mb rounds``. The start is after a first round (the mesh readers are
imported then, about 40 MB, and the caches filled); rss_idle_mb is before any request. CPU per
sim second: the sim's CPU seconds over 20 quiet wall seconds at the start and at the end,
divided by the sim seconds run meanwhile. make bench's ``hostile``
group runs it (not a default group: it takes --minutes plus about a minute).
Run from a shell where ``source catkin_ws/devel/setup.bash`` was done.
"""
import argparse
import math
import os
import shutil
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, os.pardir, "src"))

from run_bench import SimRun, cpu_seconds, rss_mb  # noqa: E402

QUIET = 20.0   # wall s of the CPU windows


def _sdf(body, static=True):
    return ("<sdf version='1.6'><model name='m'><static>%s</static>%s</model></sdf>"
            % ("true" if static else "false", body))


def _link(geometry):
    return ("<link name='l'><collision name='c'><geometry>%s</geometry></collision>"
            "<visual name='v'><geometry>%s</geometry></visual></link>" % (geometry, geometry))


def _model_dir(root, name, body):
    folder = os.path.join(root, name)
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "model.config"), "w") as f:
        f.write("<model><name>%s</name><sdf version='1.6'>model.sdf</sdf></model>" % name)
    with open(os.path.join(folder, "model.sdf"), "w") as f:
        f.write("<sdf version='1.6'><model name='%s'>%s</model></sdf>" % (name, body))
    return folder


def _grid_obj(path, n, z_scale=0.01):
    """An OBJ of a wavy n x n grid over 1 x 1 m: 2 n^2 triangles."""
    rows = []
    for j in range(n + 1):
        for i in range(n + 1):
            rows.append("v %.5f %.5f %.5f" % (i / n, j / n, z_scale * math.sin(i) * math.cos(j)))
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            rows.append("f %d %d %d" % (a, a + 1, a + n + 2))
            rows.append("f %d %d %d" % (a, a + n + 2, a + n + 1))
    with open(path, "w") as f:
        f.write("\n".join(rows) + "\n")
    return path


def hostile_inputs(tmp, burger):
    """[(label, service, model name, text)] of one round."""
    def robot(old, new):
        assert burger.count(old) == 1, old
        return burger.replace(old, new)
    fifo = os.path.join(tmp, "fifo.sdf")
    os.mkfifo(fifo)
    far = os.path.join(tmp, "far.obj")
    with open(far, "w") as f:
        f.write("v 0 0 0\nv 1e12 0 0\nv 0 1e12 0\nv 0 0 1e12\nf 1 3 2\nf 1 2 4\nf 1 4 3\n"
                "f 2 3 4\n")
    huge = os.path.join(tmp, "e308.obj")
    with open(huge, "w") as f:
        f.write("v 0 0 0\nv 1e308 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    box = _model_dir(tmp, "fan_box", "<static>true</static>" + _link(
        "<box><size>0.1 0.1 0.1</size></box>"))
    row = _model_dir(tmp, "fan_row", "<static>true</static>" + "".join(
        "<include><uri>%s</uri><name>b%d</name><pose>%g 0 0 0 0 0</pose></include>"
        % (box, k, 0.2 * k) for k in range(100)))
    corners = "".join("<point>%g %g</point>" % (math.cos(a), 0.5 * math.sin(a))
                      for a in (k * 2 * math.pi / 3000 for k in range(3000)))
    return [
        ("laser max 1e39", "urdf", "tb3_x", robot("<max>3.5</max>", "<max>1e39</max>")),
        ("IMU noise 1e200", "urdf", "tb3_x", robot("<gaussianNoise>0.0</gaussianNoise>",
                                                   "<gaussianNoise>1e200</gaussianNoise>")),
        ("16385 samples", "urdf", "tb3_x", robot("<samples>360</samples>",
                                                 "<samples>16385</samples>")),
        ("1e-300 m wheel", "urdf", "tb3_x", robot("<wheelDiameter>0.066</wheelDiameter>",
                                                  "<wheelDiameter>1e-300</wheelDiameter>")),
        ("include /dev/zero", "sdf", "z", _sdf("<include><uri>/dev/zero</uri></include>")),
        ("include /dev/stdin", "sdf", "z", _sdf("<include><uri>/dev/stdin</uri></include>")),
        ("include a FIFO", "sdf", "z", _sdf("<include><uri>%s</uri></include>" % fifo)),
        ("polyline of 3000 corners", "sdf", "z", _sdf(
            "<link name='l'><collision name='c'><geometry><polyline>%s<height>1</height>"
            "</polyline></geometry></collision></link>" % corners)),
        ("2000 ground planes", "sdf", "z", _sdf("".join(
            "<include><uri>model://ground_plane</uri><name>g%d</name></include>" % k
            for k in range(2000)))),
        ("fan-out 100 x 100", "sdf", "z", _sdf("".join(
            "<include><uri>%s</uri><name>r%d</name><pose>0 %g 0 0 0 0</pose></include>"
            % (row, k, 0.2 * k) for k in range(100)))),
        ("10 MB model name", "sdf", "m" * 10_000_000, _sdf("")),
        ("movable mesh of 1e12 m", "sdf", "z", _sdf(_link("<mesh><uri>%s</uri></mesh>" % far),
                                                    static=False)),
        ("mesh of 1e308 scaled by 10", "sdf", "z", _sdf(_link(
            "<mesh><uri>%s</uri><scale>10 10 10</scale></mesh>" % huge))),
    ]


def soak(minutes: float) -> dict:
    from tutorial_turtlebot.sim.files.urdf_file import urdf_path
    with open(urdf_path("burger", False)) as f:
        burger = f.read()
    tmp = tempfile.mkdtemp(prefix="hostile_soak_")
    run = SimRun(["real_time_factor:=1", "world:=empty"])
    try:
        inputs = hostile_inputs(tmp, burger)
        mesh = _grid_obj(os.path.join(tmp, "grid.obj"), 100)      # 20,000 triangles
        run.start()
        pid = run.sim_pid()
        os.environ["ROS_MASTER_URI"] = run.env["ROS_MASTER_URI"]
        return _replay(pid, minutes * 60.0, inputs, mesh)
    finally:
        run.stop()
        shutil.rmtree(tmp, ignore_errors=True)


def _replay(pid, seconds, inputs, mesh):
    import rospy
    from gazebo_msgs.msg import ModelState
    from gazebo_msgs.srv import (DeleteModel, GetWorldProperties, SetModelState, SpawnModel)
    from geometry_msgs.msg import Pose, Twist
    from rosgraph_msgs.msg import Clock
    from std_srvs.srv import Empty

    rospy.init_node("hostile_soak", anonymous=True, disable_signals=True)
    for name in ("spawn_sdf_model", "get_world_properties"):
        rospy.wait_for_service("/gazebo/" + name, timeout=60)
    spawn = {"sdf": rospy.ServiceProxy("/gazebo/spawn_sdf_model", SpawnModel),
             "urdf": rospy.ServiceProxy("/gazebo/spawn_urdf_model", SpawnModel)}
    delete = rospy.ServiceProxy("/gazebo/delete_model", DeleteModel)
    world = rospy.ServiceProxy("/gazebo/get_world_properties", GetWorldProperties)
    set_state = rospy.ServiceProxy("/gazebo/set_model_state", SetModelState)
    empties = {n: rospy.ServiceProxy("/gazebo/" + n, Empty)
               for n in ("pause_physics", "unpause_physics", "reset_world")}
    clock = {"sim": 0.0, "wall": None, "gap": 0.0, "watch": False}
    lock = threading.Lock()

    def on_clock(msg):
        now = time.monotonic()
        with lock:
            if clock["wall"] is not None and clock["watch"]:
                clock["gap"] = max(clock["gap"], now - clock["wall"])
            clock["wall"], clock["sim"] = now, msg.clock.to_sec()
    rospy.Subscriber("/clock", Clock, on_clock, queue_size=100)

    def cpu_per_sim_second():
        time.sleep(2.0)
        cpu0, sim0 = cpu_seconds(pid), clock["sim"]
        time.sleep(QUIET)
        return (cpu_seconds(pid) - cpu0) / max(clock["sim"] - sim0, 1e-9)

    def call(service, *args):
        try:
            return service(*args)
        except rospy.ServiceException as err:
            return err

    box_pose = Pose()
    box_pose.position.x, box_pose.position.y, box_pose.position.z = 3.0, 3.0, 0.5
    box_pose.orientation.w = 1.0
    result = {"rss_idle": rss_mb(pid)}
    clock["watch"] = True
    start, rounds = time.monotonic(), 0
    while rounds == 0 or time.monotonic() - start < seconds:
        if rounds == 1:   # after one round: the mesh readers imported, the caches warm
            clock["watch"] = False
            result["rss_start"], result["cpu_start"] = rss_mb(pid), cpu_per_sim_second()
            clock["watch"] = True
            start = time.monotonic()
        rounds += 1
        took = time.monotonic()
        for label, kind, name, text in inputs:
            answer = call(spawn[kind], name, text, "", box_pose, "world")
            if getattr(answer, "success", False):
                call(delete, name)
                print("  accepted: %s" % label, flush=True)
        for k in range(20):                       # 20 distinct sizes, the same each round
            size = 0.1 + 0.01 * k
            box = _sdf(_link("<box><size>%g %g %g</size></box>" % (size, size, size)))
            call(spawn["sdf"], "box", box, "", box_pose, "world")
            call(delete, "box")
        call(spawn["sdf"], "grid", _sdf(_link("<mesh><uri>%s</uri></mesh>" % mesh)), "",
             box_pose, "world")
        call(delete, "grid")
        for value in (float("nan"), 1e308):
            bad = Pose()
            bad.position.x, bad.orientation.w = value, 1.0
            call(set_state, ModelState("ground_plane", bad, Twist(), "world"))
        call(empties["pause_physics"])
        call(empties["unpause_physics"])
        call(empties["reset_world"])
        print("round %d: %.1f s, sim RSS %.1f MB, longest /clock gap so far %.2f s"
              % (rounds, time.monotonic() - took, rss_mb(pid), clock["gap"]), flush=True)
    clock["watch"] = False
    result["cpu_end"] = cpu_per_sim_second()
    result["rss_end"] = rss_mb(pid)
    result["gap"] = clock["gap"]
    answer = call(world)
    result["alive"] = bool(getattr(answer, "success", False))
    result["rounds"] = rounds
    print("RESULT %.2f %.1f %.1f %.4f %.4f %s %.1f %d" % (
        result["gap"], result["rss_start"], result["rss_end"], result["cpu_start"],
        result["cpu_end"], "alive" if result["alive"] else "DEAD", result["rss_idle"], rounds),
        flush=True)
    rospy.signal_shutdown("hostile soak done")
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--minutes", type=float, default=10.0, help="wall minutes of replay")
    args = parser.parse_args()
    soak(args.minutes)


if __name__ == "__main__":
    main()
