#!/usr/bin/env python3
"""``make bench``: launch the real sim with roslaunch and measure it; print one table.

Each figure is the median of ``--runs`` runs (default 3). Run from a shell where
``source catkin_ws/devel/setup.bash`` was done (make bench does it). Every run starts its own
master on a free port, so nothing else on the machine is disturbed.

Measured (Burger in turtlebot3_world unless said):
  start-up          roslaunch sim.launch (roscore included) -> first /scan, wall s; floor:
                    roslaunch of a launch file with one parameter and no node -> the
                    parameter set (roslaunch's and roscore's own start-up); a second
                    `make demo`: `make setup` with nothing changed (no catkin build), then
                    the same roslaunch -> first /scan
  real time         real_time_factor 1, every sensor subscribed from another process:
                    achieved factor, sim CPU (% of one core), sim memory (RSS, MB); floor:
                    Simulation.step paced as the node paces it, no ROS (alone; with every
                    sensor computed): CPU
  jitter            the same: per topic, how far the gap between two arrivals differs from
                    the gap between their stamps (p50, p99, max in ms; bench/jitter.py)
  nav               bench/nav_load.py: the sim at real time under the SLAM and Navigation
                    chapters' clients (gmapping; map_server, amcl and move_base), the Burger
                    turning in place in turtlebot3_world: sim CPU and achieved factor (skipped,
                    in one row, without the navigation extra)
  fast              real_time_factor 0, every sensor subscribed / only /odom: achieved factor;
                    with every sensor, the loop's wall time per sim second split by part
                    (gazebo/part_times.py): physics (stepping), sensors (rays, IMU, odometry,
                    wheels, camera), building (genpy messages filled), serializing (bytes
                    made), sending (socket writes), other (requests, pacing, the loop)
  physics bound     the same world and robot stepped by pybullet with no ROS (and no sensors),
                    measured just before and just after each fast run; ceilings: what the node
                    could reach if ROS cost nothing (Simulation.step alone; with every sensor
                    computed), as shares of the bound
  world API         every sensor and /gazebo/model_states subscribed (CPU at real time, factor
                    as fast as possible); spawn and delete round trips; stage 1 with a
                    turtlebot3_dqn-style client: environment steps per wall second; floor:
                    the same client's steps against a bare 1 kHz /scan node (scan_source.py)
  scaling           real_time_factor 0, 1 / 4 / 8 subscribers to /scan: achieved factor
  meshes            turtlebot3_world as Gazebo users have it (test/fixtures: the world file that
                    includes model://turtlebot3_world, whose walls and hexagons are Collada
                    meshes, found through GAZEBO_MODEL_PATH): start-up and as fast as possible
                    with every sensor subscribed, beside the same rows of the built-in world
                    (its primitive-shape copy, the default)
  meshworld         a generated world of 110 textured Collada models (bench/mesh_world.py,
                    found through GAZEBO_MODEL_PATH) beside the built-in turtlebot3_world: start-up
                    -> first /scan with an empty mesh cache (ROS_HOME a new temporary folder) and
                    again with the cache the first start filled, the second start's ratio to the
                    built-in world's; CPU s per sim s of Simulation.step (physics alone; and
                    with every sensor computed), no ROS, the two worlds stepped in turns in one
                    process, and their ratio
  meshcamera        the Waffle Pi's camera (640 x 480, 30 Hz) in meshworld's generated world
                    beside the built-in turtlebot3_world: CPU ms per image without ROS, the
                    two worlds drawn in turns in one process, their ratio, and the generated
                    world's again with every body drawn (no view culling: engine/view_culling);
                    the sim node in the generated world at real time with the camera
                    subscribed from another process: achieved factor, images per sim second
                    (frames the loop could not draw in time are skipped), sim CPU; floor:
                    the same with only /odom subscribed (no image drawn), in turns with it
  multi             three Burgers in turtlebot3_house (multi_turtlebot3.launch) with every
                    sensor of each and /tf subscribed: sim CPU at real time, factor as fast as
                    possible; 1, 2, 4, 8 Burgers spawned into the empty world (the sim node
                    alone, bench/multi_robot.py): the same two figures, and the same robots
                    stepped without ROS (physics alone; physics and every sensor computed)

  learning          the learning environments without ROS (bench/learning_speed.py): stage 1
                    with one StageEnv (seeded random actions, reset at a collision or after
                    500 steps): env steps per wall second, and its physics bound (the same
                    world, robot and step size in bare pybullet replaying the env's very
                    physics: its wheel commands before the same physics steps, its resets,
                    the obstacles' ticks, one batch of the 24 rays per env step; no
                    Simulation, drive, observation or reward), measured in turns; the vector
                    env (learning/vector.py) with one worker per core against one env in
                    turns, and Gymnasium's AsyncVectorEnv (one env per core) beside it;
                    0.005 and 0.01 s physics steps against 0.0025 s, and how far the final
                    pose of 100 scripted env steps moves (open field; into a wall); stage 3
                    (its moving obstacle) and its bound; ms per render() ("rgb_array": the
                    top-down picture; the Waffle Pi's camera) against ms per env step

  soak              bench/soak.py: 30 sim minutes as fast as possible with four Burgers, every
                    topic subscribed, spawns and deletes, resets, NaN and 1e9 cmd_vel, pauses:
                    sim RSS at the start and the end, growth over the last third (not in the
                    default groups: it takes 15 to 20 wall minutes)

  hostile           bench/hostile_soak.py: the hostile requests that once killed, froze or
                    choked the sim, replayed for 20 wall minutes against one sim at real time
                    beside three processes flooding /gazebo/set_model_state and a /scan
                    client: alive at the end, the longest wall gap between two /clock
                    messages, sim RSS, threads and CPU per sim second at the start and the
                    end, the client's /scan rate (not in the default groups: it takes about
                    22 minutes)

``--only GROUP[,GROUP]`` runs some groups of rows (startup, realtime, nav, jitter, fast, world,
subscribers, camera, render, meshes, meshworld, meshcamera, multi, learning, soak, hostile); the
default is all of them but soak and hostile.
"""
import argparse
import contextlib
import os
import signal
import statistics
import subprocess
import sys
import time
from typing import Any, Callable, NamedTuple, Tuple

HERE = os.path.dirname(os.path.abspath(__file__))
FIXTURES = os.path.join(HERE, os.pardir, "test", "fixtures")
MESH_WORLD = os.path.abspath(os.path.join(FIXTURES, "worlds", "turtlebot3_world_meshes.world"))
MESH_MODELS = os.path.abspath(os.path.join(FIXTURES, "gazebo_models"))
sys.path.insert(0, os.path.join(HERE, os.pardir, "src"))
sys.path.insert(0, os.path.join(HERE, os.pardir, "test"))
from process_helpers import (cpu_seconds, free_port, rss_kb, signal_process,  # noqa: E402,F401
                             stop_process, wait_for, node_on_master)

STOP_WAIT = 15.0   # wall s a process has to end after SIGINT before SIGTERM and SIGKILL

ALL_SENSORS = ["/scan", "/odom", "/imu", "/joint_states", "/tf"]
# gazebo/part_times.py's parts, as rows (idle is 0 as fast as possible)
PART_ROWS = ("physics", "sensors", "building", "serializing", "sending", "other")
TARGETS = {
    "startup": "<= 1.0 s",
    "startup_warm_demo": "<= start-up + 3 s",
    "rt_cpu": "<= 4 %",
    "rt_mem": "<= 200 MB",
    "fast_all": ">= 20x",
    "fast_all_bound": ">= 0.6",
    "fast_odom_bound": ">= 0.8",
    "rt_cpu_states": "<= 12 %",
    "multi_rt_cpu": "<= 10 %",
    "multi_fast": ">= 20x",
    "stage": ">= 100/s",
    "meshworld_second": "<= 2",
    "meshworld_physics": "<= 1.3",
    "meshcamera_ratio": "<= 1.5",
    "meshcamera_rtf": ">= 0.95",
    "learning_bound": ">= 0.85",
    "learning_vector": ">= 1.7",
}


