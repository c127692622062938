"""The keyboard teleop's state machine (doc/turtlebot3.md 5.1): keys, ramping, scaling, force stop,
smooth stop, the model's limits, the printed text. No ROS master, no terminal.
Units: m/s, rad/s."""
import pytest

from tutorial_turtlebot.robot_models import model_limits
from tutorial_turtlebot.lab.teleop_keys import Teleop


def teleop(model="burger"):
    return Teleop(*model_limits(model), model=model)


def run(t, keys):
    """Feed ``keys`` (None = a read timeout), return the list of (linear, angular) outputs."""
    return [tuple(t.step(key)[:2]) for key in keys]


def test_starts_still_at_speed_02_turn_1():
    t = teleop()
    assert t.status() == "currently:\tspeed 0.2\tturn 1"
    assert run(t, [None]) == [(0.0, 0.0)]


def test_banner():
    banner = teleop().banner()
    assert "Control Your TurtleBot3!" in banner
    for line in ("u    i    o", "j    k    l", "m    ,    .",
                 "q/z : increase/decrease max speeds by 10%",
                 "w/x : increase/decrease only linear speed by 10%",
                 "e/c : increase/decrease only angular speed by 10%",
                 "space key, k : force stop", "anything else : stop smoothly",
                 "CTRL-C to quit"):
        assert line in banner
    assert "burger: speed up to 0.22 m/s, turn up to 2.84 rad/s" in banner


@pytest.mark.parametrize("key, direction", [
    ("u", (1, 1)), ("i", (1, 0)), ("o", (1, -1)), ("j", (0, 1)), ("l", (0, -1)),
    ("m", (-1, -1)), (",", (-1, 0)), (".", (-1, 1))])
def test_movement_keys_reach_speed_times_direction(key, direction):
    t = teleop()
    linear, angular = run(t, [key] * 30)[-1]
    assert linear == pytest.approx(0.2 * direction[0])
    assert angular == pytest.approx(1.0 * direction[1])


def test_ramp_is_002_and_01_per_loop():
    t = teleop()
    out = run(t, ["u"] * 12)
    assert [lin for lin, _ in out[:10]] == pytest.approx([0.02 * n for n in range(1, 11)])
    assert [ang for _, ang in out[:10]] == pytest.approx([0.1 * n for n in range(1, 11)])
    assert out[10] == pytest.approx((0.2, 1.0)) and out[11] == pytest.approx((0.2, 1.0))


def test_reversing_ramps_too():
    t = teleop()
    run(t, ["i"] * 10)
    out = run(t, [","] * 3)
    assert [lin for lin, _ in out] == pytest.approx([0.18, 0.16, 0.14])


@pytest.mark.parametrize("key", [" ", "k"])
def test_force_stop_is_immediate(key):
    t = teleop()
    run(t, ["u"] * 10)
    assert run(t, [key]) == [(0.0, 0.0)]
    assert run(t, [None]) == [(0.0, 0.0)]  # and it stays stopped


@pytest.mark.parametrize("idle", [None, "a", "\x1b", "Z"])
def test_smooth_stop_after_more_than_four_idle_loops(idle):
    t = teleop()
    run(t, ["i"] * 10)
    # Four idle loops (0.4 s): still going.
    assert [lin for lin, _ in run(t, [idle] * 4)] == pytest.approx([0.2] * 4)
    # The fifth sets the target to 0; the output ramps down by 0.02 per loop.
    assert [lin for lin, _ in run(t, [idle] * 3)] == pytest.approx([0.18, 0.16, 0.14])
    assert run(t, [idle] * 10)[-1] == (0.0, 0.0)


def test_movement_key_resets_the_idle_count():
    t = teleop()
    out = run(t, ["i", None, None, None, None, "i", None, None, None, None])
    assert out[-1][0] == pytest.approx(0.2)


def test_speed_keys_scale_by_ten_percent():
    t = teleop("waffle")
    text = t.step("q").text
    assert (t.speed, t.turn) == pytest.approx((0.22, 1.1))
    assert text == "currently:\tspeed 0.22\tturn 1.1"
    t.step("z")
    assert (t.speed, t.turn) == pytest.approx((0.198, 0.99))
    t.step("w")
    assert (t.speed, t.turn) == pytest.approx((0.2178, 0.99))
    t.step("x")
    assert (t.speed, t.turn) == pytest.approx((0.19602, 0.99))
    t.step("e")
    assert (t.speed, t.turn) == pytest.approx((0.19602, 1.089))
    t.step("c")
    assert (t.speed, t.turn) == pytest.approx((0.19602, 0.9801))


def test_scaling_while_moving_changes_the_target():
    t = teleop("waffle")
    run(t, ["i"] * 10)
    t.step("w")  # speed 0.22: the output ramps on from 0.2
    assert run(t, ["i"])[0][0] == pytest.approx(0.22)


@pytest.mark.parametrize("model", ["burger", "waffle", "waffle_pi", "unknown"])
def test_clamped_to_the_models_limits(model):
    max_linear, max_angular = model_limits(model)
    t = teleop(model)
    for key in ["q"] * 30 + ["u"] * 60:
        linear, angular, _ = t.step(key)
        assert abs(linear) <= max_linear + 1e-12
        assert abs(angular) <= max_angular + 1e-12
    assert (t.speed, t.turn) == pytest.approx((max_linear, max_angular))
    assert (linear, angular) == pytest.approx((max_linear, max_angular))
    t.step("k")
    assert run(t, [","] * 60)[-1] == pytest.approx((-max_linear, 0.0))


def test_limits_differ_per_model():
    burger, waffle = teleop("burger"), teleop("waffle")
    for _ in range(2):
        burger.step("w")
        waffle.step("w")
    assert burger.speed == pytest.approx(0.22)
    assert waffle.speed == pytest.approx(0.242)
    waffle.step("w")
    assert waffle.speed == pytest.approx(0.26)
    for _ in range(20):
        burger.step("e")
        waffle.step("e")
    assert burger.turn == pytest.approx(2.84)
    assert waffle.turn == pytest.approx(1.82)


def test_status_mentions_the_limit_when_hit():
    t = teleop("burger")
    assert "(burger limits: 0.22 m/s, 2.84 rad/s)" in t.step("w").text   # 0.2 * 1.1 > 0.22
    assert "limits" not in t.step("x").text
    t = teleop("waffle")
    assert "limits" not in t.step("w").text + t.step("w").text   # 0.22, 0.242
    assert "(waffle limits: 0.26 m/s, 1.82 rad/s)" in t.step("w").text


def test_banner_again_every_15_status_lines():
    t = teleop()
    texts = [t.step("c" if n % 2 else "e").text for n in range(30)]
    with_banner = [n for n, text in enumerate(texts) if "Control Your TurtleBot3!" in text]
    assert with_banner == [14, 29]
    assert all("currently:\tspeed " in text for text in texts)


def test_other_keys_print_nothing():
    t = teleop()
    assert [t.step(key).text for key in ("i", "k", "a", None)] == [None] * 4


def test_status_shows_three_significant_digits():
    """Five presses of q on a burger: turn 1 x 1.1^5 = 1.61051 shows as 1.61 (speed stops at the
    burger's 0.22 m/s)."""
    t = teleop("burger")
    for _ in range(5):
        run(t, ["q"])
    assert t.status() == "currently:\tspeed 0.22\tturn 1.61"
