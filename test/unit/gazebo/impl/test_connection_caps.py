"""The inbound connection caps and the connection watch with plain sockets: no master, fake
handlers and topics in place of rospy's."""
import socket
import struct
import time

import pytest

from tutorial_turtlebot.gazebo.impl import connection_caps
from tutorial_turtlebot.gazebo.impl.connection_caps import (ConnectionCaps, ConnectionWatch,
                                                            ThrottledLines, unsent_bytes)

pytest.importorskip("rosgraph")


class Clock:
    def __init__(self):
        self.now = 100.0

    def __call__(self):
        return self.now


def test_one_line_per_kind_per_period_with_the_count_held_back():
    lines, clock = [], Clock()
    throttle = ThrottledLines(lines.append, period=5.0, clock=clock)
    for _ in range(3):
        throttle.line("topic", "refused a subscriber")
    throttle.line("service", "refused a caller")
    clock.now += 5.0
    throttle.line("topic", "refused a subscriber")
    assert lines == ["refused a subscriber", "refused a caller",
                     "refused a subscriber (and 2 more since the last such line)"]
    assert throttle.counts == {"topic": 4, "service": 1}


def make_caps(connections, **limits):
    return ConnectionCaps(lambda topic: connections.get(topic, 0),
                          lambda: sum(connections.values()),
                          lines=ThrottledLines(lambda line: None), **limits)


def test_a_topic_takes_per_topic_subscribers_counting_those_being_handed_over():
    connections = {"/a": 2}
    caps = make_caps(connections, per_topic=3)
    assert caps.admit_topic("/a") is None          # 2 + 1 being handed over
    assert "/a has 3 subscribers" in caps.admit_topic("/a")
    caps.topic_done("/a")
    connections["/a"] = 3                          # rospy added it
    assert caps.admit_topic("/a") is not None
    assert caps.admit_topic("/b") is None          # another topic is not held back
    caps.topic_done("/b")
    connections["/a"] = 1                          # two went away
    assert caps.admit_topic("/a") is None
    caps.topic_done("/a")
    assert caps._topic_pending == {}


def test_a_service_takes_per_service_open_connections_until_each_ends():
    caps = make_caps({}, per_service=2)
    assert caps.admit_service("/s") is None
    assert caps.admit_service("/s") is None
    assert "/s has 2 open connections" in caps.admit_service("/s")
    assert caps.admit_service("/t") is None
    caps.service_done("/s")
    assert caps.admit_service("/s") is None
    for name in ("/s", "/s", "/t"):
        caps.service_done(name)
    assert caps.services == {}


def test_the_total_counts_topics_and_services_together():
    connections = {"/a": 3, "/b": 3}
    caps = make_caps(connections, per_topic=10, total=8)
    assert caps.admit_service("/s") is None
    assert caps.admit_topic("/a") is None          # 8 with this one
    assert "8 connections are open" in caps.admit_topic("/c")
    assert "8 connections are open" in caps.admit_service("/t")


class FakeServer:
    """A TCPROS server's two handlers, as rospy's: a service handler that 'starts a thread'."""

    def __init__(self):
        self.topics, self.services = [], []

    def topic_connection_handler(self, sock, addr, header):
        self.topics.append(header["topic"])

    def service_connection_handler(self, sock, addr, header):
        if header["service"] == "/missing":
            return "not a provider of /missing"
        self.services.append(header["service"])


def read_error_header(sock) -> str:
    sock.settimeout(5.0)
    data = b""
    while True:
        chunk = sock.recv(4096)
        if not chunk:
            break
        data += chunk
    field_size = struct.unpack("<I", data[4:8])[0]
    return data[8:8 + field_size].decode()


def test_wrapped_handlers_refuse_the_excess_with_an_error_header_and_close():
    lines = []
    connections = {"/odom": 0}
    caps = ConnectionCaps(lambda t: connections.get(t, 0), lambda: sum(connections.values()),
                          per_topic=1, per_service=1, lines=ThrottledLines(lines.append))
    server = FakeServer()
    connection_caps.wrap_handlers(server, caps)
    header = {"topic": "/odom", "callerid": "/c1"}
    (a, a_peer), (b, b_peer) = socket.socketpair(), socket.socketpair()
    server.topic_connection_handler(a, None, header)
    connections["/odom"] = 1
    server.topic_connection_handler(b, None, dict(header, callerid="/c2"))
    assert server.topics == ["/odom"]
    assert read_error_header(b_peer).startswith("error=/odom has 1")
    assert lines == ["TCPROS: refused a subscriber of /odom from /c2: /odom has 1 subscribers, "
                     "the most it takes"]
    # services: the one started holds its place until its thread ends; an error frees it
    c, d = socket.socketpair()
    assert server.service_connection_handler(c, None, {"service": "/missing"}) is not None
    assert caps.services == {}
    server.service_connection_handler(c, None, {"service": "/get"})
    server.service_connection_handler(d, None, {"service": "/get", "callerid": "/c3"})
    assert server.services == ["/get"]
    assert caps.services == {"/get": 1}
    caps.service_done("/get")        # ServiceImpl.handle returned
    server.service_connection_handler(c, None, {"service": "/get"})
    assert server.services == ["/get", "/get"]
    del a_peer   # the admitted subscriber's end of its connection: held open until here


