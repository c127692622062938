"""The sim registers again with a ROS master that was restarted: its topics, its services,
/use_sim_time and /robot_description, so that a subscriber or a service caller that comes after
the restart finds it. Runs its own ``rosmaster --core`` (not roslaunch, which would end with
it) and the sim as ``rosrun tutorial_turtlebot sim``; skipped without the ROS binaries."""
import os
import shutil
import signal
import subprocess
import threading
import time
import xmlrpc.client

import pytest

from unit_helpers import free_port, stop_process, wait_for

pytestmark = pytest.mark.skipif(
    not (shutil.which("rosmaster") and shutil.which("rostopic") and shutil.which("rosservice")),
    reason="needs the ROS binaries (rosmaster, rostopic, rosservice)")

REGISTERED_WITHIN = 5.0   # wall s after the new master answers
WAIT = 90.0               # wall s for the sim to come up on a loaded machine
CALLER = "/test_master_watch"
DESCRIPTION = "<robot name='kept'><link name='base'/></robot>"
TOPICS = ("/odom", "/scan", "/clock", "/tf", "/imu", "/joint_states")
SERVICES = ("/gazebo/get_world_properties", "/gazebo/reset_world", "/gazebo/spawn_urdf_model",
            "/gazebo/get_model_state", "/gazebo/pause_physics")


def sim_executable() -> str:
    try:
        import roslib.packages
    except ImportError:
        pytest.skip("no roslib in this Python")
    found = roslib.packages.find_node("tutorial_turtlebot", "sim")
    if not found:
        pytest.skip("the sim node is not built (no devel space)")
    return found[0]


class Process:
    """A child process with its output collected (both streams)."""

    def __init__(self, args, env):
        self.proc = subprocess.Popen(args, env=env, stdin=subprocess.DEVNULL,
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     start_new_session=True)
        self.lines = []
        threading.Thread(target=self._drain, daemon=True).start()

    def _drain(self):
        for line in iter(self.proc.stdout.readline, b""):
            self.lines.append(line.decode("utf-8", "replace"))

    @property
    def output(self) -> str:
        return "".join(self.lines)

    def stop(self, sig=signal.SIGINT, timeout: float = 20.0):
        stop_process(self.proc, timeout, sig)


class Master:
    """A ``rosmaster --core`` on ``port``, and questions to it."""

    def __init__(self, port: int, env):
        self.uri = "http://127.0.0.1:%d/" % port
        self.process = Process(["rosmaster", "--core", "-p", str(port)], env)
        assert wait_for(self.pid, 30.0), "rosmaster did not start:\n" + self.process.output

    def api(self):
        return xmlrpc.client.ServerProxy(self.uri)

    def pid(self):
        try:
            return self.api().getPid(CALLER)[2]
        except OSError:
            return None

    def state(self):
        """({topic: publishers}, {service: providers})."""
        code, _, (pubs, _, srvs) = self.api().getSystemState(CALLER)
        return dict(pubs), dict(srvs)

    def param(self, name):
        code, _, value = self.api().getParam(CALLER, name)
        return value if code == 1 else None


def sim_registered(master: Master):
    pubs, srvs = master.state()
    return (all("/gazebo" in pubs.get(t, ()) for t in TOPICS)
            and all("/gazebo" in srvs.get(s, ()) for s in SERVICES))


@pytest.fixture
def ros(tmp_path):
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:%d/" % port,
               ROS_LOG_DIR=str(tmp_path), ROS_HOME=str(tmp_path), ROS_IP="127.0.0.1")
    env.pop("ROS_HOSTNAME", None)
    env.pop("PYTHONUNBUFFERED", None)   # as on a user's machine: the sim's lines come when said
    running = []
    yield port, env, running
    for process in reversed(running):
        process.stop()


def test_the_sim_registers_again_with_a_restarted_master(ros):
    port, env, running = ros
    master = Master(port, env)
    running.append(master.process)
    api = master.api()
    api.setParam(CALLER, "/use_sim_time", True)          # as sim.launch sets them
    api.setParam(CALLER, "/robot_description", DESCRIPTION)
    sim = Process([sim_executable(), "_world:=empty", "_status_period:=0"], env)
    running.insert(0, sim)
    assert wait_for(lambda: sim_registered(master), WAIT), "the sim did not come up:\n" \
        + sim.output
    time.sleep(2.0)   # the watch has looked at the first master (once a second)

    master.process.stop(signal.SIGINT)
    master = Master(port, env)                           # the same URI, a new master
    restarted = time.monotonic()
    running.append(master.process)
    assert wait_for(lambda: sim_registered(master), REGISTERED_WITHIN, 0.02), \
        "not registered again within %.0f s: %s\n%s" % (REGISTERED_WITHIN, master.state(),
                                                        sim.output)
    took = time.monotonic() - restarted
    assert wait_for(lambda: master.param("/robot_description") == DESCRIPTION, 2.0)
    assert master.param("/use_sim_time") is True
    print("registered again %.2f s after the new master answered" % took)

    # Clients that come after the restart find the sim and talk to it.
    run = subprocess.run(["rostopic", "echo", "-n", "1", "/odom"], env=env, capture_output=True,
                         text=True, timeout=WAIT)
    assert run.returncode == 0 and "pose:" in run.stdout, run.stdout + run.stderr
    run = subprocess.run(["rosservice", "call", "/gazebo/get_world_properties"], env=env,
                         capture_output=True, text=True, timeout=WAIT)
    assert run.returncode == 0 and "success: True" in run.stdout, run.stdout + run.stderr
    lines = [line for line in sim.output.splitlines() if "ROS master restarted" in line]
    assert len(lines) == 1, sim.output
    assert "registered again" in lines[0] and "2 parameters" in lines[0], lines[0]
    assert "Traceback" not in sim.output, sim.output
