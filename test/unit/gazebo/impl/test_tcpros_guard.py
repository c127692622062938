"""The TCPROS handshake guard with plain sockets: no master, a fake handler in place of rospy's."""
import socket
import struct
import threading
import time

import pytest

from tutorial_turtlebot.gazebo.impl import tcpros_guard
from tutorial_turtlebot.gazebo.impl.tcpros_guard import (HandshakeGuard, HandshakeRefused,
                                                         read_header)


def encode(fields: dict) -> bytes:
    body = b""
    for key, value in fields.items():
        line = ("%s=%s" % (key, value)).encode()
        body += struct.pack("<I", len(line)) + line
    return struct.pack("<I", len(body)) + body


HEADER = {"topic": "/odom", "md5sum": "*", "callerid": "/test"}


class Server:
    """A listening socket whose accept thread calls ``guard(sock, addr)``, as rospy's TCPServer."""

    def __init__(self, **options):
        self.dispatched = []                 # (header, wall time) per dispatched connection
        self.lines = []
        self.guard = HandshakeGuard(self._dispatch, log=self.lines.append, **options)
        self.listener = socket.socket()
        self.listener.bind(("127.0.0.1", 0))
        self.listener.listen(128)
        self.port = self.listener.getsockname()[1]
        self.clients = []
        threading.Thread(target=self._accept, daemon=True).start()

    def _accept(self):
        while True:
            try:
                sock, addr = self.listener.accept()
            except OSError:
                return
            self.guard(sock, addr)

    def _dispatch(self, sock, addr, header):
        assert sock.gettimeout() is None  # blocking again, as rospy's handlers expect
        extra = sock.recv(16, socket.MSG_DONTWAIT) if header.get("extra") else b""
        self.dispatched.append((header, time.monotonic(), extra))
        sock.sendall(b"ok")
        sock.close()

    def connect(self) -> socket.socket:
        client = socket.create_connection(("127.0.0.1", self.port))
        self.clients.append(client)
        return client

    def call(self, fields=HEADER, timeout=5.0) -> float:
        """A well-behaved client: the time until its answer came."""
        start = time.monotonic()
        client = self.connect()
        client.settimeout(timeout)
        client.sendall(encode(fields))
        assert client.recv(2) == b"ok"
        return time.monotonic() - start

    def close(self):
        self.listener.close()
        for client in self.clients:
            client.close()


@pytest.fixture
def server():
    servers = []

    def make(**options):
        servers.append(Server(**options))
        return servers[-1]
    yield make
    for s in servers:
        s.close()


def closed_by_server(client, timeout=5.0) -> bool:
    client.settimeout(timeout)
    try:
        return client.recv(1) == b""
    except ConnectionResetError:
        return True


def test_a_normal_header_is_dispatched_decoded(server):
    s = server()
    assert s.call() < 1.0
    assert s.dispatched[0][0] == HEADER
    assert s.guard.refused == 0 and s.guard.pending == 0


def test_bytes_after_the_header_stay_for_the_handler(server):
    s = server()
    client = s.connect()
    client.sendall(encode(dict(HEADER, extra="1")) + b"REQUEST")
    assert client.recv(2) == b"ok"
    assert s.dispatched[0][2] == b"REQUEST"


def test_half_open_headers_do_not_delay_others_and_are_dropped(server):
    s = server(timeout=1.5)
    start = time.monotonic()
    stalled = [s.connect() for _ in range(20)]
    for client in stalled:
        client.sendall(b"\x10\x00")
    time.sleep(0.05)
    assert s.call() < 0.5  # not after the stalled ones' 1.5 s
    assert all(closed_by_server(c) for c in stalled)
    assert 1.4 < time.monotonic() - start < 3.0
    assert s.guard.refused == 20
    assert len(s.lines) == 1 and "no whole header within 1.5 s (2 bytes came)" in s.lines[0]
    assert "127.0.0.1:" in s.lines[0]


def test_http_is_refused_at_once(server):
    s = server()
    client = s.connect()
    client.sendall(b"GET / HTTP/1.1\r\nHost: x\r\n\r\n")
    start = time.monotonic()
    assert closed_by_server(client)
    assert time.monotonic() - start < 0.5
    assert "over the limit" in s.lines[0]


