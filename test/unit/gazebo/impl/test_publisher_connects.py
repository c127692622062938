"""The bound on publishers connected to, and requestTopic's tries, with loopback sockets and no
master."""
import errno
import socket
import threading
import time

import pytest

from tutorial_turtlebot.gazebo.impl import publisher_connects
from tutorial_turtlebot.gazebo.impl.connection_caps import ThrottledLines
from tutorial_turtlebot.gazebo.impl.publisher_connects import BoundedRequest, PublisherBudget

from unit_helpers import free_port as closed_port


def test_an_update_is_cut_to_the_bound_the_connected_first_and_each_uri_once():
    lines = []
    budget = PublisherBudget(per_topic=3, lines=ThrottledLines(lines.append))
    uris = ["http://127.0.0.1:1/%d" % i for i in range(10)] + ["http://127.0.0.1:1/0"]
    kept = budget.update("/cmd_vel", uris, lambda uri: uri.endswith("/7"))
    assert kept == ["http://127.0.0.1:1/7", "http://127.0.0.1:1/0", "http://127.0.0.1:1/1"]
    assert lines == ["publisherUpdate: /cmd_vel named 10 publishers; the sim connects to 3 at "
                     "most"]
    assert budget.is_named("/cmd_vel", "http://127.0.0.1:1/1")
    assert not budget.is_named("/cmd_vel", "http://127.0.0.1:1/5")
    assert budget.is_named("/other", "http://127.0.0.1:1/5")   # nothing known: rospy decides
    budget.update("/cmd_vel", [], lambda uri: False)
    assert not budget.is_named("/cmd_vel", "http://127.0.0.1:1/7")
    budget.forget({"/odom"})
    assert budget.named == {}


def test_connects_of_one_topic_are_bounded_with_those_connected():
    lines = []
    budget = PublisherBudget(per_topic=3, lines=ThrottledLines(lines.append))
    assert budget.start("/cmd_vel", 1) and budget.start("/cmd_vel", 1)
    assert not budget.start("/cmd_vel", 1)
    assert budget.start("/scan", 2)
    budget.done("/cmd_vel")
    assert budget.start("/cmd_vel", 1)
    for topic in ("/cmd_vel", "/cmd_vel", "/scan"):
        budget.done(topic)
    assert budget.connecting == {}
    assert len(lines) == 1 and "/cmd_vel has 3 publishers connected or connecting" in lines[0]


class HangingListener:
    """Accepts connections and never answers (at most 16 held), on 127.0.0.1."""

    def __init__(self):
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(16)
        self.uri = "http://127.0.0.1:%d/" % self.sock.getsockname()[1]
        self.held = []
        threading.Thread(target=self._accept, daemon=True).start()

    def _accept(self):
        while len(self.held) < 16:
            try:
                self.held.append(self.sock.accept()[0])
            except OSError:
                return

    def close(self):
        self.sock.close()
        for sock in self.held:
            sock.close()


@pytest.fixture
def hanging(monkeypatch):
    monkeypatch.setattr(publisher_connects, "REQUEST_TIMEOUT", 0.2)
    listener = HangingListener()
    yield listener
    listener.close()


def request(uri, is_named=lambda topic, uri: True):
    return BoundedRequest(uri, is_named).requestTopic("/gazebo", "/cmd_vel", [["TCPROS"]])


def test_a_hanging_publisher_is_given_up_after_max_attempts(hanging):
    publisher_connects._attempts.count = 0
    tries = 0
    start = time.monotonic()
    while True:
        tries += 1
        try:
            answer = request(hanging.uri)
            break
        except socket.timeout:
            assert tries < publisher_connects.MAX_ATTEMPTS
    took = time.monotonic() - start
    assert tries == publisher_connects.MAX_ATTEMPTS
    assert answer[0] == 0 and "gave up on %s after 3 tries" % hanging.uri in answer[1]
    assert took < 3 * 0.2 + 1.0


def test_a_publisher_no_longer_named_is_given_up_at_its_next_failure(hanging):
    publisher_connects._attempts.count = 0
    answer = request(hanging.uri, is_named=lambda topic, uri: False)
    assert answer[0] == 0 and "no longer a publisher of /cmd_vel" in answer[1]


def test_a_refused_connection_is_raised_for_rospy_to_stop_at_once():
    publisher_connects._attempts.count = 0
    with pytest.raises(OSError) as err:
        request("http://127.0.0.1:%d/" % closed_port())
    assert err.value.errno == errno.ECONNREFUSED


def test_an_answering_publisher_is_answered_as_it_answers():
    class Proxy:
        def requestTopic(self, caller_id, topic, protocols):  # noqa: N802
            return [1, "", ["TCPROS", "127.0.0.1", 1234]]
    publisher_connects._attempts.count = 0
    answer = BoundedRequest("http://x/", lambda t, u: True, proxy=Proxy()).requestTopic(
        "/gazebo", "/cmd_vel", [["TCPROS"]])
    assert answer == [1, "", ["TCPROS", "127.0.0.1", 1234]]
