"""Wall-clock pacing of sim time (pacing.py: Pacer), with a fake clock. No ROS master."""
import math

import pytest

from tutorial_turtlebot.sim.world.pacing import Pacer


# --- Pacer -------------------------------------------------------------------------------------

class FakeClock:
    """A monotonic clock that only moves when told to, or when someone sleeps on it."""

    def __init__(self, start=100.0):
        self.now = start
        self.sleeps = []

    def __call__(self):
        return self.now

    def sleep(self, seconds):
        assert seconds > 0
        self.sleeps.append(seconds)
        self.now += seconds


def wait(pacer, sim):
    """What the sim's loop does after a step, messages aside: sleep when the batch is done."""
    end = pacer.batch_end(sim)
    if end is not None and end > pacer._clock():
        pacer._clock.sleep(end - pacer._clock())


def run(pacer, clock, sim_start, sim_step, steps, compute=0.0005):
    """Step sim time by ``sim_step`` ``steps`` times, each step costing ``compute`` s of wall."""
    sim = sim_start
    for _ in range(steps):
        clock.now += compute
        sim += sim_step
        wait(pacer, sim)
    return sim


def make(rtf, min_sleep=0.001):
    clock = FakeClock()
    return Pacer(rtf, clock=clock, min_sleep=min_sleep), clock


def test_rtf_1_keeps_wall_time_with_sim_time():
    """At factor 1, 1 s of sim takes 1 s of wall: sleeps fill what computing did not use."""
    pacer, clock = make(1.0)
    run(pacer, clock, 0.0, 0.01, 100)
    assert clock.now - 100.0 == pytest.approx(1.0, abs=1e-9)
    assert sum(clock.sleeps) == pytest.approx(1.0 - 100 * 0.0005, abs=1e-9)
    assert all(s == pytest.approx(0.0095) for s in clock.sleeps)


def test_default_sleeps_once_per_20_ms_of_steps():
    """By default steps run until the sim is 20 ms ahead of wall time, then one sleep catches up:
    2.5 ms steps costing 0.1 ms sleep after every 9th step (21.6 ms ahead). After each wait the
    sim is less than 20 ms ahead of wall time, and never behind."""
    clock = FakeClock()
    pacer = Pacer(1.0, clock=clock)
    sim = 0.0
    for _ in range(400):
        clock.now += 0.0001
        sim += 0.0025
        wait(pacer, sim)
        assert -1e-9 <= sim - (clock.now - 100.0) < Pacer.MIN_SLEEP
    assert len(clock.sleeps) == 400 // 9
    assert all(s == pytest.approx(9 * 0.0024) for s in clock.sleeps)
    assert 1.0 - Pacer.MIN_SLEEP < clock.now - 100.0 <= 1.0


def test_wall_of_says_when_each_moment_is_due():
    """What the sim made ahead leaves when due: wall_of maps sim time to the clock (at factor 2,
    sim 1.0 s is wall 0.5 s after the anchor, and after a restart from that moment on)."""
    clock = FakeClock()
    pacer = Pacer(2.0, clock=clock)
    assert pacer.wall_of(1.0) == pytest.approx(100.5)
    assert pacer.wall_of(0.01) == pytest.approx(100.005)
    clock.now = 103.0
    pacer.restart(4.0)
    assert pacer.wall_of(5.0) == pytest.approx(103.5)


def test_ahead_forgives_a_large_debt():
    """ahead() is how far sim time runs ahead of the clock; far behind (a stall) the pacer
    re-anchors at the present instead of racing to catch up; at factor 0 it is always 0."""
    clock = FakeClock()
    pacer = Pacer(1.0, clock=clock)
    assert pacer.ahead(0.015) == pytest.approx(0.015)
    clock.now += 0.1
    assert pacer.ahead(0.015) == pytest.approx(-0.085)
    clock.now += 1.0
    assert pacer.ahead(0.015) == 0.0
    assert pacer.wall_of(0.025) == pytest.approx(clock.now + 0.01)
    assert Pacer(0.0, clock=clock).ahead(5.0) == 0.0


