"""A lab node that publishes from its main thread stops cleanly on Ctrl-C even when the signal
arrives in the middle of a publish (no ROS master; the node runs in a child process, as a
shutdown ends rospy for the whole process)."""
import os
import subprocess
import sys
import unit_paths

ROOT = unit_paths.ROOT
SCRIPT = """
import os, signal, sys, time
import rospy
from tutorial_turtlebot.lab import lab_node

class Recording:
    def __init__(self):
        self.sent = []
    def publish(self, msg):
        self.sent.append((msg.linear.x, msg.angular.z))
        if len(self.sent) == 1:          # Ctrl-C lands while the command is being published
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.2)              # the handler runs here, in this (main) thread

if sys.argv[1] == "ours":
    lab_node.shut_down_on_signals()
else:                                    # what rospy's own handler does: the hooks in place
    signal.signal(signal.SIGINT, lambda *_: rospy.signal_shutdown("Ctrl-C"))
lab_node.SHUTDOWN_GRACE = 0.0
publisher = lab_node.CommandPublisher()
recording = publisher._publisher = Recording()
publisher.publish(0.2, 0.5)
publisher.publish(0.2, 0.5)              # after the shutdown began: dropped
for _ in range(100):
    if rospy.is_shutdown():
        break
    time.sleep(0.05)
print(recording.sent, flush=True)
"""


def run(handler, timeout):
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        p for p in (os.path.join(ROOT, "src"), os.environ.get("PYTHONPATH")) if p),
        ROS_MASTER_URI="http://localhost:9")
    try:
        done = subprocess.run([sys.executable, "-c", SCRIPT, handler], capture_output=True,
                              text=True, timeout=timeout, env=env)
    except subprocess.TimeoutExpired:
        return None
    return done.stdout.strip().splitlines()[-1] if done.stdout.strip() else done.stderr


def test_ctrl_c_in_the_middle_of_a_publish_sends_the_zero_twist_last():
    """The command being published goes out (and the next, if it was quicker than the
    shutdown), then the zero Twist, once; nothing after it."""
    sent = run("ours", 30)
    assert sent in ("[(0.2, 0.5), (0.0, 0.0)]", "[(0.2, 0.5), (0.2, 0.5), (0.0, 0.0)]"), sent


def test_the_hooks_in_the_interrupted_thread_would_hang():
    """Why: run in the interrupted main thread (rospy's own handler), the zero-Twist hook waits
    for the lock that thread holds, forever."""
    assert run("in place", 5) is None