class FakeConnection:
    """A publisher-side transport: its socket, the bytes it wrote, close()."""

    def __init__(self, sock, endpoint_id="/sub"):
        self.socket, self.endpoint_id = sock, endpoint_id
        self.stat_bytes, self.done = 0, False

    def write(self, data):
        self.stat_bytes += self.socket.send(data, socket.MSG_DONTWAIT)

    def close(self):
        self.done = True
        self.socket.close()
        self.socket = None


class FakeTopic:
    def __init__(self, *connections):
        self.resolved_name = "/parameter_updates"
        self.connections = list(connections)

    def remove_connection(self, conn):
        self.connections.remove(conn)
        conn.close()


def tcp_pair():
    """A loopback TCP connection (TIOCOUTQ counts what the peer has not acknowledged)."""
    listener = socket.socket()
    listener.bind(("127.0.0.1", 0))
    listener.listen(1)
    client = socket.create_connection(listener.getsockname())
    server, _ = listener.accept()
    listener.close()
    for sock in (client, server):
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 4096)
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, 4096)
    return server, client


def test_a_closed_subscriber_is_removed_at_the_next_look():
    (s1, c1), (s2, c2) = tcp_pair(), tcp_pair()
    gone, stays = FakeConnection(s1), FakeConnection(s2)
    topic = FakeTopic(gone, stays)
    watch = ConnectionWatch(lambda: [topic], lines=ThrottledLines(lambda line: None))
    watch.scan()
    assert topic.connections == [gone, stays]
    c1.close()
    watch.scan()
    assert topic.connections == [stays] and gone.done and watch.closed == 1
    c2.close()
    s2.close()


def fill(conn):
    """Write until the kernel takes no more (the peer does not read)."""
    for _ in range(10000):
        before = conn.stat_bytes
        try:
            conn.write(b"x" * 65536)
        except BlockingIOError:
            return
        if conn.stat_bytes == before:
            return
    raise AssertionError("the peer took everything")


def drain(sock, sender):
    """Read all that comes until the sender's queue moved (at most 5 s)."""
    sock.settimeout(0)
    before = unsent_bytes(sender)
    deadline = time.monotonic() + 5.0
    while time.monotonic() < deadline:
        try:
            while sock.recv(65536):
                pass
        except BlockingIOError:
            pass
        if unsent_bytes(sender) != before:
            return
        time.sleep(0.05)
    raise AssertionError("the sender's queue did not move")


def test_a_subscriber_that_takes_nothing_for_the_stall_timeout_is_dropped():
    (s1, c1), (s2, c2) = tcp_pair(), tcp_pair()
    stalled, reading = FakeConnection(s1, "/never_reads"), FakeConnection(s2, "/reads")
    topic = FakeTopic(stalled, reading)
    lines, clock = [], Clock()
    watch = ConnectionWatch(lambda: [topic], stall_timeout=30.0,
                            lines=ThrottledLines(lines.append, clock=clock), clock=clock)
    fill(stalled)
    fill(reading)
    assert unsent_bytes(s1) > 0 and unsent_bytes(s2) > 0
    watch.scan()
    clock.now += 20.0
    drain(c2, s2)                       # the reader takes all it has: progress
    watch.scan()
    clock.now += 15.0                   # 35 s without progress, 15 s since the reader's
    watch.scan()
    assert topic.connections == [reading]
    assert stalled.done and watch.stalled == 1
    assert lines == ["TCPROS: dropped /parameter_updates's subscriber /never_reads: it took no "
                     "byte for 30 s"]
    for sock in (c1, c2, s2):
        sock.close()


def test_an_idle_subscriber_with_nothing_unsent_is_never_dropped():
    server, client = tcp_pair()
    idle = FakeConnection(server)
    topic = FakeTopic(idle)
    clock = Clock()
    watch = ConnectionWatch(lambda: [topic], stall_timeout=1.0, clock=clock)
    for _ in range(3):
        watch.scan()
        clock.now += 100.0
    assert topic.connections == [idle] and not idle.done
    client.close()
    server.close()
