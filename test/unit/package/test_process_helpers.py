"""test/process_helpers.py, which the unit tests, the rostests and the bench share, on real
processes: free_port gives a port one can bind, wait_for returns the predicate's value or gives
up on time, stop_process ends what ignores SIGINT (and SIGTERM) and what is left of its process
group, cpu_seconds and rss_kb read what a busy or big child uses."""
import os
import signal
import socket
import subprocess
import sys
import time

import pytest

import unit_paths

sys.path.insert(0, os.path.join(unit_paths.ROOT, "test"))
import process_helpers  # noqa: E402
from process_helpers import (cpu_seconds, free_port, rss_kb, signal_process,  # noqa: E402
                             stop_process, wait_for)

# a Python child that ignores the signals named in IGNORE, then says "ready". It first sets
# SIGINT and SIGTERM to their default (a child inherits an ignored SIGINT: a shell's background
# job, as in CI's Debian 13 pass, has one)
CHILD = """
import signal, time
signal.signal(signal.SIGINT, signal.SIG_DFL)
signal.signal(signal.SIGTERM, signal.SIG_DFL)
for name in %r:
    signal.signal(getattr(signal, name), signal.SIG_IGN)
print("ready", flush=True)
time.sleep(120)
"""
# the same, after starting a child in its process group that ignores SIGINT and SIGTERM; it
# says "ready CHILD_PID"
PARENT = """
import signal, subprocess, sys, time
signal.signal(signal.SIGINT, signal.SIG_DFL)
signal.signal(signal.SIGTERM, signal.SIG_DFL)
for name in %r:
    signal.signal(getattr(signal, name), signal.SIG_IGN)
child = subprocess.Popen([sys.executable, "-c", %r], stdout=subprocess.PIPE)
assert child.stdout.readline() == b"ready\\n"
print("ready", child.pid, flush=True)
time.sleep(120)
"""


def child(*ignore):
    return CHILD % (ignore,)


def parent(*ignore):
    return PARENT % (ignore, child("SIGINT", "SIGTERM"))


def start(code, own_group=True):
    """A Python child running ``code``, once it has said "ready" (in a session of its own unless
    ``own_group`` is false); (Popen, the words after "ready")."""
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE,
                            start_new_session=own_group)
    line = proc.stdout.readline().split()
    assert line[:1] == [b"ready"], line
    return proc, line[1:]


