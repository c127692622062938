"""The loop's time by part: every moment in exactly one part, and the report make bench reads."""
import time

from tutorial_turtlebot.gazebo.part_times import PARTS, PartTimes, read_line


def test_the_parts_add_up_to_the_time_passed_with_nothing_counted_twice():
    times = PartTimes()
    start = time.perf_counter()
    times.switch("physics")
    time.sleep(0.02)
    previous = times.switch("sending")
    time.sleep(0.01)
    assert times.switch(previous) == "sending"   # back to physics, as the writers do
    time.sleep(0.01)
    times.switch("other")
    passed = time.perf_counter() - start
    totals = times.totals
    assert previous == "physics"
    assert 0.029 < totals["physics"] < 0.029 + 0.02
    assert 0.0095 < totals["sending"] < 0.0095 + 0.02
    assert abs(sum(totals.values()) - passed) < 0.002


def test_the_report_line_reads_back_with_the_running_part_included():
    times = PartTimes()
    times.switch("sensors")
    time.sleep(0.01)
    sim, parts = read_line(times.line(12.5))
    assert sim == 12.5
    assert set(parts) == set(PARTS)
    assert parts["sensors"] >= 0.0095           # still running, yet counted
    assert times.totals["sensors"] == 0.0       # the line does not end the part


def test_run_counts_an_action_in_its_part_and_goes_back():
    times = PartTimes()
    times.switch("physics")
    assert times.run("sending", lambda seconds: time.sleep(seconds) or "sent", 0.01) == "sent"
    assert times.part == "physics"
    assert times.totals["sending"] >= 0.0095
