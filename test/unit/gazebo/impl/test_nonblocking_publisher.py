"""The sim's publisher connections never block and keep the byte stream whole. No ROS master:
a socket pair stands in for the TCP connection to one subscriber."""
import signal
import socket
import struct

import pytest
from rospy.exceptions import TransportTerminated

from tutorial_turtlebot.gazebo.impl.nonblocking_publisher import (Backlog, NonBlockingConnection,
                                                                  make_nonblocking)


class Transport:
    """The parts of rospy's TCPROSTransport a publisher connection uses."""

    def __init__(self, sock):
        self.socket = sock
        self.done = False
        self.endpoint_id = "/listener"
        self.stat_bytes = 0
        self.stat_num_msg = 0

    def close(self):
        self.done = True
        self.socket.close()
        self.socket = None


def message(n: int, size: int) -> bytes:
    """A TCPROS frame: 4-byte little-endian length, then ``size`` bytes starting with n."""
    body = struct.pack("<I", n) + bytes([n % 251]) * (size - 4)
    return struct.pack("<I", len(body)) + body


def read_frames(sock) -> list:
    """Every frame the reader can get now, as message numbers; asserts each arrived whole."""
    sock.setblocking(False)
    data = b""
    while True:
        try:
            chunk = sock.recv(1 << 20)
        except BlockingIOError:
            break
        if not chunk:
            break
        data += chunk
    numbers = []
    while data:
        (length,) = struct.unpack_from("<I", data)
        body, data = data[4:4 + length], data[4 + length:]
        assert len(body) == length, "a frame was cut short"
        n = struct.unpack_from("<I", body)[0]
        assert body[4:] == bytes([n % 251]) * (length - 4), "a frame was corrupted"
        numbers.append(n)
    return numbers


@pytest.fixture(autouse=True)
def never_blocks():
    """A write that blocks on a subscriber that does not read fails the test after 10 s."""
    def blocked(_signum, _frame):
        raise AssertionError("a write blocked on a subscriber that does not read")
    previous = signal.signal(signal.SIGALRM, blocked)
    signal.alarm(10)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, previous)


@pytest.fixture
def pair():
    writer, reader = socket.socketpair()
    writer.setsockopt(socket.SOL_SOCKET, socket.SO_SNDBUF, 65536)
    reader.setsockopt(socket.SOL_SOCKET, socket.SO_RCVBUF, 65536)
    yield writer, reader
    reader.close()
    if writer.fileno() >= 0:
        writer.close()


def test_a_reading_subscriber_gets_every_message_in_order(pair):
    writer, reader = pair
    transport = Transport(writer)
    connection = NonBlockingConnection(transport, Backlog())
    received = []
    for n in range(200):
        connection.write_data(message(n, 300))
        received += read_frames(reader)
    assert received == list(range(200))
    assert connection.dropped == 0
    assert transport.stat_num_msg == 200
    assert transport.stat_bytes == 200 * (300 + 4)


def test_a_stalled_subscriber_never_blocks_and_gets_the_newest_message(pair):
    """With nobody reading, 2000 writes of 10 kB return (the kernel holds about 128 kB). When
    the reader catches up and the backlog is flushed, every frame it gets is whole, in order,
    and the last is the newest written; the ones in between were dropped."""
    writer, reader = pair
    backlog = Backlog()
    connection = NonBlockingConnection(Transport(writer), backlog)
    for n in range(2000):
        connection.write_data(message(n, 10_000))
    assert backlog                           # something is waiting to be sent
    assert connection.dropped > 1900
    received = []
    for _ in range(100):
        received += read_frames(reader)
        backlog.flush()
        if not backlog:
            received += read_frames(reader)
            break
    assert not backlog
    assert received == sorted(received)
    assert received[0] == 0                  # the first message was started, so it is finished
    assert received[-1] == 1999              # the newest message is delivered
    assert len(received) + connection.dropped == 2000


def test_messages_flow_again_after_a_stall(pair):
    writer, reader = pair
    connection = NonBlockingConnection(Transport(writer), Backlog())
    for n in range(500):
        connection.write_data(message(n, 10_000))
    while read_frames(reader):
        connection.flush()
    for n in range(500, 510):
        connection.write_data(message(n, 300))
        assert read_frames(reader)[-1] == n