class SimRun:
    """One roslaunch of sim.launch on its own master, plus helper processes."""

    def __init__(self, launch_args, model="burger", world="turtlebot3_world",
                 launch="sim.launch", env=None):
        self.port = free_port()
        self.env = dict(os.environ, ROS_MASTER_URI="http://localhost:%d" % self.port,
                        **(env or {}))
        self.launch_file = launch
        self.args = (["model:=%s" % model, "status_period:=0"] + launch_args
                     + (["world:=%s" % world] if launch == "sim.launch" else []))
        self.procs = []
        self.launch = None

    def start_helper(self, script, *args, stdin=None):
        proc = subprocess.Popen([sys.executable, os.path.join(HERE, script)] + list(args),
                                env=self.env, stdin=stdin, stdout=subprocess.PIPE,
                                stderr=subprocess.DEVNULL, text=True, start_new_session=True)
        self.procs.append(proc)
        return proc

    def start(self):
        self.launch = subprocess.Popen(
            ["roslaunch", "-p", str(self.port)]
            + ([] if os.path.isabs(self.launch_file) else ["tutorial_turtlebot"])
            + [self.launch_file] + self.args,
            env=self.env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
            start_new_session=True)
        self.procs.append(self.launch)

    def sim_pid(self, timeout=30.0):
        """The pid of this run's sim node, waiting up to ``timeout`` wall s for it."""
        pid = wait_for(self._find_sim, timeout, 0.2)
        if pid is None:
            raise RuntimeError("sim process not found")
        return pid

    def _find_sim(self):
        """The pid of the node named gazebo on this run's master (None if none yet)."""
        return node_on_master("gazebo", self.port)

    def stop(self):
        """SIGINT to every process group at once (roslaunch and the helpers end together),
        then stop_process each (SIGTERM, SIGKILL if it has not ended within STOP_WAIT s)."""
        for proc in reversed(self.procs):
            signal_process(proc, signal.SIGINT)
        for proc in reversed(self.procs):
            stop_process(proc, STOP_WAIT, sig=None)


def rss_mb(pid) -> float:
    """Resident memory of process ``pid`` (MB; NaN if it has none)."""
    kb = rss_kb(pid)
    return float("nan") if kb is None else kb / 1024.0


def read_report(proc):
    """Next 'wall sim messages topics_heard' line of a subscribers.py process, as
    (wall, sim, messages, topics_heard) (other lines skipped)."""
    for line in proc.stdout:
        fields = line.split()
        if len(fields) == 4:
            try:
                return float(fields[0]), float(fields[1]), int(fields[2]), int(fields[3])
            except ValueError:
                continue
    raise RuntimeError("subscriber process ended")


def mesh_world_run(launch_args=()):
    """SimRun keywords of the mesh turtlebot3_world at the built-in one's spawn."""
    return dict(launch_args=["x_pos:=-2.0", "y_pos:=-0.5"] + list(launch_args),
                world=MESH_WORLD, env={"GAZEBO_MODEL_PATH": MESH_MODELS})


def measure_startup(**run_args) -> float:
    run = SimRun(**dict({"launch_args": []}, **run_args))
    try:
        probe = run.start_helper("first_scan.py")
        time.sleep(1.5)  # its imports are done; it now waits for the master
        t0 = time.time()
        run.start()
        for line in probe.stdout:  # rospy may first say it is waiting for the master
            try:
                return float(line) - t0
            except ValueError:
                continue
        raise RuntimeError("no /scan arrived")
    finally:
        run.stop()


def measure_warm_demo() -> float:
    """A second `make demo` with nothing changed, up to the sim's first /scan: the set-up's
    run (make setup: every check, no catkin build), then roslaunch as measure_startup."""
    t0 = time.time()
    subprocess.run(["make", "-s", "-C", os.path.join(HERE, os.pardir), "setup"], check=True,
                   stdout=subprocess.DEVNULL)
    return time.time() - t0 + measure_startup()


def read_part_times(path):
    """(sim s, {part: s}) of the sim's part-times file (gazebo/part_times.py)."""
    from tutorial_turtlebot.gazebo.part_times import read_line
    for _ in range(50):
        try:
            with open(path) as f:
                return read_line(f.read())
        except (OSError, ValueError):   # not written yet, or being rewritten
            time.sleep(0.05)
    raise RuntimeError("the sim wrote no part times to %s" % path)


def measure_running(rtf, topics, seconds=8.0, warmup=3.0, model="burger", mesh_world=False,
                    parts=None, world=None, world_env=None):
    """(achieved factor, sim CPU % of one core, sim RSS MB, messages per sim second) with
    ``topics`` subscribed; ``mesh_world``: in the mesh turtlebot3_world; ``world``: in that
    world file, with ``world_env`` (GAZEBO_MODEL_PATH ...). ``parts``: a dict filled with the
    loop's ms per sim second by part over the same window."""
    import tempfile
    rate = ["real_time_factor:=%g" % rtf]
    parts_file = tempfile.NamedTemporaryFile(prefix="bench_parts_", delete=False).name
    env = {"TUTORIAL_TURTLEBOT_PART_TIMES": parts_file}
    run = (SimRun(model=model, **dict(mesh_world_run(rate), env=dict(
        mesh_world_run(rate)["env"], **env))) if mesh_world
           else SimRun(rate, model=model, world=world, env=dict(world_env or {}, **env))
           if world is not None else SimRun(rate, model=model, env=env))
    try:
        run.start()
        subs = run.start_helper("subscribers.py", *topics)
        pid = run.sim_pid()
        # wait until the clock runs and the subscribers are connected
        deadline = time.time() + 60
        while read_report(subs)[1] <= 0.0 and time.time() < deadline:
            pass
        end_warmup = time.time() + warmup
        while time.time() < end_warmup:
            read_report(subs)
        wall0, sim0, count0, _ = read_report(subs)
        cpu0 = cpu_seconds(pid)
        parts0 = read_part_times(parts_file)
        samples = int(seconds)
        for _ in range(samples):
            wall1, sim1, count1, _ = read_report(subs)
        cpu1 = cpu_seconds(pid)
        parts1 = read_part_times(parts_file)
        if parts is not None:
            span = parts1[0] - parts0[0]
            parts.update({k: 1000.0 * (parts1[1][k] - parts0[1][k]) / span for k in parts1[1]})
        mem = rss_mb(pid)
        return ((sim1 - sim0) / (wall1 - wall0), 100.0 * (cpu1 - cpu0) / (wall1 - wall0), mem,
                (count1 - count0) / (sim1 - sim0))
    finally:
        run.stop()
        os.unlink(parts_file)


JITTER_TOPICS = ["/clock", "/imu", "/odom", "/joint_states", "/scan"]


