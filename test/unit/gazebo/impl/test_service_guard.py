"""gazebo/impl/service_guard.py: one warning line per client per period for malformed service
requests, the clients remembered bounded; faults told in one short line. No ROS master."""
from tutorial_turtlebot.gazebo.impl import service_guard
from tutorial_turtlebot.gazebo.impl.service_guard import ClientWarnings, fault_text


def test_one_line_per_client_per_period():
    now = [0.0]
    lines = []
    said = ClientWarnings(lines.append, clock=lambda: now[0])
    for _ in range(50):
        said.warn("/evil", "bad from /evil")
    said.warn("/other", "bad from /other")
    assert lines == ["bad from /evil", "bad from /other"]
    now[0] = service_guard.WARN_PERIOD + 0.1
    assert said.warn("/evil", "again")
    assert lines[-1] == "again"


def test_the_clients_remembered_are_bounded(monkeypatch):
    monkeypatch.setattr(service_guard, "MAX_CLIENTS", 3)
    lines = []
    said = ClientWarnings(lines.append, clock=lambda: 0.0)
    for i in range(10):
        said.warn("/c%d" % i, "line %d" % i)
    assert len(said._last) == 3
    assert said.warn("/c0", "the oldest was forgotten")       # told again
    assert not said.warn("/c9", "still remembered")


def test_a_fault_is_one_short_line():
    text = fault_text(ValueError("receive_once[/gazebo/x]:\n DeserializationError " + "x" * 500))
    assert "\n" not in text and len(text) <= service_guard.MAX_FAULT
    assert text.startswith("receive_once[/gazebo/x]: DeserializationError")
    assert fault_text(RuntimeError()) == "RuntimeError"
