#!/usr/bin/env python3
"""``make corpus``: every public Gazebo world of the corpus through the real sim; one table.

The corpus (tools/corpus/manifest.json: public worlds with the model folders they name) lies
outside this repository, in $TUTORIAL_TURTLEBOT_CORPUS, else /work/corpus;
tools/corpus/fetch_corpus.py makes it. Without it this says so in one line and stops. Not part
of make test: it takes about 1 to 3 wall minutes a world, one world at a time.

Each world is started as a user starts it, ``roslaunch tutorial_turtlebot sim.launch
model:=waffle_pi world:=FILE x_pos:=.. y_pos:=.. yaw:=..`` with the GAZEBO_MODEL_PATH (and
GAZEBO_RESOURCE_PATH) the manifest gives, each roslaunch on a master of its own, in three steps:

1. **cold**: ROS_HOME a new temporary folder (an empty mesh cache), the robot parked far
   outside the world (FAR); whether the world loads, and the start-up.
2. **free pose**: bench/corpus_pose.py, the world in the simulator itself (no ROS, the cache of
   step 1): a point on a flat static floor, clear of anything within 0.6 m, where the robot's
   own laser agrees, and its most open direction.
3. **warm**: roslaunch again with the same ROS_HOME, the robot at that pose (``z_pos`` left at
   0, as a user leaves it), and bench/corpus_probe.py measuring over ROS. If the sim refuses
   that spawn and the floor there is raised, the run is repeated with ``z_pos`` at the floor's
   height to measure the rest ("yes, z_pos" in the table).

The columns:

  world           the manifest's name (source repository and path: tools/corpus/manifest.json)
  loaded          yes: cold and warm starts loaded the world as it is, the robot at the free
                  pose; no: the one-line refusal (or what failed) is listed under the table
  models          names in /gazebo/model_states (the robot included)
  laser           share of the laser's ranges that are returns (finite), over five scans
  camera colours  distinct colours (each channel in 8 levels, each covering 0.2 % of an
                  image) in the Waffle Pi's 640x480 camera over four headings 90 degrees apart,
                  the robot turned in place by /gazebo/set_model_state; "colour" when at least
                  1 % of one image's pixels has channels 24 apart (0..255), else "grey"
  drive           0.2 m/s for 2 sim s, then 0.5 rad/s for 2 sim s, from the free pose facing
                  its most open direction: "ok" when the robot went 0.4 m +-20 % ahead,
                  less than 5 cm sideways, and turned 1 rad +-20 % (poses from
                  /gazebo/model_states); else what it did
  start cold/warm roslaunch (roscore included) to the first /scan, wall s, with an empty mesh
                  cache, then with the cache the cold start filled
  CPU             the sim process's CPU seconds per sim second at real time over 5 sim s with
                  /scan and /odom subscribed, as a multiple of the same figure for the built-in
                  turtlebot3_world measured at the start of the run; in brackets the same with
                  the camera image subscribed too

``--only NAME[,NAME]`` runs some worlds; ``--limit S`` is each world's wall time limit (default
600 s); the table goes to stdout and to ``--out`` (default: a markdown file in the temporary
folder), every figure and warning line to a JSON file beside it; ``--images DIR`` keeps each
world's four camera images (PPM) in DIR/NAME/.
"""
import argparse
import json
import os
import select
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, os.pardir)
sys.path.insert(0, os.path.join(ROOT, "src"))
sys.path.insert(0, os.path.join(ROOT, "test"))
sys.path.insert(0, os.path.join(ROOT, "tools", "corpus"))
from corpus_metrics import format_report, refusal_line, warning_lines  # noqa: E402
from fetch_corpus import corpus_root, load_manifest, world_env, world_file  # noqa: E402
from process_helpers import (free_port, node_on_master, signal_process,  # noqa: E402
                             stop_process)