def measure_jitter(seconds=10.0, warmup=3.0):
    """{topic: (p50, p99, max)} of the arrival-interval error (ms of wall time, see jitter.py)
    at real time with every sensor subscribed from another process."""
    run = SimRun(["real_time_factor:=1"])
    try:
        run.start()
        subs = run.start_helper("subscribers.py", *ALL_SENSORS)
        run.sim_pid()
        deadline = time.time() + 60
        while read_report(subs)[1] <= 0.0 and time.time() < deadline:
            pass
        time.sleep(warmup)
        probe = run.start_helper("jitter.py", "%g" % seconds, *JITTER_TOPICS)
        result = {}
        for line in probe.stdout:
            fields = line.split()
            if len(fields) == 5 and fields[0] in JITTER_TOPICS:
                result[fields[0]] = tuple(float(v) for v in fields[2:])
        return result
    finally:
        run.stop()


def measure_world_calls(count=20):
    """(spawn ms, delete ms): median wall time of a service round trip from another process."""
    run = SimRun([])
    try:
        run.start()
        run.sim_pid()
        probe = run.start_helper("world_calls.py", str(count))
        for line in probe.stdout:
            fields = line.split()
            if len(fields) == 2:
                return float(fields[0]), float(fields[1])
        raise RuntimeError("world_calls.py said nothing")
    finally:
        run.stop()


def measure_stage_client(seconds=20.0):
    """Environment steps per wall second of a turtlebot3_dqn-style client (one step per scan,
    reset_simulation and a goal respawned every episode) on stage 1, 24 samples, as fast as
    possible."""
    run = SimRun(["real_time_factor:=0", "lidar_samples:=24"], launch="turtlebot3_stage_1.launch")
    try:
        run.start()
        run.sim_pid()
        probe = run.start_helper("stage_client.py", "%g" % seconds)
        for line in probe.stdout:
            try:
                return float(line)
            except ValueError:
                continue
        raise RuntimeError("stage_client.py said nothing")
    finally:
        run.stop()


def step_outputs(sim, due) -> None:
    """Compute every output of ``due`` (Simulation.step's list) as the node does for a
    subscriber: scan, odom, imu, joint_states (world outputs such as the clock cost nothing)."""
    for robot, name in due:
        if robot is not None:
            getattr(robot, name)()


def stepping_factors(sim, runs, wall_seconds, rounds=3):
    """Real-time factor of each of ``runs`` (callables that each advance ``sim`` by one step),
    no ROS. They take turns in ``rounds`` rounds over ``wall_seconds`` in all, so that a drift
    of the machine's speed falls on each alike."""
    sim_s, wall_s = [0.0] * len(runs), [0.0] * len(runs)
    slot = wall_seconds / (rounds * len(runs))
    for _ in range(rounds):
        for k, run in enumerate(runs):
            t0 = time.perf_counter()
            while time.perf_counter() - t0 < slot:
                for _ in range(80):   # 0.2 s of sim time: whole scan periods
                    run()
                sim_s[k] += 80 * sim.config.time_step
            wall_s[k] += time.perf_counter() - t0
    return tuple(s / w for s, w in zip(sim_s, wall_s))


def sim_bounds(wall_seconds=6.0):
    """Real-time factors, no ROS, Burger in turtlebot3_world standing at its spawn with the
    brake on, as in the fast runs (nothing sends cmd_vel there): (pybullet's step alone,
    Simulation.step (the drive, IMU filter and schedules too), Simulation.step with every output
    computed as it falls due). The last two are what the node could reach with ROS costing
    nothing: the ceilings under the only-/odom and every-sensor rows."""
    from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
    sim = Simulation(SimConfig(model="burger", world="turtlebot3_world"))
    try:
        for _ in range(400):   # 1 s of sim time: settled on its wheels, the brake on
            sim.step()
        return stepping_factors(sim, (lambda: sim.physics.step(), lambda: sim.step(),
                                      lambda: step_outputs(sim, sim.step())), wall_seconds)
    finally:
        sim.close()


def paced_floor(seconds=8.0):
    """(CPU % of one core: physics alone, physics and every sensor) of the Simulation paced at
    real time as the node paces it (Pacer.MIN_SLEEP of sim time stepped at once, then a sleep),
    with no ROS: the floor under the real-time CPU row on this machine."""
    from tutorial_turtlebot.sim.world.pacing import Pacer
    from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
    sim = Simulation(SimConfig(model="burger", world="turtlebot3_world"))
    try:
        batch = int(round(Pacer.MIN_SLEEP / sim.config.time_step))
        cpu = []
        for sensors in (False, True):
            wall0, cpu0 = time.monotonic(), time.process_time()
            while time.monotonic() - wall0 < seconds:
                start = time.monotonic()
                for _ in range(batch):
                    due = sim.step()
                    if sensors:
                        step_outputs(sim, due)
                time.sleep(max(0.0, start + Pacer.MIN_SLEEP - time.monotonic()))
            cpu.append(100.0 * (time.process_time() - cpu0) / (time.monotonic() - wall0))
        return tuple(cpu)
    finally:
        sim.close()


class BareMaster:
    """roslaunch of a launch file that sets one parameter and starts no node, on its own port:
    roslaunch's and roscore's own start-up, and a master for helpers that need no sim."""

    def __init__(self):
        import tempfile
        self.port = free_port()
        self.env = dict(os.environ, ROS_MASTER_URI="http://localhost:%d" % self.port)
        fd, self.launch_file = tempfile.mkstemp(suffix=".launch", prefix="bench_bare_")
        with os.fdopen(fd, "w") as f:
            f.write('<launch><param name="/bench_ready" value="1"/></launch>\n')
        self.proc = None

    def start(self, timeout=30.0) -> float:
        """Start it; the wall s until the master answers with the parameter set."""
        import xmlrpc.client
        t0 = time.time()
        self.proc = subprocess.Popen(["roslaunch", "-p", str(self.port), self.launch_file],
                                     env=self.env, stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL, start_new_session=True)
        master = xmlrpc.client.ServerProxy("http://localhost:%d" % self.port)
        while time.time() - t0 < timeout:
            try:
                if master.getParam("/bench", "/bench_ready")[0] == 1:
                    return time.time() - t0
            except OSError:
                pass
            time.sleep(0.002)
        raise RuntimeError("roslaunch set no parameter within %g s" % timeout)

    def stop(self):
        if self.proc is not None:
            stop_process(self.proc, STOP_WAIT)
        os.unlink(self.launch_file)


def measure_roslaunch_floor() -> float:
    """Wall s from roslaunch's start to its master holding a parameter, with no node: the part
    of the start-up row that is roslaunch and roscore alone."""
    bare = BareMaster()
    try:
        return bare.start()
    finally:
        bare.stop()


def measure_stage_client_floor(seconds=10.0) -> float:
    """Steps per wall second of stage_client.py's step (publish an action, wait_for_message for
    the next scan) against bench/scan_source.py, a bare rospy node publishing 24-ray scans at
    1 kHz of wall time, with no sim: how fast such a client can step at all."""
    bare = BareMaster()
    procs = []
    try:
        bare.start()
        for args in (["scan_source.py"], ["stage_client.py", "%g" % seconds, "--steps-only"]):
            procs.append(subprocess.Popen(
                [sys.executable, os.path.join(HERE, args[0])] + args[1:], env=bare.env,
                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                start_new_session=True))
        for line in procs[1].stdout:
            try:
                return float(line)
            except ValueError:
                continue
        raise RuntimeError("stage_client.py --steps-only said nothing")
    finally:
        for proc in procs:
            stop_process(proc, STOP_WAIT)
        bare.stop()


