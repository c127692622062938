"""gazebo/loop_requests.py: an action the loop did not start in time never runs; one it started
is always answered; its exception reaches its caller, and the loop goes on."""
import threading
import time

import pytest

from tutorial_turtlebot.gazebo.loop_requests import LoopRequests, NotAnswered


def test_an_action_runs_in_the_loop_and_its_result_comes_back():
    requests = LoopRequests()
    ran_in = []
    loop = threading.Thread(target=lambda: (requests.wake.wait(5.0), requests.run_pending()))
    loop.start()
    assert requests.call(lambda: ran_in.append(threading.current_thread()) or 42, 5.0) == 42
    loop.join()
    assert ran_in == [loop]


def test_a_request_the_loop_did_not_start_in_time_never_runs():
    requests = LoopRequests()
    ran = []
    start = time.monotonic()
    with pytest.raises(NotAnswered):
        requests.call(lambda: ran.append(1), 0.2)     # the loop is busy elsewhere
    assert time.monotonic() - start < 1.0
    assert requests.run_pending() == 0               # the loop comes back: nothing to do
    assert ran == []


def test_a_started_action_is_waited_for_beyond_the_timeout():
    requests = LoopRequests()
    started = threading.Event()

    def slow():
        started.set()
        time.sleep(0.5)
        return "done"
    loop = threading.Thread(target=lambda: (requests.wake.wait(5.0), requests.run_pending()))
    loop.start()
    assert requests.call(slow, 0.1) == "done"        # started within 0.1 s, finished after
    loop.join()
    assert started.is_set()


def test_an_exception_goes_to_the_caller_and_the_next_action_still_runs():
    requests = LoopRequests()
    results = {}

    def caller(name, action):
        try:
            results[name] = requests.call(action, 5.0)
        except Exception as err:  # noqa: BLE001
            results[name] = err
    threads = [threading.Thread(target=caller, args=("bad", lambda: 1 / 0)),
               threading.Thread(target=caller, args=("good", lambda: "ok"))]
    for thread in threads:
        thread.start()
    deadline = time.monotonic() + 5.0
    while len(results) < 2 and time.monotonic() < deadline:
        requests.run_pending()
        time.sleep(0.01)
    for thread in threads:
        thread.join()
    assert isinstance(results["bad"], ZeroDivisionError) and results["good"] == "ok"


def test_put_wakes_the_loop_and_does_not_wait():
    requests = LoopRequests()
    assert not requests
    requests.put(lambda: None)
    assert requests and requests.wake.is_set()
    assert requests.run_pending() == 1 and not requests


def test_call_wakes_a_waiting_loop_and_returns_the_answer_or_the_error():
    """The one queue-and-wake helper (put, and call over it): a loop waiting for work
    (LoopRequests.wait, as when paused) wakes at once, runs it, and the caller gets its answer
    or its exception."""
    requests = LoopRequests()
    woke = []

    def loop():
        for _ in range(2):
            start = time.monotonic()
            requests.wait(5.0)
            woke.append(time.monotonic() - start)
            requests.run_pending()
    thread = threading.Thread(target=loop)
    thread.start()
    time.sleep(0.05)
    assert requests.call(lambda: "answer", 5.0) == "answer"
    time.sleep(0.05)
    with pytest.raises(KeyError):
        requests.call(lambda: {}["missing"], 5.0)
    thread.join()
    assert len(woke) == 2 and max(woke) < 1.0
    assert not requests.wake.is_set()       # cleared: the next wait waits again


def test_clear_wake_before_reading_leaves_a_later_request_to_wake_again():
    requests = LoopRequests()
    requests.put(lambda: None)
    requests.clear_wake()
    assert requests.run_pending() == 1 and not requests.wake.is_set()
    requests.put(lambda: None)
    assert requests.wake.is_set()


def test_a_full_queue_refuses_at_once_and_the_refused_action_never_runs():
    from tutorial_turtlebot.gazebo.loop_requests import Busy

    requests = LoopRequests(limit=3)
    ran = []
    for i in range(3):
        requests.put(lambda i=i: ran.append(i))
    start = time.monotonic()
    with pytest.raises(Busy):
        requests.call(lambda: ran.append("late"), 5.0)
    assert time.monotonic() - start < 0.5            # no wait for a refusal
    assert isinstance(Busy(), NotAnswered)           # "nothing was done", as a timeout
    assert requests.run_pending() == 3
    assert ran == [0, 1, 2]


def test_the_loop_runs_what_was_queued_when_it_began_and_comes_back_for_the_rest():
    """A producer that queues from inside the loop's turn cannot keep the loop from stepping."""
    requests = LoopRequests()
    ran = []

    def refill(i):
        ran.append(i)
        requests.put(lambda: refill(i + 1))          # another, queued while the loop runs
    requests.put(lambda: refill(0))
    requests.clear_wake()
    assert requests.run_pending() == 1
    assert ran == [0]
    assert requests.wake.is_set()                    # the rest waits for the next turn
    assert requests.run_pending() == 1
    assert ran == [0, 1]


def test_the_latest_message_of_a_key_wins_and_holds_one_place():
    requests = LoopRequests(limit=2)
    ran = []
    for i in range(1000):                            # a flood on one model
        assert requests.put_latest(("set_model_state", "box"), lambda i=i: ran.append(("box", i)))
    assert requests.put_latest(("set_model_state", "ball"), lambda: ran.append(("ball", 0)))
    assert not requests.put_latest(("set_model_state", "cone"), lambda: ran.append("cone"))
    assert requests.run_pending() == 2
    assert ran == [("box", 999), ("ball", 0)]
    assert requests.put_latest(("set_model_state", "cone"), lambda: ran.append("cone"))
    assert requests.run_pending() == 1 and ran[-1] == "cone"


def test_a_connection_is_paced_to_its_rate_and_another_is_not_held_by_it():
    from tutorial_turtlebot.gazebo.callback_pace import CallbackPace

    now = [0.0]
    slept = []

    def sleep(seconds):
        slept.append(seconds)
        now[0] += seconds
    pace = CallbackPace(max_rate=100.0, clock=lambda: now[0], sleep=sleep)
    for _ in range(5):              # a flood: five messages at once on one connection
        pace.wait()
    assert slept == [0.01] * 4      # each later one waits for its period
    other = threading.Thread(target=pace.wait)
    other.start()
    other.join()                    # another connection's first message waits for nothing
    assert len(slept) == 4
    now[0] += 1.0
    pace.wait()                     # a message after a pause waits for nothing
    assert len(slept) == 4