FAR = 5000.0            # m: the cold start's spawn, outside any world
STARTUP_LIMIT = 240.0   # wall s to the first /scan at most
MEASURE_LIMIT = 180.0   # wall s for the probe's measurements at most
STOP_WAIT = 15.0        # wall s a roslaunch has to end after SIGINT
RAISED = 0.005          # m: a floor higher than this is raised (the z_pos retry)
MAX_ATTEMPTS = 4        # warm starts at most when the sim refuses the spawn


class WorldRun:
    """One roslaunch of sim.launch (Waffle Pi) on its own master, with corpus_probe.py."""

    def __init__(self, world, pose, env):
        self.port = free_port()
        self.env = dict(os.environ, ROS_MASTER_URI="http://localhost:%d" % self.port, **env)
        self.args = ["model:=waffle_pi", "world:=%s" % world, "status_period:=0"]
        if pose is not None:   # else the world's own spawn
            self.args += ["x_pos:=%g" % pose[0], "y_pos:=%g" % pose[1], "z_pos:=%g" % pose[2],
                          "yaw:=%g" % pose[3]]
        self.log = tempfile.NamedTemporaryFile(prefix="corpus_roslaunch_", suffix=".log",
                                               delete=False)
        self.probe_log = tempfile.NamedTemporaryFile(prefix="corpus_probe_", suffix=".log",
                                                     delete=False)
        self.procs = []

    def run(self, phase, limit, drive_yaw=0.0):
        """Start the probe, then roslaunch; return a dict: cold/warm start-up s and the probe's
        figures, or "reason" (the sim's refusal, or what timed out)."""
        deadline = time.time() + limit
        probe = subprocess.Popen(
            [sys.executable, os.path.join(HERE, "corpus_probe.py"), phase,
             "%g" % min(STARTUP_LIMIT, limit), "%g" % drive_yaw],
            env=self.env, stdin=subprocess.PIPE, stdout=subprocess.PIPE,
            stderr=self.probe_log, text=True, start_new_session=True)
        self.procs.append(probe)
        time.sleep(1.5)   # its imports are done; it now waits for the master
        t0 = time.time()
        launch = subprocess.Popen(["roslaunch", "-p", str(self.port), "tutorial_turtlebot",
                                   "sim.launch"] + self.args, env=self.env, stdout=self.log,
                                  stderr=subprocess.STDOUT, start_new_session=True)
        self.procs.append(launch)
        first = self.read_line(probe, launch, min(deadline, t0 + STARTUP_LIMIT))
        if first is None or first.get("first_scan") is None:
            return {"reason": self.why(launch, "no /scan within %.0f s" % (time.time() - t0))}
        result = {"startup_s": round(first["first_scan"] - t0, 2)}
        if phase != "measure":
            return result
        pid = self.sim_pid()
        probe.stdin.write("%d\n" % pid)
        probe.stdin.flush()
        figures = self.read_line(probe, launch, min(deadline, time.time() + MEASURE_LIMIT))
        if figures is None:
            with open(self.probe_log.name, encoding="utf-8", errors="replace") as f:
                probe_error = refusal_line(f.read())
            result["reason"] = self.why(launch, "the measurements did not end%s" % (
                " (corpus_probe.py: %s)" % probe_error if probe_error else ""))
        else:
            result.update(figures)
        return result

    def read_line(self, probe, launch, deadline):
        """The probe's next JSON line, or None when roslaunch ends or ``deadline`` passes."""
        while time.time() < deadline:
            ready, _, _ = select.select([probe.stdout], [], [], 0.5)
            if ready:
                line = probe.stdout.readline()
                if not line:
                    return None
                try:
                    return json.loads(line)
                except ValueError:
                    continue
            if launch.poll() is not None:
                time.sleep(0.5)   # the probe may still print what it has
                ready, _, _ = select.select([probe.stdout], [], [], 0.5)
                return json.loads(probe.stdout.readline() or "null") if ready else None
        return None

    def why(self, launch, otherwise):
        """The sim's refusal line from the log, else ``otherwise``."""
        time.sleep(0.5)
        line = refusal_line(self.log_text())
        if line:
            return line
        return otherwise if launch.poll() is None else "roslaunch ended: %s" % otherwise

    def sim_pid(self):
        """The pid of the node named gazebo on this run's master, or -1."""
        pid = node_on_master("gazebo", self.port)
        return -1 if pid is None else pid

    def log_text(self):
        with open(self.log.name, encoding="utf-8", errors="replace") as f:
            return f.read()

    def stop(self):
        for proc in reversed(self.procs):
            signal_process(proc, signal.SIGINT)
        for proc in reversed(self.procs):
            stop_process(proc, STOP_WAIT, sig=None)
        for log in (self.log, self.probe_log):
            log.close()
            os.unlink(log.name)