def measure_fast():
    """One run of the as-fast-as-possible rows: {"all", "odom": achieved factors with every
    sensor / only /odom subscribed; "parts": the loop's ms per sim s by part (every sensor);
    "bound", "stepped", "with_sensors": sim_bounds' factors, the mean of a measure just before
    and one just after, so that the machine's drift in between falls on both sides}."""
    before = sim_bounds()
    parts = {}
    result = {"all": measure_running(0, ALL_SENSORS, parts=parts)[0],
              "odom": measure_running(0, ["/odom"])[0], "parts": parts}
    after = sim_bounds()
    for k, name in enumerate(("bound", "stepped", "with_sensors")):
        result[name] = (before[k] + after[k]) / 2
    return result


ROBOT_SENSORS = ("scan", "odom", "imu", "joint_states")
HOUSE_ROBOTS = ("tb3_0", "tb3_1", "tb3_2")   # multi_turtlebot3.launch's namespaces
HOUSE_POSES = ((-7.0, -1.0, 1.57), (7.0, -1.0, 1.57), (0.5, 3.0, 0.0))  # and its poses
ROBOT_COUNTS = (1, 2, 4, 8)


def robot_topics(namespaces):
    """Every sensor topic of each robot, and the shared /tf."""
    return ["/%s/%s" % (ns, topic) for ns in namespaces for topic in ROBOT_SENSORS] + ["/tf"]


def window(subs, pid, seconds, warmup):
    """(achieved factor, sim CPU % of one core, messages per sim second) over ``seconds``
    reports of ``subs`` after ``warmup`` wall seconds."""
    end_warmup = time.time() + warmup
    while time.time() < end_warmup:
        read_report(subs)
    wall0, sim0, count0, _ = read_report(subs)
    cpu0 = cpu_seconds(pid)
    for _ in range(int(seconds)):
        wall1, sim1, count1, _ = read_report(subs)
    cpu1 = cpu_seconds(pid)
    return ((sim1 - sim0) / (wall1 - wall0), 100.0 * (cpu1 - cpu0) / (wall1 - wall0),
            (count1 - count0) / max(sim1 - sim0, 1e-9))


def wait_heard(subs, topics, timeout=60.0):
    """Until every one of ``topics`` has delivered a message (the robots are all up)."""
    deadline = time.time() + timeout
    while time.time() < deadline:
        if read_report(subs)[3] >= len(topics):
            return
    raise RuntimeError("not every topic of %s delivered within %g s" % (topics, timeout))


def tell(helper, command):
    """Send ``command`` to bench/multi_robot.py and read up to its answer (rospy may say
    other things first); RuntimeError with its line if it reports an error or ends."""
    helper.stdin.write(command + "\n")
    helper.stdin.flush()
    word = command.split()[0]
    word = "spawned" if word == "spawn" else word
    for line in helper.stdout:
        if line.startswith(word):
            return
        if line.startswith("error"):
            raise RuntimeError("multi_robot.py: %s" % line.strip())
    raise RuntimeError("multi_robot.py ended before answering %r" % command)


def measure_both(run, helper, topics, seconds, warmup):
    """With the sim of ``run`` running at real time: subscribe ``topics`` from a new process,
    measure; switch to as fast as possible, measure; back to real time. ((factor, CPU %,
    messages per sim s) at real time, the same as fast as possible)."""
    subs = run.start_helper("subscribers.py", *topics)
    try:
        pid = run.sim_pid()
        wait_heard(subs, topics)
        real_time = window(subs, pid, seconds, warmup)
        tell(helper, "fast")
        fast = window(subs, pid, seconds, warmup)
        tell(helper, "realtime")
        return real_time, fast
    finally:
        os.killpg(subs.pid, signal.SIGKILL)  # it only counts: nothing to shut down cleanly
        subs.wait()
        run.procs.remove(subs)


def measure_house(seconds=4.0, warmup=1.0):
    """multi_turtlebot3.launch (three Burgers in the house, each with robot_state_publisher),
    every sensor of all three and /tf subscribed: ((factor, sim CPU %, messages per sim s) at
    real time, the same as fast as possible). The pace is switched as Gazebo's is, by
    set_physics_properties (max_update_rate 0), which sets what real_time_factor:=0 sets."""
    run = SimRun(["real_time_factor:=1"], launch="multi_turtlebot3.launch")
    try:
        run.start()
        helper = run.start_helper("multi_robot.py", stdin=subprocess.PIPE)
        return measure_both(run, helper, robot_topics(HOUSE_ROBOTS), seconds, warmup)
    finally:
        run.stop()


EMPTY_SIM_LAUNCH = """<launch>
  <arg name="model" default="burger"/>
  <arg name="status_period" default="0"/>
  <arg name="real_time_factor" default="1.0"/>
  <param name="/use_sim_time" value="true"/>
  <node name="gazebo" pkg="tutorial_turtlebot" type="sim" required="true">
    <param name="world" value="empty"/>
    <param name="spawn_robot" value="false"/>
    <param name="real_time_factor" value="$(arg real_time_factor)"/>
    <param name="status_period" value="$(arg status_period)"/>
  </node>
</launch>
"""


def measure_scaling(seconds=4.0, warmup=1.0):
    """The sim node alone in the empty world; Burgers spawned by bench/multi_robot.py, 1, then
    up to 2, 4, 8; at each count every sensor of each and /tf subscribed from a new process:
    {count: ((factor, CPU %, messages per sim s) at real time, the same as fast as possible
    (set_physics_properties, max_update_rate 0))}."""
    import tempfile
    with tempfile.NamedTemporaryFile("w", suffix=".launch", prefix="bench_empty_sim_",
                                     delete=False) as f:
        f.write(EMPTY_SIM_LAUNCH)
    run = SimRun(["real_time_factor:=1"], launch=f.name)
    results = {}
    try:
        run.start()
        helper = run.start_helper("multi_robot.py", stdin=subprocess.PIPE)
        for count in ROBOT_COUNTS:
            tell(helper, "spawn %d" % count)
            results[count] = measure_both(run, helper,
                                          robot_topics(["tb3_%d" % i for i in range(count)]),
                                          seconds, warmup)
        return results
    finally:
        run.stop()
        os.unlink(f.name)


def robots_bound(count, world="empty", poses=None, wall_seconds=3.0):
    """(physics alone, physics and sensors): real-time factors of ``count`` Burgers in
    ``world`` at ``poses`` ((x, y, yaw) each; default: bench/multi_robot.py's grid) stepped by
    Simulation.step with no ROS; for the second, every output that falls due is also computed
    (scan, odom, imu, joint_states), as the node computes it for a subscriber."""
    import math
    from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
    from tutorial_turtlebot.sim.files.urdf.urdf_file import read_urdf, urdf_path
    from multi_robot import grid_pose
    if poses is None:
        poses = [(p.x, p.y, 0.0) for p in (grid_pose(i).position for i in range(count))]
    sim = Simulation(SimConfig(world=world, spawn_robot=False))
    try:
        description = read_urdf(urdf_path("burger"))
        for i, (x, y, yaw) in enumerate(poses):
            sim.add_robot("tb3_%d" % i, "tb3_%d" % i, description,
                          ((x, y, 0.0), (0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2))))
        for _ in range(400):  # 1 s of sim time: the robots settle on their wheels
            sim.step()
        return stepping_factors(sim, (lambda: sim.step(), lambda: step_outputs(sim, sim.step())),
                                wall_seconds)
    finally:
        sim.close()


