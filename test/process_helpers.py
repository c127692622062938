"""Process helpers shared by the unit tests (test/unit/unit_helpers.py), the rostest nodes
(test/rostest/sim_test_support.py) and the bench (bench/*.py): a free local port, stopping a
child process and its process group, its CPU time and resident memory, waiting on a condition.
Pure standard library, Python 3.8, Linux (/proc). Each user puts this folder on sys.path (an
absolute path computed from its own __file__) and imports it by name."""
import os
import signal
import socket
import time

TERM_WAIT = 5.0   # s stop_process gives a process between SIGTERM and SIGKILL


def free_port() -> int:
    """A local TCP port (on 127.0.0.1) where nothing listens: bound, then closed."""
    with socket.socket() as sock:
        sock.bind(("127.0.0.1", 0))
        return sock.getsockname()[1]


def wait_for(predicate, timeout: float, step: float = 0.02, give_up=None):
    """Call ``predicate`` every ``step`` s until it returns a true value or ``timeout`` s of
    wall time pass (or ``give_up()`` is true, e.g. rospy.is_shutdown); return that value, or
    the falsy value of one last call once time is up."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline and not (give_up is not None and give_up()):
        value = predicate()
        if value:
            return value
        time.sleep(step)
    return predicate()


def _group_of(proc):
    """``proc``'s process group id if it leads a group of its own (start_new_session, setsid)
    and is not yet reaped; None if it shares ours (signal it alone) or is gone."""
    if proc.returncode is not None:
        return None
    try:
        pgid = os.getpgid(proc.pid)
    except ProcessLookupError:
        return None
    return pgid if pgid == proc.pid and pgid != os.getpgrp() else None


def signal_process(proc, sig) -> None:
    """Send ``sig`` to ``proc``'s process group if it leads one of its own, else to ``proc``
    alone (never to our own group); nothing if it has been reaped."""
    group = _group_of(proc)
    try:
        if group is not None:
            os.killpg(group, sig)
        elif proc.returncode is None:
            os.kill(proc.pid, sig)
    except (ProcessLookupError, PermissionError):
        pass


def _exited(proc, timeout: float) -> bool:
    """Whether ``proc`` exits within ``timeout`` s; it is left unreaped (a zombie), so that
    its pid and process group id cannot be reused meanwhile."""
    deadline = time.monotonic() + timeout
    delay = 0.001
    while proc.returncode is None:
        try:
            if os.waitid(os.P_PID, proc.pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is not None:
                return True
        except ChildProcessError:   # reaped by someone else
            proc.poll()
            return True
        left = deadline - time.monotonic()
        if left <= 0:
            return False
        time.sleep(min(delay, left))
        delay = min(2 * delay, 0.05)
    return True


def stop_process(proc, timeout: float = 20.0, sig=signal.SIGINT):
    """Stop a subprocess.Popen as Ctrl-C does and make sure it is gone; return its exit status.

    SIGCONT (in case it was suspended) and ``sig`` (None: it was already signalled) to its
    process group (to it alone if it shares ours), up to ``timeout`` s to exit, then SIGTERM
    and up to TERM_WAIT s, then SIGKILL. Once it has exited, whatever is left of its group
    (children that outlived it) is SIGKILLed; then it is reaped."""
    group = _group_of(proc)
    if group is None and proc.returncode is not None:
        return proc.returncode
    if sig is not None:
        signal_process(proc, signal.SIGCONT)
        signal_process(proc, sig)
    for wait, then in ((timeout, signal.SIGTERM), (TERM_WAIT, signal.SIGKILL)):
        if _exited(proc, wait):
            break
        signal_process(proc, then)
    if group is not None:
        try:
            os.killpg(group, signal.SIGKILL)   # the leader is a zombie: group id still ours
        except (ProcessLookupError, PermissionError):
            pass
    return proc.wait()


def _stat_fields(pid):
    """The fields of /proc/PID/stat after the command name (fields[0] is the state)."""
    with open("/proc/%s/stat" % pid) as f:
        return f.read().rsplit(")", 1)[1].split()


def cpu_seconds(pid="self", children: bool = False) -> float:
    """CPU seconds (user + system) process ``pid`` has used so far; with ``children``, plus
    those of its children it has waited for (reaped)."""
    fields = _stat_fields(pid)
    ticks = int(fields[11]) + int(fields[12])
    if children:
        ticks += int(fields[13]) + int(fields[14])
    return ticks / os.sysconf("SC_CLK_TCK")


def rss_kb(pid="self"):
    """Resident memory (KB, VmRSS) of process ``pid``; None if it has none (a zombie)."""
    with open("/proc/%s/status" % pid) as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    return None


def node_on_master(name: str, port: int):
    """The pid of the process running ROS node ``name`` (its ``__name:=`` argument) on the
    master at local ``port`` (its ROS_MASTER_URI in its environment), None if there is none."""
    wanted = b"__name:=" + name.encode()
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            with open("/proc/%s/cmdline" % pid, "rb") as f:
                cmd = f.read().split(b"\0")
            with open("/proc/%s/environ" % pid, "rb") as f:
                env = f.read().split(b"\0")
        except OSError:
            continue
        master = [e for e in env if e.startswith(b"ROS_MASTER_URI=")]
        if (wanted in cmd and master
                and master[0].rstrip(b"/").endswith(b":%d" % port)):
            return int(pid)
    return None