def alive(pid) -> bool:
    """Whether ``pid`` is a running process (not gone, not a zombie)."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


@pytest.fixture
def cleanup():
    """Processes SIGKILLed at the end whatever happened (the helper under test may be broken)."""
    procs, pids = [], []
    yield procs, pids
    for proc in procs:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    for pid in pids:
        try:
            os.kill(pid, signal.SIGKILL)
        except ProcessLookupError:
            pass


# --- free_port ---------------------------------------------------------------------------------

def test_free_port_can_be_bound_and_nothing_listens_there():
    port = free_port()
    assert 1024 <= port <= 65535
    with socket.socket() as probe:     # nothing listens: a connection is refused
        assert probe.connect_ex(("127.0.0.1", port)) != 0
    with socket.socket() as sock:      # and it is ours to take
        sock.bind(("127.0.0.1", port))
        sock.listen(1)


def test_free_port_changes():
    assert len({free_port() for _ in range(5)}) > 1


# --- wait_for ----------------------------------------------------------------------------------

def test_wait_for_returns_the_predicates_value_once_true():
    calls = []

    def predicate():
        calls.append(time.monotonic())
        return ["found"] if len(calls) >= 3 else []
    assert wait_for(predicate, 5.0, 0.05) == ["found"]
    assert len(calls) == 3
    assert calls[2] - calls[0] >= 0.09          # it slept ``step`` between calls


def test_wait_for_times_out_with_the_last_falsy_value():
    start = time.monotonic()
    assert wait_for(lambda: 0, 0.3, 0.02) == 0
    assert 0.3 <= time.monotonic() - start < 2.0


def test_wait_for_gives_up_when_asked():
    start = time.monotonic()
    assert wait_for(lambda: None, 30.0, 0.02, give_up=lambda: True) is None
    assert time.monotonic() - start < 2.0


# --- stop_process ------------------------------------------------------------------------------

def test_stop_process_interrupts_as_ctrl_c_does(cleanup):
    proc, _ = start(child())
    cleanup[0].append(proc)
    started = time.monotonic()
    assert stop_process(proc, 10.0) == -signal.SIGINT
    assert proc.returncode == -signal.SIGINT     # reaped
    assert time.monotonic() - started < 5.0


def test_stop_process_wakes_a_suspended_process(cleanup):
    proc, _ = start(child())
    cleanup[0].append(proc)
    proc.send_signal(signal.SIGSTOP)
    assert stop_process(proc, 10.0) == -signal.SIGINT


def test_stop_process_sends_sigterm_to_what_ignores_sigint(cleanup):
    proc, _ = start(child("SIGINT"))
    cleanup[0].append(proc)
    started = time.monotonic()
    assert stop_process(proc, 0.5) == -signal.SIGTERM
    assert 0.5 <= time.monotonic() - started < 5.0


def test_stop_process_kills_what_ignores_sigint_and_sigterm_and_its_group(cleanup, monkeypatch):
    monkeypatch.setattr(process_helpers, "TERM_WAIT", 0.5)
    proc, words = start(parent("SIGINT", "SIGTERM"))
    grandchild = int(words[0])
    cleanup[0].append(proc)
    cleanup[1].append(grandchild)
    assert alive(grandchild)
    started = time.monotonic()
    assert stop_process(proc, 0.5) == -signal.SIGKILL
    assert 1.0 <= time.monotonic() - started < 5.0
    assert wait_for(lambda: not alive(grandchild), 5.0)


def test_stop_process_ends_what_is_left_of_the_group_after_its_leader(cleanup):
    # the leader ends on SIGINT; its child ignores SIGINT and SIGTERM and would outlive it
    proc, words = start(parent())
    grandchild = int(words[0])
    cleanup[0].append(proc)
    cleanup[1].append(grandchild)
    started = time.monotonic()
    assert stop_process(proc, 10.0) == -signal.SIGINT
    assert time.monotonic() - started < 5.0
    assert wait_for(lambda: not alive(grandchild), 5.0)


def test_stop_process_of_a_child_in_our_group_signals_it_alone(cleanup):
    # were our own process group signalled, this test (and pytest) would end here
    proc, _ = start(child(), own_group=False)
    cleanup[0].append(proc)
    assert os.getpgid(proc.pid) == os.getpgrp()
    assert stop_process(proc, 10.0) == -signal.SIGINT


def test_stop_process_after_a_signal_already_sent_only_waits(cleanup):
    proc, _ = start(child("SIGINT"))
    cleanup[0].append(proc)
    signal_process(proc, signal.SIGTERM)
    assert stop_process(proc, 10.0, sig=None) == -signal.SIGTERM


def test_stop_process_of_an_ended_process_returns_its_status():
    proc = subprocess.Popen([sys.executable, "-c", "raise SystemExit(3)"],
                            start_new_session=True)
    proc.wait()
    assert stop_process(proc, 1.0) == 3


# --- cpu_seconds and rss_kb --------------------------------------------------------------------

BUSY = "import time\nend = time.process_time() + %g\nwhile time.process_time() < end: pass\n"


def test_cpu_seconds_of_a_busy_child_grows_and_of_a_sleeping_one_does_not(cleanup):
    busy = subprocess.Popen([sys.executable, "-c", BUSY % 30 + "print('x')"])
    cleanup[0].append(busy)
    idle, _ = start(child())
    cleanup[0].append(idle)
    time.sleep(0.2)
    busy0, idle0 = cpu_seconds(busy.pid), cpu_seconds(idle.pid)
    time.sleep(1.0)
    assert cpu_seconds(busy.pid) - busy0 >= 0.3
    assert cpu_seconds(idle.pid) - idle0 < 0.1


def test_cpu_seconds_with_children_counts_the_waited_for_children(cleanup):
    code = ("import subprocess, sys, time\nsubprocess.run([sys.executable, '-c', %r])\n"
            "print('ready', flush=True)\ntime.sleep(120)\n" % (BUSY % 0.6))
    proc, _ = start(code)
    cleanup[0].append(proc)
    own = cpu_seconds(proc.pid)
    assert cpu_seconds(proc.pid, children=True) - own >= 0.5


def test_cpu_seconds_of_this_process_grows():
    before = cpu_seconds()
    end = time.process_time() + 0.3
    while time.process_time() < end:
        pass
    assert cpu_seconds() - before >= 0.2


def test_rss_kb_of_a_child_that_fills_100_mb(cleanup):
    proc, _ = start(child())
    cleanup[0].append(proc)
    big, _ = start("import time\nb = b'x' * (100 << 20)\nprint('ready', flush=True)\n"
                   "time.sleep(120)\n")
    cleanup[0].append(big)
    assert 0 < rss_kb(proc.pid) < 80 << 10
    assert rss_kb(big.pid) - rss_kb(proc.pid) >= 90 << 10
    assert rss_kb() > 0                      # this process


def test_rss_kb_of_a_zombie_is_none():
    proc = subprocess.Popen(["true"])
    os.waitid(os.P_PID, proc.pid, os.WEXITED | os.WNOWAIT)   # ended, not reaped
    try:
        assert rss_kb(proc.pid) is None
    finally:
        proc.wait()


def test_a_node_is_found_by_its_name_and_its_master_port():
    env = dict(os.environ, ROS_MASTER_URI="http://127.0.0.1:54321/")
    child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(30)",
                              "__name:=some_node"], env=env)
    try:
        found = process_helpers.wait_for(
            lambda: process_helpers.node_on_master("some_node", 54321), 10.0)
        assert found == child.pid
        assert process_helpers.node_on_master("some_node", 54322) is None
        assert process_helpers.node_on_master("other_node", 54321) is None
    finally:
        child.kill()
        child.wait()