def test_set_rtf_changes_the_factor_from_now_on():
    """set_physics_properties' max_update_rate: a new factor, anchored at the present; 0 stops
    all sleeping, and a bad factor is refused."""
    clock = FakeClock()
    pacer = Pacer(1.0, clock=clock)
    clock.now += 0.5
    pacer.set_rtf(4.0, 0.5)
    assert pacer.wall_of(1.5) == pytest.approx(clock.now + 0.25)
    pacer.set_rtf(0.0, 1.0)
    assert pacer.ahead(100.0) == 0.0
    wait(pacer, 100.0)
    assert clock.sleeps == []
    with pytest.raises(ValueError):
        pacer.set_rtf(-1.0, 1.0)


def test_rtf_2_takes_half_the_wall_time():
    """At factor 2, 1 s of sim takes 0.5 s of wall."""
    pacer, clock = make(2.0)
    run(pacer, clock, 0.0, 0.01, 100)
    assert clock.now - 100.0 == pytest.approx(0.5, abs=1e-9)
    assert all(s == pytest.approx(0.0045) for s in clock.sleeps)


def test_rtf_0_never_sleeps():
    """Factor 0: as fast as the machine allows."""
    pacer, clock = make(0.0)
    run(pacer, clock, 0.0, 0.01, 1000)
    assert clock.sleeps == []


def test_no_sleep_when_not_ahead():
    """A slow machine (each step costs more wall than sim) never sleeps."""
    pacer, clock = make(1.0)
    run(pacer, clock, 0.0, 0.0025, 100, compute=0.003)
    assert clock.sleeps == []


@pytest.mark.parametrize("rtf", [1.0, 2.0, 0.5])
def test_achieved_reports_the_factor(rtf):
    """achieved() gives sim seconds per wall second since the last call, then starts anew."""
    pacer, clock = make(rtf)
    sim = run(pacer, clock, 0.0, 0.01, 200)
    assert pacer.achieved(sim) == pytest.approx(rtf, rel=1e-6)
    assert pacer.achieved(sim) is None      # no wall time since the last call
    clock.now += 1.0                        # a stall: 1 s of wall, no sim progress
    assert pacer.achieved(sim) == pytest.approx(0.0)


def test_achieved_when_unpaced():
    """With factor 0 it reports what the machine does: 0.01 s of sim per 0.002 s = 5."""
    pacer, clock = make(0.0)
    sim = run(pacer, clock, 0.0, 0.01, 100, compute=0.002)
    assert pacer.achieved(sim) == pytest.approx(5.0)


def test_big_lag_is_forgiven():
    """After a stall longer than MAX_LAG the pacer re-anchors instead of racing to catch up."""
    pacer, clock = make(1.0)
    sim = run(pacer, clock, 0.0, 0.01, 10)
    clock.now += 2.0                        # the machine froze for 2 s
    sim += 0.01
    n_before = len(clock.sleeps)
    wait(pacer, sim)                         # far behind: forgive, do not sleep
    assert len(clock.sleeps) == n_before
    run(pacer, clock, sim, 0.01, 10)
    # Paced again at once: every later step sleeps its 9.5 ms, none is skipped.
    assert len(clock.sleeps) == n_before + 10
    assert all(s == pytest.approx(0.0095) for s in clock.sleeps[n_before:])


def test_small_lag_is_made_up():
    """Behind by less than MAX_LAG: no sleeping until sim time has caught up."""
    pacer, clock = make(1.0)
    sim = run(pacer, clock, 0.0, 0.01, 10)
    clock.now += 0.1                        # 0.1 s behind
    n_before = len(clock.sleeps)
    sim = run(pacer, clock, sim, 0.01, 20)
    later = clock.sleeps[n_before:]
    assert len(later) < 20 - 5              # about ten steps ran without sleeping
    assert clock.now - 100.0 == pytest.approx(sim, abs=0.001)


def test_restart_reanchors():
    """restart(sim) after a pause: pacing continues from now, with no debt and no credit."""
    pacer, clock = make(1.0)
    sim = run(pacer, clock, 0.0, 0.01, 10)
    clock.now += 30.0                       # paused for 30 s
    pacer.restart(sim)
    start = clock.now
    sim = run(pacer, clock, sim, 0.01, 50)
    assert clock.now - start == pytest.approx(0.5, abs=1e-9)


@pytest.mark.parametrize("rtf", [-1.0, -0.001, math.nan])
def test_negative_rtf_raises(rtf):
    """A negative (or NaN) real_time_factor is a ValueError."""
    with pytest.raises(ValueError, match="real_time_factor"):
        Pacer(rtf)
