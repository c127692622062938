#!/usr/bin/env python3
"""``make peer``: gazebo_ros_pkgs' own tests, unmodified, with the sim in place of gzserver; one
table. Not part of make test.

The peer (ros-simulation/gazebo_ros_pkgs, noetic-devel, tools/peer/fetch_peer.py's
PEER_COMMIT) lies outside this repository, in $PEER_SRC, else /work/peer/gazebo_ros_pkgs;
tools/peer/fetch_peer.py makes it. Without it this says so in one line and exits 1, as make
corpus does without its corpus.

1. **apt**: the system packages the C++ tests build against (peer_plan.APT_PACKAGES), the
   missing ones only, through sudo when not root; one line says which.
2. **The scratch workspace** catkin_ws/peer/ (git-ignored, as all of catkin_ws/): the packages
   gazebo_plugins, gazebo_ros and gazebo_tests (tools/peer/peer_plan.py says what each holds),
   upstream's files copied from PEER_SRC and the build files written here, overlaid on
   catkin_ws/devel (the project's gazebo_msgs). catkin_make runs only when something in it
   changed (a digest of its files in build/peer_stamp.json), with /usr/bin first on PATH and
   -DPYTHON_EXECUTABLE=/usr/bin/python3; an executable that does not compile fails its tests
   with the compiler's first error, and the others are built (make -k).
3. **The tests**, each ``rostest <its .test or launch file>`` in the scratch workspace, on a
   master of its own (rostest's random port), in a new ROS_HOME; set_model_state_test 10 times.
   gazebo_ros's ``gzserver`` there is tools/peer/gzserver_args.py: the sim with the world and
   no robot. The ros_network tests get tools/peer/yaml_shim.py as sitecustomize.

``--only NAME[,NAME]`` runs some tests; ``--runs N`` runs each N times; ``--limit S`` is one
run's wall time limit (default 300 s); the table goes to stdout and to ``--out`` (default: a
markdown file in the temporary folder); every run's output is kept in catkin_ws/peer/logs/.
Exit status 0 when every test passed, 1 otherwise.
"""
import argparse
import glob
import hashlib
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, os.pardir, os.pardir))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(ROOT, "test"))
import fetch_peer  # noqa: E402
import peer_plan  # noqa: E402
from process_helpers import _exited, stop_process  # noqa: E402

WS = os.path.join(ROOT, "catkin_ws", "peer")
MAIN_DEVEL = os.path.join(ROOT, "catkin_ws", "devel")
STAMP = os.path.join(WS, "build", "peer_stamp.json")
SHIM_DIR = os.path.join(WS, "python_shims")
LOGS = os.path.join(WS, "logs")
PEER_MODELS = os.path.join(HERE, "models")   # our own stand-ins for models the tests include
RUN_LIMIT = 300.0    # wall s of one rostest run at most
STOP_WAIT = 15.0     # wall s a rostest has to end after SIGINT
SHIMMED_NODES = {"ros_api_checker"}   # test nodes that get the PyYAML shim

ENTRY = '''#!/usr/bin/env python3
"""gazebo_ros's {entry}, standing in: the sim (written by tools/peer/run_peer.py)."""
import sys
sys.path.insert(0, {here!r})
from gzserver_args import main
main(entry={entry!r})
'''
GZCLIENT = '''#!/usr/bin/env python3
"""gazebo_ros's gzclient, standing in (written by tools/peer/run_peer.py): the sim has no
separate client (gazebo, or the sim's ~gui, opens its window); this waits to be stopped."""
import signal
import sys
print("gzclient (stand-in): no separate client; waiting to be stopped", flush=True)
for sig in (signal.SIGINT, signal.SIGTERM):
    signal.signal(sig, lambda *_: sys.exit(0))
while True:
    signal.pause()
'''
SPAWN_MODEL = '''#!/usr/bin/env python3
"""gazebo_ros's spawn_model, standing in: the sim's (written by tools/peer/run_peer.py)."""
import os
import sys
os.execvp("rosrun", ["rosrun", "tutorial_turtlebot", "spawn_model"] + sys.argv[1:])
'''