def launch_once(world, pose, env, phase, limit, drive_yaw=0.0):
    """One WorldRun (``pose``: x, y, z, yaw; None: the world's spawn); its result with the
    sim's warning lines."""
    run = WorldRun(world, pose, env)
    try:
        result = run.run(phase, limit, drive_yaw)
        result["warnings"] = warning_lines(run.log_text())
        return result
    finally:
        run.stop()


def find_pose(world, env, limit):
    """bench/corpus_pose.py's answer for ``world`` (a dict), run in a child process."""
    try:
        out = subprocess.run([sys.executable, os.path.join(HERE, "corpus_pose.py"), world],
                             env=dict(os.environ, **env), capture_output=True, text=True,
                             timeout=limit).stdout
    except subprocess.TimeoutExpired:
        return {"error": "no free pose within %.0f s" % limit}
    lines = [line for line in out.splitlines() if line.startswith("{")]
    return json.loads(lines[-1]) if lines else {"error": "corpus_pose.py printed nothing"}


def spawn_attempts(pose):
    """[(free pose, z_pos)] to try, at most MAX_ATTEMPTS: each free pose found (numbered,
    best first) with z_pos 0 as a user leaves it, then at its floor's height if raised."""
    attempts = []
    for number, spot in enumerate([pose] + pose.get("alternates", [])):
        spot = dict(spot, number=number)
        attempts.append((spot, 0.0))
        if spot["z"] > RAISED:
            attempts.append((spot, spot["z"]))
    return attempts[:MAX_ATTEMPTS]


def run_world(name, world, env, limit):
    """The row of one world (a dict; see the module docstring for what each key means)."""
    deadline = time.time() + limit
    row = {"name": name}
    home = tempfile.mkdtemp(prefix="corpus_ros_home_")
    env = dict(env, ROS_HOME=home)
    try:
        cold = launch_once(world, (FAR, FAR, 0.0, 0.0), env, "startup", limit)
        row["cold_warnings"] = cold["warnings"]
        if "reason" in cold:
            row.update(loaded=False, reason=cold["reason"])
            return row
        row["cold_s"] = cold["startup_s"]
        pose = find_pose(world, env, max(10.0, deadline - time.time()))
        row["pose"] = pose
        if "error" in pose:
            row.update(loaded=True, reason="no free pose found: " + pose["error"])
            return row
        warm, used, first_reason = None, None, None
        for number, (spot, z) in enumerate(spawn_attempts(pose)):
            warm = launch_once(world, (spot["x"], spot["y"], z, spot["yaw"]), env, "measure",
                               max(10.0, deadline - time.time()), spot["yaw"])
            if "startup_s" in warm:
                used = (number, spot, z)
                break
            first_reason = first_reason or warm.get("reason", "?")
            if "spawn (" not in warm.get("reason", ""):
                break   # a refusal of the world, not of the pose: no other pose helps
        row["warnings"] = warm.pop("warnings")
        if used is None:
            row.update(loaded=False, reason=first_reason)
            return row
        number, spot, z = used
        row["spawn"] = [spot["x"], spot["y"], z, spot["yaw"]]
        row["warm_s"] = warm.pop("startup_s")
        row["loaded"] = number == 0
        if number:
            row["reason"] = first_reason
            row["workaround"] = ("z_pos %.3f" % z if z else "") + (
                "%sfree pose %d" % (", " if z else "", spot["number"] + 1)
                if spot["number"] else "")
        row.update({k: v for k, v in warm.items() if k != "reason"})
        if warm.get("reason"):
            row["reason"] = warm["reason"]
        return row
    finally:
        shutil.rmtree(home, ignore_errors=True)