def test_a_huge_header_is_refused_by_its_length_unread(server):
    s = server()
    client = s.connect()
    client.sendall(struct.pack("<I", 100_000_000))
    sent = 0
    client.settimeout(5.0)
    chunk = b"x" * 65536
    try:
        while sent < 50_000_000:
            sent += client.send(chunk)
    except (BrokenPipeError, ConnectionResetError, TimeoutError):
        pass
    assert sent < 20_000_000  # the server closed it long before
    assert s.guard.refused == 1 and s.dispatched == []


def test_the_size_limit_is_the_header_s(server):
    s = server(limit=100)
    fields = dict(HEADER, message_definition="x" * 200)
    client = s.connect()
    client.sendall(encode(fields))
    assert closed_by_server(client)
    assert "a header of %d bytes is over the limit of 100" % (len(encode(fields)) - 4) in s.lines[0]
    assert s.call() < 1.0  # a small one still passes


def test_a_trickle_is_cut_at_the_deadline(server):
    s = server(timeout=0.5)
    client = s.connect()
    start = time.monotonic()
    data = encode(HEADER)
    try:
        for byte in data:
            client.sendall(bytes([byte]))
            time.sleep(0.05)
    except (BrokenPipeError, ConnectionResetError):
        pass
    assert closed_by_server(client)
    assert time.monotonic() - start < 1.0 + 0.05 * len(data)
    assert s.dispatched == [] and s.guard.refused == 1


@pytest.mark.parametrize("garbage", [
    struct.pack("<I", 5) + b"\x00\x00\x00\x00x",           # a 0-length field
    struct.pack("<I", 7) + struct.pack("<I", 3) + b"abc",  # no '='
    struct.pack("<I", 8) + struct.pack("<I", 4) + b"a=\xff\xfe",  # not UTF-8
    struct.pack("<I", 4) + struct.pack("<I", 99)])         # a field longer than the header
def test_garbage_fields_are_refused(server, garbage):
    s = server()
    client = s.connect()
    client.sendall(garbage)
    assert closed_by_server(client)
    assert s.guard.refused == 1 and s.dispatched == []
    assert s.call() < 1.0


def test_beyond_max_pending_connections_are_closed_at_once(server):
    s = server(timeout=1.0, max_pending=5)
    held = [s.connect() for _ in range(5)]
    time.sleep(0.1)
    extra = s.connect()
    start = time.monotonic()
    assert closed_by_server(extra)
    assert time.monotonic() - start < 0.5
    assert "5 handshakes are already being read" in s.lines[0]
    for client in held:
        assert closed_by_server(client)
    time.sleep(0.05)
    assert s.guard.pending == 0
    assert s.call() < 1.0


def test_refusals_are_logged_once_per_period_with_a_count():
    now = [0.0]
    lines = []
    guard = HandshakeGuard(None, log=lines.append, log_period=5.0, clock=lambda: now[0])
    for t in (0.0, 1.0, 2.0, 4.9, 5.5, 6.0):
        now[0] = t
        a, b = socket.socketpair()
        b.close()
        guard.refuse(a, ("10.0.0.7", 4242), "why")
    assert lines == ["TCPROS: refused a connection from 10.0.0.7:4242: why",
                     "TCPROS: refused a connection from 10.0.0.7:4242: why "
                     "(4 refused since the last such line)"]
    assert guard.refused == 6


def test_read_header_refuses_a_closed_connection():
    a, b = socket.socketpair()
    b.sendall(b"\x10\x00")
    b.close()
    with pytest.raises(HandshakeRefused, match="closed after 2 bytes"):
        read_header(a, time.monotonic() + 1.0)


class FakeTCPServer:
    def __init__(self):
        self.inbound_handler = "rospy's"


class FakeTCPROSServer:
    def __init__(self):
        self.tcp_ros_server = FakeTCPServer()


def test_install_replaces_the_accept_handler_once(monkeypatch):
    from rospy.impl import tcpros_base
    fake = FakeTCPROSServer()
    monkeypatch.setattr(tcpros_base, "_tcpros_server", fake)
    monkeypatch.setattr(tcpros_base, "start_tcpros_server", lambda: None)
    guard = tcpros_guard.install()
    assert isinstance(guard, HandshakeGuard) and fake.tcp_ros_server.inbound_handler is guard
    assert tcpros_guard.install() is guard