def say(line):
    print("make peer: %s" % line, flush=True)


# --- system packages ---------------------------------------------------------------------------

def not_installed(packages):
    """The packages among ``packages`` that dpkg does not have installed."""
    out = subprocess.run(["dpkg-query", "-W", "-f=${Package} ${Status}\n"] + list(packages),
                         capture_output=True, text=True).stdout
    installed = {line.split()[0] for line in out.splitlines()
                 if line.endswith(" install ok installed")}
    return [p for p in packages if p not in installed]


def install_packages():
    if not shutil.which("dpkg-query") or not shutil.which("apt-get"):
        sys.exit("make peer: no dpkg/apt-get here: install the equivalents of %s by hand"
                 % " ".join(peer_plan.APT_PACKAGES))
    missing = not_installed(peer_plan.APT_PACKAGES)
    if not missing:
        return
    say("installing %s (apt-get, for the C++ tests)" % " ".join(missing))
    sudo = [] if os.geteuid() == 0 else ["sudo"]
    command = sudo + ["env", "DEBIAN_FRONTEND=noninteractive", "apt-get", "install", "-y",
                      "-qq", "--no-install-recommends"] + missing
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        sys.stderr.write("\n".join((done.stdout + done.stderr).splitlines()[-20:]) + "\n")
        sys.exit("make peer: apt-get install failed (its last lines are above)")


# --- the scratch workspace -----------------------------------------------------------------------

def read(path):
    with open(path, "rb") as handle:
        return handle.read()


def tree(src, dest):
    """{dest/relative path: (bytes, mode)} of every file under ``src``."""
    files = {}
    for folder, _, names in os.walk(src):
        for name in names:
            path = os.path.join(folder, name)
            files[os.path.join(dest, os.path.relpath(path, src))] = (
                read(path), 0o755 if os.access(path, os.X_OK) else 0o644)
    return files


def upstream_version(peer, package):
    text = read(os.path.join(peer, package, "package.xml")).decode("utf-8", "replace")
    start = text.find("<version>")
    return text[start + 9:text.find("</version>")].strip() if start >= 0 else "0.0.0"


def plan(peer):
    """(files {path in src/: (bytes, mode)}, tests [PeerTest], built {(pkg, exe): Executable})
    of the scratch workspace for the tree at ``peer``."""
    def text(*parts):
        return read(os.path.join(peer, *parts)).decode("utf-8", "replace")

    plugin_exes, plugin_tests = peer_plan.catkin_tests(
        text("gazebo_plugins", "CMakeLists.txt"), "gazebo_plugins")
    _, ros_tests = peer_plan.catkin_tests(text("gazebo_ros", "test", "CMakeLists.txt"),
                                          "gazebo_ros", "test/")
    old_exes, old_tests = peer_plan.rosbuild_tests(
        text("gazebo_plugins", "test2", "CMakeLists_tests_pkg.txt"), "gazebo_tests")
    files = {}
    files.update(tree(os.path.join(peer, "gazebo_plugins", "test"), "gazebo_plugins/test"))
    files.update(tree(os.path.join(peer, "gazebo_plugins", "test2"), "gazebo_plugins/test2"))
    files.update(tree(os.path.join(peer, "gazebo_plugins", "scripts"), "gazebo_plugins/scripts"))
    files.update(tree(os.path.join(peer, "gazebo_ros", "launch"), "gazebo_ros/launch"))
    files.update(tree(os.path.join(peer, "gazebo_ros", "test"), "gazebo_ros/test"))
    files.update(tree(os.path.join(peer, "gazebo_plugins", "test2"), "gazebo_tests/test"))
    for entry in ("gzserver", "gazebo", "debug"):
        files["gazebo_ros/scripts/" + entry] = (
            ENTRY.format(entry=entry, here=HERE).encode(), 0o755)
    files["gazebo_ros/scripts/gzclient"] = (GZCLIENT.encode(), 0o755)
    files["gazebo_ros/scripts/spawn_model"] = (SPAWN_MODEL.encode(), 0o755)
    # test2's executables go where its launch files' <test pkg=...> look for them.
    wanted = set()
    for test in old_tests:
        launch = files.get("gazebo_tests/" + test.path, (b"", 0))[0].decode("utf-8", "replace")
        wanted.update(peer_plan.launch_test_nodes(launch))
    exes = {"gazebo_plugins": list(plugin_exes), "gazebo_ros": [], "gazebo_tests": []}
    for exe in old_exes:
        if ("gazebo_tests", exe.name) in wanted:
            exes["gazebo_tests"].append(exe)
        if ("gazebo_plugins", exe.name) in wanted:   # test2/ is its test/ there
            exes["gazebo_plugins"].append(exe._replace(sources=[
                "test2/" + s[len("test/"):] for s in exe.sources]))
    for package, package_exes in exes.items():
        sources = "".join(files.get(package + "/" + s, (b"", 0))[0].decode("utf-8", "replace")
                          for e in package_exes for s in e.sources)
        services = peer_plan.compat_services(sources)
        for service in services:
            files["%s/%s/gazebo/%s.h" % (package, peer_plan.COMPAT_DIR, service)] = (
                peer_plan.compat_header(service).encode(), 0o644)
        files[package + "/CMakeLists.txt"] = (
            peer_plan.cmakelists(package, package_exes, compat=bool(services)).encode(), 0o644)
        version = upstream_version(peer, "gazebo_plugins")
        files[package + "/package.xml"] = (peer_plan.package_xml(
            package, version, "gazebo_ros_pkgs %s's %s tests for make peer" % (
                fetch_peer.PEER_COMMIT[:8], package)).encode(), 0o644)
    built = {(p, e.name): e for p, package_exes in exes.items() for e in package_exes}
    tests = peer_plan.ordered(plugin_tests + ros_tests + old_tests)
    return files, tests, built


