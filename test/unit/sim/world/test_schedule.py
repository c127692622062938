"""Sim-time rate schedules (schedule.py): which steps a rate fires at. No ROS master."""
import math

import pytest

from tutorial_turtlebot.sim.world.schedule import NS_PER_S, RateSchedule, seconds_to_ns

STEP_NS = 2_500_000   # the default physics step, 2.5 ms


def firings(schedule, start_step, steps):
    """Indices k (time k * 2.5 ms) of the steps in [start_step, start_step + steps) that fire."""
    return [k for k in range(start_step, start_step + steps) if schedule.due(k * STEP_NS)]


# --- RateSchedule ------------------------------------------------------------------------------

def test_seconds_to_ns_rounds():
    """Float seconds become exact integer nanoseconds."""
    assert seconds_to_ns(0.0025) == 2_500_000
    assert seconds_to_ns(1.0) == NS_PER_S
    assert seconds_to_ns(0.1 + 0.2) == 300_000_000


def test_30hz_fires_300_times_in_10s():
    """30 Hz fed 2.5 ms steps for 10 s: exactly 300 firings (the average rate is exact)."""
    schedule = RateSchedule(30.0)
    schedule.reset(0)
    fired = firings(schedule, 0, 4000)
    assert len(fired) == 300
    # 100 s: still exact, no drift from the 13.33-step period.
    assert len(firings(schedule, 4000, 36000)) == 2700


@pytest.mark.parametrize("rate", [5.0, 30.0, 100.0, 200.0, 15.0, 60.0, 7.0, 13.0])
def test_rates_average_exactly(rate):
    """Each rate fires rate * 10 times in 10 s of 2.5 ms steps, never in a burst."""
    schedule = RateSchedule(rate)
    schedule.reset(0)
    fired = firings(schedule, 0, 4000)
    assert len(fired) == round(rate * 10)
    min_gap = math.floor(NS_PER_S / rate / STEP_NS)
    assert all(b - a >= min_gap for a, b in zip(fired, fired[1:]))


def test_each_firing_is_at_the_first_step_after_its_time():
    """The n-th firing happens at the first step at or after n/30 s, late by under one step."""
    schedule = RateSchedule(30.0)
    schedule.reset(0)
    fired = firings(schedule, 0, 4000)
    for n, k in enumerate(fired):
        assert k == math.ceil(n * NS_PER_S / 30.0 / STEP_NS - 1e-9)
        assert 0 <= k * STEP_NS - n * NS_PER_S / 30.0 < STEP_NS


def test_never_twice_in_one_step():
    """Asking again at the same time says no; a rate above the step rate fires once per step."""
    schedule = RateSchedule(30.0)
    schedule.reset(0)
    assert schedule.due(0) is True
    assert schedule.due(0) is False
    fast = RateSchedule(1000.0)   # 2.5 firings per step
    fast.reset(0)
    fired = firings(fast, 0, 400)
    assert fired == list(range(400))


def test_reset_restarts_the_schedule():
    """reset(now) makes a firing due at now and the next one period later."""
    schedule = RateSchedule(10.0)
    schedule.reset(0)
    firings(schedule, 0, 100)                  # runs to 0.2475 s
    start = 123_456_789
    schedule.reset(start)
    assert schedule.due(start - 1) is False
    assert schedule.due(start) is True
    assert schedule.due(start + 99_999_999) is False
    assert schedule.due(start + 100_000_000) is True


def test_resumes_without_a_burst_after_a_gap():
    """After a long pause it fires once, then keeps its normal period (no catching up)."""
    schedule = RateSchedule(30.0)
    schedule.reset(0)
    firings(schedule, 0, 400)                  # 0 .. 0.9975 s
    resume = 2000                              # step at 5.0 s
    fired = firings(schedule, resume, 400)     # 5.0 .. 5.9975 s
    assert fired[0] == resume
    assert fired[1] - fired[0] >= 13
    assert all(b - a in (13, 14) for a, b in zip(fired[1:], fired[2:]))
    assert len(fired) in (30, 31)


@pytest.mark.parametrize("rate", [5.0, 30.0, 100.0, 200.0, 7.0, 13.0, 1000.0])
def test_next_ns_is_when_due_will_say_yes(rate):
    """next_ns is the earliest time due() is True: the simulation skips asking before then.
    Checked at every 0.1 ms over 2 s, and after a reset."""
    schedule = RateSchedule(rate)
    schedule.reset(7)
    for now in range(7, 2 * NS_PER_S, 100_000):
        expected = now >= schedule.next_ns
        assert schedule.due(now) is expected
    schedule.reset(123_456_789)
    assert schedule.next_ns == 123_456_789


@pytest.mark.parametrize("rate", [0.0, -5.0, math.nan])
def test_rate_must_be_positive(rate):
    """A rate that is not > 0 Hz raises ValueError."""
    with pytest.raises(ValueError):
        RateSchedule(rate)
