"""The stepping loop's sleep at a slow pace: requests are served at once, Ctrl-C ends it.

A SimNode without ROS: only what its pacing sleep (``_send_on_time_until``) touches."""
import threading
import time
import types

import pytest

from tutorial_turtlebot.gazebo import sim_node
from tutorial_turtlebot.gazebo.loop_pacer import WAKE_CHECK, LoopPacer
from tutorial_turtlebot.gazebo.loop_requests import LoopRequests
from tutorial_turtlebot.gazebo.send_queue import SendQueue
from tutorial_turtlebot.sim.world.pacing import MIN_REAL_TIME_FACTOR, Pacer


class FakeSim:
    def __init__(self, t=0.0):
        self.time = t
        self.time_ns = int(t * 1e9)
        self.physics = types.SimpleNamespace(ray_threads=1)


def slow_node(step=0.01):
    """A node one ``step`` of sim time ahead at the slowest pace: its batch ends
    step / MIN_REAL_TIME_FACTOR wall s from now."""
    node = object.__new__(sim_node.SimNode)
    node.sim = FakeSim(0.0)
    node.requests = LoopRequests()
    node.stop_requested = False
    node.pacer = LoopPacer(MIN_REAL_TIME_FACTOR, node.requests.wake, node._stopping)
    node.pacer.restart(0.0)
    node.sim.time = step
    node.paused = False
    node.sends = SendQueue()
    return node


def request(node, action, delay):
    """Queue ``action`` from another thread after ``delay`` s, as a service callback does; the
    time from queueing to done."""
    took = []

    def call():
        time.sleep(delay)
        start = time.monotonic()
        node.run_in_loop(action, 10.0)
        took.append(time.monotonic() - start)
    thread = threading.Thread(target=call)
    thread.start()
    return thread, took


def test_a_request_is_served_during_a_slow_sleep_which_then_goes_on():
    node = slow_node(0.01)                      # a batch of 1 wall s
    wall_time = node.pacer.batch_end(node.sim.time)
    thread, took = request(node, lambda: None, 0.2)
    start = time.monotonic()
    node._send_on_time_until(wall_time)
    thread.join()
    assert took[0] < 0.05
    assert time.monotonic() - start == pytest.approx(1.0, abs=0.05)  # the pace is kept


def test_a_pause_during_the_sleep_ends_it():
    node = slow_node(0.01)
    thread, took = request(node, node.pause, 0.1)
    start = time.monotonic()
    node._send_on_time_until(node.pacer.batch_end(node.sim.time))
    thread.join()
    assert time.monotonic() - start < 0.3 and took[0] < 0.05


def test_a_faster_pace_during_the_sleep_ends_it():
    node = slow_node(0.01)
    thread, _ = request(node, lambda: node.set_real_time_factor(1.0), 0.1)
    start = time.monotonic()
    node._send_on_time_until(node.pacer.batch_end(node.sim.time))
    thread.join()
    assert time.monotonic() - start < 0.3


def test_ctrl_c_ends_the_sleep_within_wake_check():
    node = slow_node(0.01)
    timer = threading.Timer(0.1, lambda: setattr(node, "stop_requested", True))
    timer.start()
    start = time.monotonic()
    node._send_on_time_until(node.pacer.batch_end(node.sim.time))
    assert time.monotonic() - start < 0.1 + WAKE_CHECK + 0.05


def test_kept_messages_leave_on_time_during_the_sleep():
    node = slow_node(0.01)
    sent = []

    class Connection:
        done = False

        def write_data(self, data):
            sent.append((data, time.monotonic()))
    start = time.monotonic()
    node.sends.keep(lambda _due: node.sends.held.append((Connection(), b"a")), [], start + 0.3)
    node._send_on_time_until(start + 0.5)
    assert sent and sent[0][1] - start == pytest.approx(0.3, abs=0.03)


# --- the slowest pace ------------------------------------------------------------------------

from tutorial_turtlebot.sim.world.pacing import check_rtf  # noqa: E402
from tutorial_turtlebot.sim.world.physics_properties import PhysicsProperties, validate  # noqa: E402