def sync(files):
    """Write ``files`` into catkin_ws/peer/src (a file only when it differs, so make sees what
    changed), remove what is not among them; return the digest of them all and of the
    gazebo_msgs headers they are built with."""
    src = os.path.join(WS, "src")
    digest = hashlib.sha256()
    for rel in sorted(files):
        data, mode = files[rel]
        digest.update(b"%s\0%o\0%d\0" % (rel.encode(), mode, len(data)) + data)
        path = os.path.join(src, rel)
        if not os.path.isfile(path) or read(path) != data:
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "wb") as handle:
                handle.write(data)
        if os.stat(path).st_mode & 0o777 != mode:
            os.chmod(path, mode)
    # What the build reads from the project's workspace: gazebo_msgs' headers.
    for header in sorted(glob.glob(os.path.join(MAIN_DEVEL, "include", "gazebo_msgs", "*.h"))):
        digest.update(b"%s\0" % os.path.basename(header).encode() + read(header))
    packages = {rel.split("/")[0] for rel in files}
    for name in os.listdir(src):
        if os.path.isdir(os.path.join(src, name)) and name not in packages:
            shutil.rmtree(os.path.join(src, name))
    for folder, _, names in os.walk(src):
        for name in names:
            rel = os.path.relpath(os.path.join(folder, name), src)
            if "/" in rel and rel not in files:
                os.unlink(os.path.join(folder, name))
    return digest.hexdigest()


def build_env():
    """The environment for catkin_make: /usr/bin first (a pyenv python3 breaks catkin's
    configure step), the project's workspace sourced (its gazebo_msgs)."""
    env = dict(os.environ)
    env["PATH"] = "/usr/bin:/bin:" + env.get("PATH", "")
    return env


