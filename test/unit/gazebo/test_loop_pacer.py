"""gazebo/loop_pacer.py: when the loop's next step may run (the batch end against the wall
clock, the catch-up bound), its sleep that a request or a stop cuts short, and the /clock
throttle (Gazebo's ~pub_clock_frequency)."""
import threading
import time

import pytest

from tutorial_turtlebot.gazebo.loop_pacer import SHORT_SLEEP, WAKE_CHECK, LoopPacer
from tutorial_turtlebot.sim.world.pacing import Pacer


def pacer(rtf=1.0, pub_clock_frequency=0.0, stopping=lambda: False):
    return LoopPacer(rtf, threading.Event(), stopping, pub_clock_frequency)


def test_the_next_step_waits_for_the_wall_clock_once_a_batch_is_ahead():
    p = pacer(0.5)                      # half real time: 1 sim ms is 2 wall ms
    start = time.monotonic()
    p.restart(0.0)
    assert p.batch_end(0.001) is None   # 2 ms ahead: step on (the batch is 20 ms)
    end = p.batch_end(0.02)             # 40 ms ahead: sleep until the sim time is due
    assert end == pytest.approx(start + 0.04, abs=0.005)
    assert p.wall_of(0.02) == end


def test_as_fast_as_possible_never_waits():
    p = pacer(0.0)
    assert p.batch_end(1000.0) is None


def test_a_stall_longer_than_the_catch_up_bound_is_forgiven():
    p = pacer(1.0)
    p.restart(0.0)
    time.sleep(Pacer.MAX_LAG + 0.05)    # the loop stalled: 0.3 s behind
    assert p.ahead(0.0) == 0.0          # not raced to repay
    assert p.wall_of(0.0) == pytest.approx(time.monotonic(), abs=0.01)   # re-anchored now
    behind = pacer(1.0)
    behind.restart(0.0)
    time.sleep(0.1)                     # within the bound: owed
    assert behind.ahead(0.0) == pytest.approx(-0.1, abs=0.03)


def test_the_sleep_lasts_until_its_wall_time():
    p = pacer()
    for delay in (SHORT_SLEEP / 2, 0.15):
        start = time.monotonic()
        assert p.sleep_until(start + delay) is True
        assert time.monotonic() - start == pytest.approx(delay, abs=0.01)


def test_a_request_cuts_a_long_sleep_short():
    p = pacer()
    threading.Timer(0.05, p._wake.set).start()
    start = time.monotonic()
    assert p.sleep_until(start + 2.0) is False
    assert time.monotonic() - start < 0.05 + 0.03


def test_a_stop_ends_a_long_sleep_within_wake_check():
    stop = []
    p = pacer(stopping=lambda: bool(stop))
    threading.Timer(0.05, lambda: stop.append(1)).start()
    start = time.monotonic()
    assert p.sleep_until(start + 2.0) is False
    assert time.monotonic() - start < 0.05 + WAKE_CHECK + 0.03


def test_clock_at_most_one_a_gap_by_its_due_wall_time():
    p = pacer(1.0, pub_clock_frequency=100.0)        # gap 10 ms
    p.restart(0.0)
    assert p.clock_due(0.0) is True
    assert p.clock_due(0.005) is False               # due 5 ms later: within the gap
    assert p.clock_due(0.010) is True
    p.clock_anew()
    assert p.clock_due(0.011) is True                # after a reset: whatever the gap
    assert pacer(1.0, pub_clock_frequency=0.0).clock_due(0.0) is True
    unlimited = pacer(1.0)
    assert all(unlimited.clock_due(k * 1e-6) for k in range(10))


def test_a_camera_frame_is_skipped_while_the_loop_is_behind_the_wall_clock():
    p = pacer(1.0)
    p.restart(0.0)
    assert p.frame_in_time(0.100) is True            # due 100 ms from now: drawn
    time.sleep(0.05)                                 # a frame took 50 ms: the loop is late
    assert p.frame_in_time(0.033) is False           # due 17 ms ago: skipped
    assert p.frame_in_time(0.200) is True            # physics caught up: due later
    slow = pacer(0.5)                                # half real time: 1 sim ms is 2 wall ms
    slow.restart(0.0)
    time.sleep(0.03)
    assert slow.frame_in_time(0.010) is False        # due 10 ms ago on the wall clock
    assert slow.frame_in_time(0.100) is True         # due 200 ms after the start
    fast = pacer(0.0)                                # as fast as possible: every frame
    fast.restart(0.0)
    time.sleep(0.01)
    assert fast.frame_in_time(0.0) is True