@pytest.mark.parametrize("rtf", [1e-9, 2.5e-9, 0.0099])
def test_a_pace_below_the_slowest_is_refused(rtf):
    with pytest.raises(ValueError, match="below the slowest pace 0.01"):
        check_rtf(rtf)
    with pytest.raises(ValueError, match="below the slowest pace"):
        Pacer(rtf)


@pytest.mark.parametrize("rtf", [0.0, MIN_REAL_TIME_FACTOR, 1.0, 1000.0])
def test_the_slowest_pace_and_faster_run(rtf):
    check_rtf(rtf)
    Pacer(rtf).set_rtf(rtf, 0.0)


def test_set_physics_properties_refuses_max_update_rate_1e_6_naming_field_and_limit():
    with pytest.raises(ValueError) as err:
        validate(PhysicsProperties(time_step=0.0025, max_update_rate=1e-6))
    assert str(err.value) == ("max_update_rate 1e-06 is below 4 at time_step 0.0025 (a real-time "
                              "factor of at least 0.01; 0 = as fast as possible)")


@pytest.mark.parametrize("time_step", [0.0001, 0.001, 0.0025, 0.01])
def test_exactly_the_slowest_rate_passes_at_every_step(time_step):
    props = PhysicsProperties(time_step=time_step, max_update_rate=MIN_REAL_TIME_FACTOR / time_step)
    validate(props)
    check_rtf(props.real_time_factor)  # what the node's pacer then gets
    validate(PhysicsProperties(time_step=time_step, max_update_rate=0.0))


def test_dynamic_reconfigure_says_the_limit():
    from tutorial_turtlebot.gazebo import physics_config
    rate = next(p for p in physics_config.config_description["parameters"]
                if p["name"] == "max_update_rate")
    assert "0.01 / time_step" in rate["description"]


class ClockPublisher:
    def __init__(self):
        self.stamps = []

    def publish_packed(self, packed):
        self.stamps.append(packed.message().clock.to_nsec())


def clock_node(rtf, pub_clock_frequency):
    """A node whose /clock is recorded; its pace ``rtf`` (0: as fast as possible)."""
    node = object.__new__(sim_node.SimNode)
    node.sim = FakeSim(0.0)
    node.pacer = LoopPacer(rtf, threading.Event(), lambda: False, pub_clock_frequency)
    node.pacer.restart(0.0)
    node.clock_packed = sim_node.PackedClock()
    node.clock_pub = ClockPublisher()
    return node


def tick(node, sim_ns):
    node.sim.time_ns, node.sim.time = sim_ns, sim_ns / 1e9
    node._publish_clock(sim_node.rospy.Time(*divmod(sim_ns, 1_000_000_000)))


def test_clock_at_most_pub_clock_frequency_a_wall_second_as_fast_as_possible():
    """Gazebo's ~pub_clock_frequency: 100 ticks of 10 ms of sim time made within a few wall ms
    give a message per wall ms at most; with no limit (0), every tick."""
    node = clock_node(0.0, 1000.0)
    start = time.monotonic()
    for k in range(100):
        tick(node, k * 10_000_000)
    took = time.monotonic() - start
    assert node.clock_pub.stamps[0] == 0          # the first tick always goes
    assert len(node.clock_pub.stamps) <= 1 + took / 0.001
    assert node.clock_pub.stamps == sorted(node.clock_pub.stamps)
    unlimited = clock_node(0.0, 0.0)
    for k in range(100):
        tick(unlimited, k * 10_000_000)
    assert unlimited.clock_pub.stamps == [k * 10_000_000 for k in range(100)]


def test_at_real_time_the_clock_limit_never_bites():
    """At real time the gap is judged by when each tick is due on the wall clock (10 ms
    apart), not when it was made (a batch ahead): every tick is sent."""
    node = clock_node(1.0, 1000.0)
    for k in range(50):
        tick(node, k * 10_000_000)
    assert len(node.clock_pub.stamps) == 50