def test_a_subscriber_that_went_away_ends_the_connection(pair):
    """rospy drops a connection whose write raises TransportTerminated."""
    writer, reader = pair
    transport = Transport(writer)
    connection = NonBlockingConnection(transport, Backlog())
    reader.close()
    with pytest.raises(TransportTerminated):
        for n in range(10):
            connection.write_data(message(n, 300))
    assert transport.done
    with pytest.raises(TransportTerminated):
        connection.write_data(message(99, 300))


def test_flush_forgets_closed_connections(pair):
    writer, _reader = pair
    backlog = Backlog()
    transport = Transport(writer)
    connection = NonBlockingConnection(transport, backlog)
    for n in range(100):
        connection.write_data(message(n, 10_000))
    assert backlog
    transport.close()
    backlog.flush()
    assert not backlog


def test_other_attributes_are_the_transports(pair):
    writer, _reader = pair
    connection = NonBlockingConnection(Transport(writer), Backlog())
    assert connection.endpoint_id == "/listener"
    assert connection.done is False


class FakeImpl:
    def __init__(self):
        self.queue_size = 1
        self.connections = []

    def add_connection(self, connection):
        self.connections.append(connection)
        return True


class FakePublisher:
    def __init__(self):
        self.impl = FakeImpl()


def test_make_nonblocking_wraps_each_new_connection_once(pair):
    """No rospy writer thread (queue_size None), and every connection is wrapped, once."""
    writer, _reader = pair
    publisher, backlog = FakePublisher(), Backlog()
    make_nonblocking(publisher, backlog)
    make_nonblocking(publisher, backlog)
    assert publisher.impl.queue_size is None
    transport = Transport(writer)
    assert publisher.impl.add_connection(transport) is True
    (connection,) = publisher.impl.connections
    assert isinstance(connection, NonBlockingConnection)
    assert connection._connection is transport


def test_held_messages_leave_in_order_when_due(pair):
    """Between hold() and keep_until(t) nothing is written; send_due(now) writes, in order, the
    groups due by ``now`` and keeps the later ones."""
    writer, reader = pair
    backlog = Backlog()
    connection = NonBlockingConnection(Transport(writer), backlog)
    for group, due in ((range(0, 3), 10.0), (range(3, 5), 10.005), (range(5, 6), 10.010)):
        backlog.hold()
        for n in group:
            connection.write_data(message(n, 300))
        backlog.keep_until(due)
    backlog.hold()
    backlog.keep_until(10.020)  # nothing published: no group kept
    assert read_frames(reader) == []
    assert backlog.next_due() == 10.0
    backlog.send_due(9.999)
    assert read_frames(reader) == []
    backlog.send_due(10.005)
    assert read_frames(reader) == [0, 1, 2, 3, 4]
    assert backlog.next_due() == 10.010
    backlog.send_due()
    assert read_frames(reader) == [5]
    assert backlog.next_due() is None


def test_a_kept_message_for_a_subscriber_that_went_away_closes_its_connection(pair):
    writer, reader = pair
    backlog = Backlog()
    transport = Transport(writer)
    connection = NonBlockingConnection(transport, backlog)
    backlog.hold()
    connection.write_data(message(1, 300))
    backlog.keep_until(1.0)
    reader.close()
    for _ in range(10):  # the kernel may take the first writes after the peer closed
        backlog.send_due()
        if transport.done:
            break
        backlog.hold()
        connection.write_data(message(2, 300))
        backlog.keep_until(1.0)
    assert transport.done
    with pytest.raises(TransportTerminated):  # rospy then drops the connection
        connection.write_data(message(3, 300))


def test_each_write_runs_through_the_backlogs_timed_hook(pair):
    """Backlog(timed): every write of its connections runs as timed(write, data), whose result
    it returns (the node times them); without the hook the write runs directly."""
    writer, reader = pair
    calls = []

    def timed(write, data):
        calls.append(data)
        return write(data)
    connection = NonBlockingConnection(Transport(writer), Backlog(timed=timed))
    assert connection.write_data(message(1, 300)) is True
    assert calls == [message(1, 300)] and read_frames(reader) == [1]
    untimed = NonBlockingConnection(Transport(writer), Backlog())
    assert untimed.write_data(message(2, 300)) is True
    assert calls == [message(1, 300)] and read_frames(reader) == [2]