def render_times(frames=10):
    """Median ms per rendered frame at each RESOLUTIONS size, with EGL (where it loads) and
    with TinyRenderer, from the Waffle Pi's camera pose at the turtlebot3_world spawn."""
    from tutorial_turtlebot.sim.engine.rendering import CameraRenderer
    from tutorial_turtlebot.sim.files.plugins.robot_plugin_types import CameraSpec
    from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
    results = {}
    pose = None  # the camera's optical frame in the world: (position, 3x3 rotation)
    for camera in (True, False):  # True: the sim loads EGL for its camera; False: none
        sim = Simulation(SimConfig(model="waffle_pi", camera=camera))
        try:
            if pose is None:  # the same spawn in both runs; only the first has the camera
                pose = sim.robot.camera_pose()
            for width, height, hfov in RESOLUTIONS:
                renderer = CameraRenderer(sim.physics.client, CameraSpec(width, height, hfov, 30.0),
                                          use_egl=sim.physics.egl)
                renderer.render(*pose)
                times = []
                for _ in range(frames if (sim.physics.egl or width < 1000) else 3):
                    t0 = time.perf_counter()
                    renderer.render(*pose)
                    times.append(time.perf_counter() - t0)
                results[(renderer.renderer_name, width, height)] = 1000 * median(times)
        finally:
            sim.close()
    return results


RESOLUTIONS = ((160, 120, 1.085595), (320, 240, 1.085595), (640, 480, 1.085595),
               (1920, 1080, 1.3439))


def median(values):
    return statistics.median(values)


def measure_soak():
    """bench/soak.py's last line: (RSS MB at the start, at the end, growth over the last
    third)."""
    import re
    out = subprocess.run([sys.executable, os.path.join(HERE, "soak.py")], stdout=subprocess.PIPE,
                         stderr=subprocess.DEVNULL, text=True, check=False).stdout
    found = re.search(r"RSS ([\d.]+) MB at the first sample, ([\d.]+) MB at the end; over the "
                      r"last third \([^)]*\) it grew (-?[\d.]+) MB", out)
    if not found:
        raise RuntimeError("soak.py gave no result: %s" % out[-500:])
    return tuple(float(v) for v in found.groups())


def measure_hostile(minutes=20.0):
    """bench/hostile_soak.py's RESULT line: {gap, rss_start, rss_end, cpu_start, cpu_end,
    alive, rss_idle, rounds, threads_start, threads_end, scan_hz}."""
    out = subprocess.run([sys.executable, os.path.join(HERE, "hostile_soak.py"), "--minutes",
                          str(minutes)], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                         text=True, check=False).stdout
    line = [text for text in out.splitlines() if text.startswith("RESULT ")]
    if not line:
        raise RuntimeError("hostile_soak.py gave no result: %s" % out[-500:])
    fields = line[-1].split()[1:]
    keys = ("gap", "rss_start", "rss_end", "cpu_start", "cpu_end")
    result = dict(zip(keys, (float(v) for v in fields[:5])))
    result["alive"] = fields[5] == "alive"
    result["rss_idle"], result["rounds"] = float(fields[6]), int(fields[7])
    result["threads_start"], result["threads_end"] = int(fields[8]), int(fields[9])
    result["scan_hz"] = float(fields[10])
    return result


def startup_rows(runs, row):
    """The startup group: roslaunch -> first /scan, its floor, and a second make demo."""
    row("start-up: roslaunch (with roscore) -> first /scan",
        "%.2f" % median([measure_startup() for _ in range(runs)]), "s", TARGETS["startup"])
    row("  floor: roslaunch (with roscore), no node -> a parameter set",
        "%.2f" % median([measure_roslaunch_floor() for _ in range(runs)]), "s")
    row("start-up, a second make demo: make setup + roslaunch -> first /scan",
        "%.2f" % median([measure_warm_demo() for _ in range(runs)]), "s",
        TARGETS["startup_warm_demo"])


def realtime_rows(runs, row):
    """The realtime group: factor, CPU and memory at real time, and the paced floor."""
    rt = [measure_running(1.0, ALL_SENSORS) for _ in range(runs)]
    row("real time, every sensor subscribed: achieved factor",
        "%.2f" % median([r[0] for r in rt]), "x")
    row("real time, every sensor subscribed: sim CPU",
        "%.1f" % median([r[1] for r in rt]), "% core", TARGETS["rt_cpu"])
    row("real time, every sensor subscribed: sim memory (RSS)",
        "%.0f" % median([r[2] for r in rt]), "MB", TARGETS["rt_mem"])
    floors = [paced_floor() for _ in range(runs)]
    row("  floor: Simulation.step paced as the node paces it, no ROS: CPU",
        "%.1f" % median([f[0] for f in floors]), "% core")
    row("  floor: the same with every sensor computed: CPU",
        "%.1f" % median([f[1] for f in floors]), "% core")


def nav_rows(runs, row):
    """The nav group: the sim's CPU at real time with gmapping or the navigation stack running
    on it (bench/nav_load.py), beside the every-sensor row; skipped without the extra."""
    import nav_load
    env = nav_load.nav_env()
    if env is None:
        row("real time, gmapping / navigation stack running: sim CPU", "skipped", "",
            "the navigation extra is not installed: bash tools/install_extra.sh nav")
        return
    for kind, label in (("slam", "gmapping (turtlebot3_slam.launch)"),
                        ("nav", "map_server, amcl, move_base (turtlebot3_navigation.launch)")):
        figures = [nav_load.measure(kind, env) for _ in range(runs)]
        row("real time, %s: sim CPU" % label, "%.1f" % median([f[1] for f in figures]),
            "% core")
        row("  the same: achieved factor", "%.2f" % median([f[0] for f in figures]), "x")


def jitter_rows(runs, row):
    """The jitter group: each topic's arrival-interval error at real time."""
    jitter = [measure_jitter() for _ in range(runs)]
    for topic in JITTER_TOPICS:
        row("real time, %s arrival-interval error p50 / p99 / max" % topic,
            " / ".join("%.1f" % median([j[topic][k] for j in jitter if topic in j])
                       for k in range(3)), "ms", "each <= 5 ms of its moment")


def fast_rows(runs, row):
    """The fast group's first rows (factor and loop parts); returns the runs for
    fast_bound_rows."""
    fast = [measure_fast() for _ in range(runs)]
    row("as fast as possible, every sensor subscribed",
        "%.1f" % median([f["all"] for f in fast]), "x", TARGETS["fast_all"])
    for part in PART_ROWS:
        row("  the same: the loop's wall time per sim second, %s" % part,
            "%.1f" % median([f["parts"][part] for f in fast]), "ms")
    return fast


def world_rows(runs, row):
    """The world group: /gazebo/model_states subscribed, world calls, the stage 1 client."""
    with_states = ALL_SENSORS + ["/gazebo/model_states"]
    rt_states = [measure_running(1.0, with_states) for _ in range(runs)]
    row("real time, every sensor and /gazebo/model_states subscribed: sim CPU",
        "%.1f" % median([r[1] for r in rt_states]), "% core", TARGETS["rt_cpu_states"])
    row("as fast as possible, every sensor and /gazebo/model_states subscribed",
        "%.1f" % median([measure_running(0, with_states)[0] for _ in range(runs)]),
        "x", TARGETS["fast_all"])
    calls = [measure_world_calls() for _ in range(runs)]
    row("spawn_sdf_model / delete_model round trip (median of 20)",
        "%.0f / %.0f" % (median([c[0] for c in calls]), median([c[1] for c in calls])),
        "ms", "each < 50 ms")
    row("stage 1, DQN-style client stepping once per scan (24 samples, max speed)",
        "%.1f" % median([measure_stage_client() for _ in range(runs)]), "steps/s",
        TARGETS["stage"])
    row("  floor: the same client's steps against a bare 1 kHz /scan node, no sim",
        "%.1f" % median([measure_stage_client_floor() for _ in range(runs)]),
        "steps/s")