def run_reference(limit, env):
    """The built-in turtlebot3_world at its own spawn (facing +x), measured as the worlds are."""
    home = tempfile.mkdtemp(prefix="corpus_ros_home_")
    try:
        warm = launch_once("turtlebot3_world", None, dict(env, ROS_HOME=home), "measure", limit,
                           0.0)
        warm["warm_s"] = warm.pop("startup_s", None)
        return warm
    finally:
        shutil.rmtree(home, ignore_errors=True)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--only", help="worlds to run, comma-separated names")
    parser.add_argument("--limit", type=float, default=600.0, help="wall s per world")
    parser.add_argument("--out", default=os.path.join(tempfile.gettempdir(),
                                                      "tutorial_turtlebot_corpus.md"))
    parser.add_argument("--images", help="keep each world's four camera images (PPM) in "
                        "IMAGES/NAME/")
    args = parser.parse_args(argv)
    root = corpus_root()
    manifest = load_manifest()
    worlds = manifest["worlds"]
    if args.only:
        names = args.only.split(",")
        unknown = sorted(set(names) - {w["name"] for w in worlds})
        if unknown:
            sys.exit("make corpus: no world %s in tools/corpus/manifest.json" % ", ".join(unknown))
        worlds = [w for w in worlds if w["name"] in names]
    if not os.path.isdir(root) or not all(os.path.isfile(world_file(root, w)) for w in worlds):
        sys.exit("make corpus: the corpus is not in %s (or is incomplete): make it with "
                 "python3 tools/corpus/fetch_corpus.py" % root)
    print("make corpus: %d worlds from %s, %s, %d cores" % (len(worlds), root,
                                                            socket.gethostname(), os.cpu_count()),
          flush=True)
    images = {} if not args.images else {"CORPUS_IMAGES": os.path.join(args.images, "reference")}
    reference = run_reference(args.limit, images)
    print("reference turtlebot3_world: %s" % json.dumps(reference), flush=True)
    results = []
    json_path = os.path.splitext(args.out)[0] + ".json"
    for world in worlds:
        t0 = time.time()
        env = world_env(root, world)
        if args.images:
            env["CORPUS_IMAGES"] = os.path.join(args.images, world["name"])
        row = run_world(world["name"], world_file(root, world), env, args.limit)
        row["wall_s"] = round(time.time() - t0, 1)
        results.append(row)
        print("%s: %s (%.0f s)" % (world["name"], "loaded" if row.get("loaded") else
                                   "NOT loaded: %s" % row.get("reason"), row["wall_s"]),
              flush=True)
        with open(json_path, "w", encoding="utf-8") as f:
            json.dump({"reference": reference, "worlds": results}, f, indent=1)
    header = "make corpus, %s, %s (%d cores)" % (time.strftime("%Y-%m-%d"),
                                                 socket.gethostname(), os.cpu_count())
    shown = [dict(row, reason=row["reason"].replace(root.rstrip("/") + "/", ""))
             if row.get("reason") else row for row in results]   # paths within the corpus
    report = format_report(shown, reference, header)
    print(report)
    with open(args.out, "w", encoding="utf-8") as f:
        f.write(report)
    print("table: %s; every figure: %s" % (args.out, json_path))


if __name__ == "__main__":
    main()