def build(digest, built):
    """catkin_make the scratch workspace unless its stamp says this digest was built; return
    {(pkg, exe): the first compiler error} of the executables that did not build."""
    try:
        with open(STAMP, encoding="utf-8") as handle:
            stamp = json.load(handle)
    except (OSError, ValueError):
        stamp = {}
    if stamp.get("digest") == digest and all(
            os.path.isfile(exe_path(p, e)) or "%s/%s" % (p, e) in stamp.get("failed", {})
            for p, e in built):
        say("scratch workspace %s up to date: nothing to build" % os.path.relpath(WS, ROOT))
        return {tuple(k.split("/")): v for k, v in stamp.get("failed", {}).items()}
    say("building %d test executables in %s (catkin_make; a few minutes the first time)"
        % (len(built), os.path.relpath(WS, ROOT)))
    t0 = time.time()
    log_path = os.path.join(WS, "build.log")
    with open(log_path, "w", encoding="utf-8") as log:
        status = subprocess.run(
            ["/usr/bin/catkin_make", "-C", WS, "-DPYTHON_EXECUTABLE=/usr/bin/python3",
             "-j2", "-k"], stdout=log, stderr=subprocess.STDOUT,
            env=build_env()).returncode
    with open(log_path, encoding="utf-8", errors="replace") as log:
        lines = log.read().splitlines()
    if status != 0 and (not os.path.isfile(os.path.join(WS, "devel", "setup.bash"))
                        or 'Invoking "cmake" failed' in lines):
        sys.stderr.write("\n".join(lines[-20:]) + "\n")
        sys.exit("make peer: catkin_make's cmake step failed (the last lines are above; %s)"
                 % log_path)
    failed = {}
    for (package, name), exe in sorted(built.items()):
        if not os.path.isfile(exe_path(package, name)):
            bases = [os.path.basename(s) for s in exe.sources]
            first = next((line for line in lines if "error" in line and
                          any(b in line for b in bases)), "")
            failed["%s/%s" % (package, name)] = "not built: %s" % (
                peer_plan.first_line(re.sub(r"^\S*/", "", first)) or "see " + log_path)
    os.makedirs(os.path.dirname(STAMP), exist_ok=True)
    with open(STAMP, "w", encoding="utf-8") as handle:
        json.dump({"digest": digest, "failed": failed}, handle, indent=1)
    say("built in %.0f s%s" % (time.time() - t0, "; not built: %s" % ", ".join(failed)
                               if failed else ""))
    return {tuple(k.split("/")): v for k, v in failed.items()}


def exe_path(package, name):
    return os.path.join(WS, "devel", "lib", package, name)


# --- running ------------------------------------------------------------------------------------

def run_env():
    """os.environ with catkin_ws/peer/devel/setup.bash sourced (it chains catkin_ws/devel), and
    PEER_MODELS last on GAZEBO_MODEL_PATH (the models upstream's worlds include that Gazebo
    does not install: checkerboard_plane)."""
    out = subprocess.run(["bash", "-c", 'source "$1" && env -0', "bash",
                          os.path.join(WS, "devel", "setup.bash")],
                         capture_output=True, check=True).stdout.decode("utf-8", "replace")
    env = dict(item.split("=", 1) for item in out.split("\0") if "=" in item)
    env["GAZEBO_MODEL_PATH"] = os.pathsep.join(
        p for p in (env.get("GAZEBO_MODEL_PATH", ""), PEER_MODELS) if p)
    return env