def fast_bound_rows(row, fast):
    """The fast group's last rows (after the world group's): /odom only, the physics bound
    and the ceilings, from fast_rows' runs."""
    row("as fast as possible, only /odom subscribed",
        "%.1f" % median([f["odom"] for f in fast]), "x")
    row("physics bound: pybullet alone, no ROS, no sensors (before and after each run)",
        "%.1f" % median([f["bound"] for f in fast]), "x")
    row("  fast (every sensor) / physics bound",
        "%.2f" % median([f["all"] / f["bound"] for f in fast]), "", TARGETS["fast_all_bound"])
    row("  fast (only /odom) / physics bound",
        "%.2f" % median([f["odom"] / f["bound"] for f in fast]), "",
        TARGETS["fast_odom_bound"])
    row("  ceiling: Simulation.step, no ROS, no sensors / physics bound",
        "%.2f" % median([f["stepped"] / f["bound"] for f in fast]), "")
    row("  ceiling: Simulation.step and every sensor, no ROS / physics bound",
        "%.2f" % median([f["with_sensors"] / f["bound"] for f in fast]), "")


def subscriber_rows(runs, row):
    """The subscribers group: as fast as possible with 1, 4, 8 subscribers to /scan."""
    for n in (1, 4, 8):
        row("as fast as possible, %d subscriber(s) to /scan" % n,
            "%.1f" % median([measure_running(0, ["/scan:%d" % n])[0]
                             for _ in range(runs)]), "x")


def camera_rows(runs, row):
    """The camera group: the Waffle Pi's and the Waffle's camera subscribed at real time."""
    for model, target in (("waffle_pi", ">= 27/s at >= 0.9x"), ("waffle", "")):
        cam = [measure_running(1.0, ["/camera/rgb/image_raw"], model=model)
               for _ in range(runs)]
        row("%s camera subscribed, real time: images per sim second" % model,
            "%.1f" % median([r[3] for r in cam]), "/s", target)
        row("%s camera subscribed, real time: achieved factor" % model,
            "%.2f" % median([r[0] for r in cam]), "x")
        row("%s camera subscribed, real time: sim CPU" % model,
            "%.0f" % median([r[1] for r in cam]), "% core")


def render_rows(row):
    """The render group: ms per image at each resolution and renderer (one measurement)."""
    for (renderer, width, height), ms in sorted(render_times().items()):
        row("render %dx%d, %s" % (width, height, renderer), "%.1f" % ms, "ms")


def soak_rows(row):
    """The soak group (one run: it is long): sim RSS over 30 sim minutes with churn."""
    first, last, growth = measure_soak()
    row("soak, 30 sim min with churn: sim RSS at the start / at the end", "%.0f / %.0f"
        % (first, last), "MB")
    row("soak: RSS growth over the last third", "%.2f" % growth, "MB", "< 2 MB")


def hostile_rows(row):
    """The hostile group (one run: it is long): bench/hostile_soak.py's figures."""
    hostile = measure_hostile()
    row("hostile soak, 20 wall min: the sim alive at the end", "yes" if hostile["alive"]
        else "NO", "", "yes")
    row("hostile soak: longest wall time between two /clock", "%.2f" % hostile["gap"], "s",
        "<= 2 s")
    row("hostile soak: sim RSS idle / after a first round / at the end", "%.0f / %.0f / %.0f"
        % (hostile["rss_idle"], hostile["rss_start"], hostile["rss_end"]), "MB",
        "end <= first round + 50 MB")
    row("hostile soak: sim CPU s per sim s at the start / at the end", "%.3f / %.3f"
        % (hostile["cpu_start"], hostile["cpu_end"]), "", "end <= start x 1.1")
    row("hostile soak: sim threads after a first round / at the end", "%d / %d"
        % (hostile["threads_start"], hostile["threads_end"]), "", "end <= first round + 10")
    row("hostile soak: a client's /scan rate", "%.2f" % hostile["scan_hz"], "Hz of sim time",
        ">= 4.75 (5 published)")


def mesh_rows(runs, row):
    """The mesh turtlebot3_world (Gazebo's files) beside the built-in primitive copy."""
    for label, mesh in (("built-in turtlebot3_world (primitive shapes)", False),
                        ("turtlebot3_world from model:// with Collada meshes", True)):
        startup = [measure_startup(**(mesh_world_run() if mesh else {})) for _ in range(runs)]
        row("%s: start-up -> first /scan" % label, "%.2f" % median(startup), "s")
        fast = [measure_running(0, ALL_SENSORS, mesh_world=mesh)[0] for _ in range(runs)]
        row("  the same: as fast as possible, every sensor subscribed", "%.1f" % median(fast),
            "x")


def generated_mesh_world():
    """(world file, models folder) of bench/mesh_world.py, written once into a temporary folder
    (removed at exit)."""
    import atexit
    import shutil
    import tempfile
    from mesh_world import write_mesh_world
    folder = tempfile.mkdtemp(prefix="bench_mesh_world_")
    atexit.register(shutil.rmtree, folder, True)
    return write_mesh_world(folder)


def mesh_world_physics(world, models, sim_seconds=4.0, rounds=4):
    """{(world, sensors): CPU s per sim s} of Simulation.step of a Burger driving a 0.33 m
    circle (sensors: every output computed as it falls due), no ROS, in turtlebot3_world and
    in ``world``; the two step in turns, ``rounds`` times, in this process."""
    from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
    os.environ["GAZEBO_MODEL_PATH"] = models
    sims = {name: Simulation(SimConfig(model="burger", world=name))
            for name in ("turtlebot3_world", world)}
    cpu = {}
    try:
        for sim in sims.values():
            sim.robot.command(0.1, 0.3)
            for _ in range(400):
                sim.step()
        steps = int(round(sim_seconds / rounds / 0.0025))
        for _ in range(rounds):
            for name, sim in sims.items():
                for sensors in (False, True):
                    t0 = time.process_time()
                    for _ in range(steps):
                        due = sim.step()
                        if sensors:
                            step_outputs(sim, due)
                    key = (name, sensors)
                    cpu[key] = cpu.get(key, 0.0) + time.process_time() - t0
    finally:
        for sim in sims.values():
            sim.close()
    return {key: value / sim_seconds for key, value in cpu.items()}


@contextlib.contextmanager
def temporary_ros_home():
    """ROS_HOME a new temporary folder (an empty mesh cache) in this process for the block, then
    as it was, the folder removed; yields its path."""
    import shutil
    import tempfile
    home = tempfile.mkdtemp(prefix="bench_ros_home_")
    old_home = os.environ.get("ROS_HOME")
    os.environ["ROS_HOME"] = home
    try:
        yield home
    finally:
        if old_home is None:
            os.environ.pop("ROS_HOME", None)
        else:
            os.environ["ROS_HOME"] = old_home
        shutil.rmtree(home, ignore_errors=True)


