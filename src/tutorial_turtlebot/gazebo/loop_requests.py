"""The requests that service and topic callbacks hand to the stepping loop, and their answers.

A callback runs in one of rospy's threads; the world may change only between two steps, in the
loop's thread. ``LoopRequests.call`` queues an action, wakes the loop, and waits for what the
action returned or raised. If the loop has not started the action within the caller's time, the
action is taken back: it never runs, so a client told "did not answer" can rely on nothing
having happened. An action the loop has started is always waited for and answered (the loop
holds each one to a bounded amount of work). ``put`` queues without waiting (topic callbacks).
``put`` is the one place that queues work for the loop and wakes it; ``call`` is ``put`` and a
wait. Times (``timeout``, ANSWER_TIMEOUT) in wall seconds.

Bounded, so that no client can starve the loop:
- at most MAX_QUEUED actions wait; one more is refused at once (``Busy``: a service caller is
  answered that the simulation is busy, and nothing was done; a topic message is dropped);
- ``put_latest``: a topic's message for a key (a model, a link) replaces the one of that key
  that the loop has not run yet: the latest wins, as the state topics want, and a flood of one
  key holds one place;
- ``run_pending`` runs at most what was queued when it began: what producers add meanwhile
  waits for the next turn, and the loop steps in between.
"""
import collections
import queue
import threading
from typing import Callable, Hashable, Optional

ANSWER_TIMEOUT = 10.0    # wall s a service waits for the loop to start its action
MAX_QUEUED = 1000        # actions waiting for the loop, at most
_QUEUED, _RUNNING, _DONE, _TAKEN_BACK = range(4)


class NotAnswered(Exception):
    """The loop did not start the action in time; it was taken back and will never run."""


class Busy(NotAnswered):
    """MAX_QUEUED actions wait already: this one was refused at once and will never run."""


class _Request:
    def __init__(self, action: Callable):
        self.action = action
        self.state = _QUEUED
        self.lock = threading.Lock()
        self.done = threading.Event()
        self.result = None
        self.error: Optional[BaseException] = None


class LoopRequests:
    """A queue of actions for the loop, and the event that wakes it from a sleep."""

    def __init__(self, limit: int = MAX_QUEUED):
        self._queue = queue.Queue(maxsize=limit)
        self.wake = threading.Event()   # set by every new request; the loop's sleeps wait on it
        self._latest: "collections.OrderedDict[Hashable, Callable]" = collections.OrderedDict()
        self._latest_lock = threading.Lock()

    def __bool__(self) -> bool:
        return not self._queue.empty()

    def wait(self, timeout: float) -> None:
        """In the loop: wait until a request is queued or ``timeout`` s have passed, and be
        ready for the next wake-up."""
        self.wake.wait(timeout)
        self.wake.clear()

    def clear_wake(self) -> None:
        """In the loop, before it reads the queue: a request queued later wakes it again."""
        self.wake.clear()

    def put(self, action: Callable) -> _Request:
        """Queue ``action()`` for the loop and wake it; return at once. Busy when MAX_QUEUED
        actions wait already (``action`` will never run)."""
        request = _Request(action)
        try:
            self._queue.put_nowait(request)
        except queue.Full:
            raise Busy() from None
        self.wake.set()
        return request

    def put_latest(self, key: Hashable, action: Callable) -> bool:
        """Queue ``action()`` for ``key``, in place of an action of the same key that the loop
        has not run yet (which then never runs); False if the queue is full (``action`` will
        never run)."""
        with self._latest_lock:
            waiting = key in self._latest
            self._latest[key] = action
        if waiting:
            self.wake.set()
            return True
        try:
            self.put(lambda: self._run_latest(key))
        except Busy:
            with self._latest_lock:
                if self._latest.get(key) is action:
                    del self._latest[key]
            return False
        return True

    def _run_latest(self, key: Hashable):
        with self._latest_lock:
            action = self._latest.pop(key)
        return action()

    def call(self, action: Callable, timeout: float):
        """Run ``action()`` in the loop: what it returns, or the exception it raised, raised
        here. NotAnswered if the loop did not start it within ``timeout`` s (it never will)."""
        request = self.put(action)
        if not request.done.wait(timeout):
            with request.lock:
                if request.state == _QUEUED:
                    request.state = _TAKEN_BACK
                    raise NotAnswered()
            request.done.wait()        # started: the loop finishes it, however long it takes
        if request.error is not None:
            raise request.error
        return request.result

    def run_pending(self, after_each: Optional[Callable[[], None]] = None) -> int:
        """In the loop: run the actions queued when it began that were not taken back, each
        caught (its exception goes to its caller), then ``after_each()``; how many ran."""
        ran = 0
        for _ in range(self._queue.qsize()):
            try:
                request = self._queue.get_nowait()
            except queue.Empty:
                break
            with request.lock:
                if request.state == _TAKEN_BACK:
                    continue
                request.state = _RUNNING
            try:
                request.result = request.action()
            except Exception as err:  # noqa: BLE001 - the caller gets it; the loop goes on
                request.error = err
            request.state = _DONE
            request.done.set()
            ran += 1
            if after_each is not None:
                after_each()
        if not self._queue.empty():
            self.wake.set()      # what waits for the next turn: a paused loop comes back for it
        return ran