def run_once(test, env, limit, log_path):
    """One rostest run of ``test``: a RunResult."""
    home = tempfile.mkdtemp(prefix="peer_ros_home_")
    results = os.path.join(home, "test_results")
    path = os.path.join(WS, "src", test.package, test.path)
    env = dict(env, ROS_HOME=home)
    launch = read(path).decode("utf-8", "replace")
    if any(node in SHIMMED_NODES for _, node in peer_plan.launch_test_nodes(launch)):
        env["PYTHONPATH"] = SHIM_DIR + os.pathsep + env.get("PYTHONPATH", "")
    t0 = time.time()
    try:
        with open(log_path, "w", encoding="utf-8") as log:
            proc = subprocess.Popen(["rostest", "--results-base-dir", results, path], env=env,
                                    stdout=log, stderr=subprocess.STDOUT,
                                    start_new_session=True, cwd=home)
            timed_out = not _exited(proc, limit)
            status = stop_process(proc, STOP_WAIT, sig=signal.SIGINT if timed_out else None)
        seconds = time.time() - t0
        src = os.path.join(WS, "src") + os.sep   # paths in the table: from the packages
        with open(log_path, encoding="utf-8", errors="replace") as log:
            output = log.read().replace(src, "")
        xml = [read(p).decode("utf-8", "replace").replace(src, "")
               for p in sorted(glob.glob(os.path.join(results, "**", "*.xml"), recursive=True))]
        result = peer_plan.run_result(status, output, xml, seconds)
        if timed_out:
            result = result._replace(passed=False,
                                     failure="no end within %.0f s (stopped)" % limit)
        return result
    finally:
        shutil.rmtree(home, ignore_errors=True)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--only", help="tests to run, comma-separated names")
    parser.add_argument("--runs", type=int, help="runs of each test (default: 1; "
                        "set_model_state_test 10)")
    parser.add_argument("--limit", type=float, default=RUN_LIMIT, help="wall s per run")
    parser.add_argument("--out", default=os.path.join(tempfile.gettempdir(),
                                                      "tutorial_turtlebot_peer.md"))
    args = parser.parse_args(argv)
    peer = fetch_peer.peer_src()
    faults = fetch_peer.check(peer)
    if faults:
        sys.exit("make peer: no gazebo_ros_pkgs %s tree in %s (%s): %s"
                 % (fetch_peer.PEER_COMMIT[:8], peer, faults[0], fetch_peer.how_to_make(peer)))
    if not os.path.isfile(os.path.join(MAIN_DEVEL, "setup.bash")):
        sys.exit("make peer: no %s: run make setup first" % MAIN_DEVEL)
    files, tests, built = plan(peer)
    if args.only:
        names = args.only.split(",")
        unknown = sorted(set(names) - {t.name for t in tests})
        if unknown:
            sys.exit("make peer: no test %s; the tests: %s"
                     % (", ".join(unknown), ", ".join(t.name for t in tests)))
        tests = [t for t in tests if t.name in names]
    t_start = time.time()
    install_packages()
    os.makedirs(os.path.join(WS, "src"), exist_ok=True)
    digest = sync(files)
    with open(os.path.join(ROOT, "tools", "peer", "yaml_shim.py"), "rb") as handle:
        shim = handle.read()
    os.makedirs(SHIM_DIR, exist_ok=True)
    with open(os.path.join(SHIM_DIR, "sitecustomize.py"), "wb") as handle:
        handle.write(shim)
    not_built = build(digest, built)
    env = run_env()
    os.makedirs(LOGS, exist_ok=True)
    say("%d tests of gazebo_ros_pkgs %s from %s, %s, %d cores"
        % (len(tests), fetch_peer.PEER_COMMIT[:8], peer, socket.gethostname(), os.cpu_count()))
    rows = []
    for test in tests:
        launch = read(os.path.join(WS, "src", test.package, test.path))
        launch = launch.decode("utf-8", "replace")
        missing = [not_built[(p, t)] for p, t in peer_plan.launch_test_nodes(launch)
                   if (p, t) in not_built]
        if missing:
            rows.append((test, [peer_plan.RunResult(False, 0.0, missing[0])]))
            say("%s: %s" % (test.name, missing[0]))
            continue
        results = []
        runs = args.runs or test.runs
        for number in range(runs):
            log_path = os.path.join(LOGS, "%s-%d.log" % (test.name, number + 1))
            result = run_once(test, env, args.limit, log_path)
            results.append(result)
            outcome = "passed" if result.passed else "FAILED: " + result.failure
            say("%s run %d/%d: %s (%.0f s)"
                % (test.name, number + 1, runs, outcome, result.seconds))
        rows.append((test, results))
    header = ("make peer, %s, %s (%d cores): gazebo_ros_pkgs %s, %.0f s in all"
              % (time.strftime("%Y-%m-%d"), socket.gethostname(), os.cpu_count(),
                 fetch_peer.PEER_COMMIT[:8], time.time() - t_start))
    table = peer_plan.format_table(rows, header)
    with open(args.out, "w", encoding="utf-8") as handle:
        handle.write(table + "\n")
    print("table: %s; each run's output: %s" % (args.out, LOGS))
    print(table, flush=True)
    return 0 if table.endswith(" 0 failed") else 1


if __name__ == "__main__":
    sys.exit(main())