def mesh_world_rows(runs, row):
    """The generated mesh world's start-up (empty cache, then filled) and physics cost, beside
    the built-in turtlebot3_world, measured in turns."""
    import shutil
    import tempfile
    world, models = generated_mesh_world()
    mesh_env = {"GAZEBO_MODEL_PATH": models}
    builtin, first, second = [], [], []
    for _ in range(runs):
        home = tempfile.mkdtemp(prefix="bench_ros_home_")
        try:
            builtin.append(measure_startup(env={"ROS_HOME": home}))
            first.append(measure_startup(world=world, env=dict(mesh_env, ROS_HOME=home)))
            second.append(measure_startup(world=world, env=dict(mesh_env, ROS_HOME=home)))
        finally:
            shutil.rmtree(home, ignore_errors=True)
    row("built-in turtlebot3_world: start-up -> first /scan", "%.2f" % median(builtin), "s")
    row("generated world, 110 textured Collada models: first start (empty mesh cache)",
        "%.2f" % median(first), "s")
    row("  the same, second start (the mesh cache filled)", "%.2f" % median(second), "s")
    row("  second start / built-in world's start", "%.2f" % median(
        [s / b for s, b in zip(second, builtin)]), "", TARGETS["meshworld_second"])
    with temporary_ros_home():
        costs = [mesh_world_physics(world, models) for _ in range(runs)]
    for sensors, label in ((False, "physics alone"), (True, "physics and every sensor")):
        builtin_cost = median([c[("turtlebot3_world", sensors)] for c in costs])
        mesh_cost = median([c[(world, sensors)] for c in costs])
        row("CPU s per sim s, no ROS, %s: built-in / generated mesh world" % label,
            "%.4f / %.4f" % (builtin_cost, mesh_cost), "s")
        row("  generated mesh world / built-in world", "%.2f" % median(
            [c[(world, sensors)] / c[("turtlebot3_world", sensors)] for c in costs]), "x",
            TARGETS["meshworld_physics"] if not sensors else "")


def camera_costs(world, models, rounds=8, images=4):
    """{key: CPU ms per image} of the Waffle Pi's camera without ROS, in turtlebot3_world
    ("builtin"), in ``world`` ("generated") and in ``world`` with every body drawn ("whole":
    no view culling), each the median of ``rounds`` rounds of ``images`` images; the three
    drawn in turns in this process (its CPU time: llvmpipe's threads are in it)."""
    from tutorial_turtlebot.sim.world.simulation import SimConfig, Simulation
    os.environ["GAZEBO_MODEL_PATH"] = models
    sims = {"builtin": Simulation(SimConfig(model="waffle_pi", world="turtlebot3_world")),
            "generated": Simulation(SimConfig(model="waffle_pi", world=world))}
    camera = sims["generated"].robot.camera
    culling = camera.view_culling
    costs = {"builtin": [], "generated": [], "whole": []}
    try:
        for sim in sims.values():
            sim.robot.camera_image()          # shaders compiled, textures loaded
        for _ in range(rounds):
            for key in costs:
                sim = sims["builtin" if key == "builtin" else "generated"]
                camera.view_culling = None if key == "whole" else culling
                t0 = time.process_time()
                for _ in range(images):
                    sim.robot.camera_image()
                costs[key].append(1000.0 * (time.process_time() - t0) / images)
    finally:
        camera.view_culling = culling
        for sim in sims.values():
            sim.close()
    return {key: median(values) for key, values in costs.items()}


def mesh_camera_rows(runs, row):
    """The Waffle Pi's camera in the generated world beside turtlebot3_world: CPU per image
    without ROS (in turns), and the sim node at real time with the camera subscribed."""
    world, models = generated_mesh_world()
    with temporary_ros_home() as home:
        costs = [camera_costs(world, models) for _ in range(runs)]
        world_env = {"GAZEBO_MODEL_PATH": models, "ROS_HOME": home}
        running, floor = [], []
        for _ in range(runs):    # with the camera subscribed, and without, in turns
            running.append(measure_running(1.0, ["/camera/rgb/image_raw"], model="waffle_pi",
                                           world=world, world_env=world_env))
            floor.append(measure_running(1.0, ["/odom"], model="waffle_pi", world=world,
                                         world_env=world_env))
    row("Waffle Pi camera, CPU per image, no ROS: turtlebot3_world / generated world",
        "%.1f / %.1f" % (median([c["builtin"] for c in costs]),
                         median([c["generated"] for c in costs])), "ms")
    row("  generated world / turtlebot3_world", "%.2f" % median(
        [c["generated"] / c["builtin"] for c in costs]), "x", TARGETS["meshcamera_ratio"])
    row("  generated world with every body drawn (no view culling)",
        "%.1f" % median([c["whole"] for c in costs]), "ms")
    row("Waffle Pi camera subscribed in the generated world, real time: achieved factor",
        "%.2f" % median([r[0] for r in running]), "x", TARGETS["meshcamera_rtf"])
    row("  the same: images per sim second (30 declared)",
        "%.1f" % median([r[3] for r in running]), "/s")
    row("  the same: sim CPU", "%.0f" % median([r[1] for r in running]), "% core")
    row("  floor: the same, only /odom subscribed (no image drawn): achieved factor",
        "%.2f" % median([r[0] for r in floor]), "x")


def multi_bound_rows(row, label, bounds, fast_factor):
    """The rows of ``bounds`` (robots_bound's runs) beside the factor as fast as possible."""
    bare, with_sensors = (median([b[k] for b in bounds]) for k in (0, 1))
    row("  %s without ROS: physics alone / physics and sensors" % label,
        "%.0f / %.0f" % (bare, with_sensors), "x")
    row("  as fast as possible / (physics and sensors, no ROS)",
        "%.2f" % (fast_factor / with_sensors), "")


def multi_house_rows(runs, row):
    """Three robots in the house: at real time, as fast as possible, and without ROS."""
    house = [measure_house() for _ in range(runs)]
    name = "3 Burgers in the house (multi_turtlebot3.launch), all sensors subscribed"
    row("%s, real time: sim CPU" % name, "%.1f" % median([r[0][1] for r in house]),
        "% core", TARGETS["multi_rt_cpu"])
    row("  the same: achieved factor", "%.2f" % median([r[0][0] for r in house]), "x")
    row("  the same: messages per sim second (all subscriptions)",
        "%.0f" % median([r[0][2] for r in house]), "/s")
    fast_factor = median([r[1][0] for r in house])
    row("%s, as fast as possible" % name, "%.1f" % fast_factor, "x", TARGETS["multi_fast"])
    row("  the same: sim CPU", "%.0f" % median([r[1][1] for r in house]), "% core")
    row("  the same: sim CPU time per sim second (1000 / it: the factor on a core of its own)",
        "%.0f" % median([10 * r[1][1] / r[1][0] for r in house]), "ms")
    multi_bound_rows(row, "the same 3", [robots_bound(3, "turtlebot3_house", HOUSE_POSES)
                                         for _ in range(runs)], fast_factor)


def multi_scaling_rows(runs, row):
    """1, 2, 4, 8 robots in the empty world: how the cost grows."""
    scaling = [measure_scaling() for _ in range(runs)]
    for count in ROBOT_COUNTS:
        results = [s[count] for s in scaling]
        label = "%d Burger%s" % (count, "" if count == 1 else "s")
        row("%s in the empty world (sim node alone), all sensors subscribed, real time: sim "
            "CPU" % label, "%.1f" % median([r[0][1] for r in results]), "% core")
        row("  the same: achieved factor at real time",
            "%.2f" % median([r[0][0] for r in results]), "x")
        fast_factor = median([r[1][0] for r in results])
        row("  the same, as fast as possible", "%.1f" % fast_factor, "x")
        row("  the same: sim CPU as fast as possible",
            "%.0f" % median([r[1][1] for r in results]), "% core")
        row("  the same: sim CPU time per sim second (as fast as possible)",
            "%.0f" % median([10 * r[1][1] / r[1][0] for r in results]), "ms")
        multi_bound_rows(row, label, [robots_bound(count) for _ in range(runs)], fast_factor)


def multi_rows(runs, row):
    """The several-robot rows: three robots in the house; how the cost grows with 1, 2, 4, 8."""
    multi_house_rows(runs, row)
    multi_scaling_rows(runs, row)


def learning_stage_1_rows(ls, runs, row):
    """Stage 1 with one StageEnv beside its physics bound."""
    stage_1 = [ls.one_env_and_bound(1, seconds=10.0) for _ in range(runs)]
    row("learning stage 1, one StageEnv (no ROS): env steps/s",
        "%.1f" % median([e for e, _ in stage_1]), "steps/s")
    row("  physics bound: bare pybullet, same steps and rays",
        "%.1f" % median([b for _, b in stage_1]), "steps/s")
    row("  one env / physics bound", "%.2f" % median([e / b for e, b in stage_1]), "",
        TARGETS["learning_bound"])


def learning_vector_rows(ls, runs, row):
    """The vector env and Gymnasium's AsyncVectorEnv beside one env."""
    cores = os.cpu_count()
    vector = [ls.vector_and_one(seconds=15.0) for _ in range(runs)]
    row("learning stage 1, vector env (%d workers x 4 envs)" % cores,
        "%.1f" % median([v["vector"] for v in vector]), "steps/s")
    row("  vector env / one env", "%.2f" % median([v["vector"] / v["one"] for v in vector]),
        "x", TARGETS["learning_vector"])
    row("  Gymnasium's AsyncVectorEnv (%d envs, lockstep) / one env" % cores,
        "%.2f" % median([v["async"] / v["one"] for v in vector]), "x")
    row("  env steps per CPU s: the workers' / one env's",
        "%.2f" % median([v["vector_per_cpu"] / v["one_per_cpu"] for v in vector]), "")
    row("  cores the workers got (CPU s per wall s; rest: other load)",
        "%.2f" % median([v["worker_cores"] for v in vector]), "of %d" % cores)


def learning_step_size_rows(ls, runs, row):
    """Coarser physics steps: their speed and how far the final pose moves."""
    speeds = [ls.coarse_speeds(seconds=9.0) for _ in range(runs)]
    diffs, contact = ls.pose_differences()
    for ts in (0.005, 0.01):
        row("learning stage 1, %g s physics steps; / 0.0025 s" % ts,
            "%.1f / %.2f" % (median([s[ts] for s in speeds]),
                             median([s[ts] / s[0.0025] for s in speeds])), "steps/s, x")
        for name in diffs:
            distance, yaw = diffs[name][ts]
            row("  final pose vs 0.0025 s, 100 steps, %s" % name,
                "%.1f / %.2f" % (distance * 1000, yaw * 1000), "mm, mrad")


def learning_stage_3_rows(ls, runs, row):
    """Stage 3 (its moving obstacle) beside its physics bound."""
    stage_3 = [ls.one_env_and_bound(3, seconds=8.0) for _ in range(runs)]
    row("learning stage 3, one StageEnv: env steps/s",
        "%.1f" % median([e for e, _ in stage_3]), "steps/s")
    row("  physics bound (the obstacle's ticks included)",
        "%.1f" % median([b for _, b in stage_3]), "steps/s")
    row("  one env / physics bound", "%.2f" % median([e / b for e, b in stage_3]), "")


def learning_render_rows(ls, runs, row):
    """ms per render() (top-down picture; the Waffle Pi's camera) beside ms per env step."""
    renders = [ls.render_cost(1, seconds=5.0) for _ in range(runs)]
    row("learning stage 1, render() rgb_array / env step",
        "%.2f / %.2f" % (median([r for r, _ in renders]), median([s for _, s in renders])),
        "ms")
    cameras = [ls.render_cost(1, seconds=3.0, model="waffle_pi", camera=True)
               for _ in range(runs)]
    row("  render_camera (waffle_pi's camera) / env step",
        "%.2f / %.2f" % (median([r for r, _ in cameras]), median([s for _, s in cameras])),
        "ms")


def learning_rows(runs, row):
    """The learning group: bench/learning_speed.py's figures, each the median of ``runs``."""
    import learning_speed as ls
    for rows in (learning_stage_1_rows, learning_vector_rows, learning_step_size_rows,
                 learning_stage_3_rows, learning_render_rows):
        rows(ls, runs, row)


class Group(NamedTuple):
    """One entry of GROUP_TABLE: a group of rows of the table and how to run it."""

    name: str                          # its name for --only
    rows: Callable[..., Any]           # prints its rows; returns what later entries need
    needs: Tuple[str, ...] = ("runs", "row")  # rows' arguments: runs, row, earlier results
    minutes: str = ""                  # wall minutes it takes, if too long for the default


# The groups in the order of the table's rows; a name may come twice (fast: its last rows come
# after the world group's). Each entry's result, unless None, is kept under its name.
GROUP_TABLE = (
    Group("startup", startup_rows),
    Group("realtime", realtime_rows),
    Group("nav", nav_rows),
    Group("jitter", jitter_rows),
    Group("fast", fast_rows),
    Group("world", world_rows),
    Group("fast", fast_bound_rows, needs=("row", "fast")),
    Group("subscribers", subscriber_rows),
    Group("camera", camera_rows),
    Group("render", render_rows, needs=("row",)),
    Group("meshes", mesh_rows),
    Group("meshworld", mesh_world_rows),
    Group("meshcamera", mesh_camera_rows),
    Group("multi", multi_rows),
    Group("learning", learning_rows),
    Group("soak", soak_rows, needs=("row",), minutes="15 to 20"),      # one run: it is long
    Group("hostile", hostile_rows, needs=("row",), minutes="22"),      # one run: it is long
)
GROUPS = tuple(dict.fromkeys(g.name for g in GROUP_TABLE if not g.minutes))
EXTRA_GROUPS = tuple(g.name for g in GROUP_TABLE if g.minutes)   # run only when in --only


def parse_args():
    """The command line: --runs and --only (checked; --only as a list of group names)."""
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--runs", type=int, default=3, help="runs per figure (median)")
    long_ones = [g for g in GROUP_TABLE if g.minutes]
    parser.add_argument("--only", default=",".join(GROUPS),
                        help="comma-separated groups of rows to run (default: all but "
                        "%s, which take %s minutes): " % (
                            " and ".join(g.name for g in long_ones),
                            " and ".join(g.minutes for g in long_ones))
                        + ", ".join(GROUPS + EXTRA_GROUPS))
    args = parser.parse_args()
    args.only = [g.strip() for g in args.only.split(",") if g.strip()]
    unknown = [g for g in args.only if g not in GROUPS + EXTRA_GROUPS]
    if unknown or not args.only:
        parser.error("--only: unknown group %r (groups: %s)"
                     % (",".join(unknown), ", ".join(GROUPS + EXTRA_GROUPS)))
    if args.runs < 1:
        parser.error("--runs must be at least 1")
    return args


def main():
    """Print the table: the rows of each group --only names, in GROUP_TABLE's order."""
    args = parse_args()
    rows = []
    started = time.time()

    def row(name, value, unit, target=""):
        rows.append((name, value, unit, target))
        print("  %-58s %10s %-8s %s" % (name, value, unit, target), flush=True)

    print("tutorial_turtlebot benchmark: %d runs each, median; %s, %d cores, load average %s"
          % (args.runs, os.uname().nodename, os.cpu_count(),
             " ".join("%.2f" % v for v in os.getloadavg())), flush=True)
    found = {"runs": args.runs, "row": row}   # what the entries need
    for group in GROUP_TABLE:
        if group.name in args.only:
            result = group.rows(*(found[need] for need in group.needs))
            if result is not None:
                found[group.name] = result
    print("(%.0f s; load average now %s)" % (time.time() - started,
                                             " ".join("%.2f" % v for v in os.getloadavg())),
          flush=True)


if __name__ == "__main__":
    main()
