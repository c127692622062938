"""Publishing from the simulation loop without rospy's per-message thread switch.

Replaces: rospy.Publisher's writer thread per connection (queue_size) or its blocking write.

A rospy publisher with a ``queue_size`` hands every message to one writer thread per
subscriber connection and then yields the GIL (``time.sleep(0)``): about 80 us of CPU per
message here, which at 400 messages per sim second was most of the sim's time. Without a
``queue_size`` rospy writes synchronously, which is cheap (about 7 us) but blocks the whole
simulation on any subscriber that stops reading (a suspended ``rostopic echo``).

``make_nonblocking(publisher)`` keeps the cheap synchronous write and removes the blocking:
each subscriber connection writes with ``MSG_DONTWAIT``; when the kernel's socket buffer is
full, the unsent rest of the current message is kept (the byte stream stays whole) plus the
newest message, so a slow subscriber loses old messages, as with rospy's ``queue_size=1``,
and never slows the others or the simulation. ``Backlog.flush()`` retries the kept bytes;
the simulation loop calls it while anything is waiting.

Between ``Backlog.hold()`` and ``Backlog.keep_until(t)`` messages are serialized but not
written: they leave, in order, when ``send_due`` is called at wall time ``t`` or later. So the
simulation makes a step's messages as soon as it has stepped, and sends them when their stamps
are due on the wall clock, however long making them took. What one subscriber connection is
sent by one ``send_due`` goes in one write (one system call, one wake-up of the subscriber);
a stalled subscriber that cannot take it loses it whole.

``publisher.publish_packed(packed)`` sends a kept serialization (packed_messages) as rospy's
``publish`` would send the message: numbered with the publisher's sequence, to every
subscriber, without genpy or rospy's buffer.

``Backlog(timed)``: every write of its connections runs as ``timed(write, data)`` (the node
passes its timing recorder, which counts the write as its loop's "sending" time); without it
the write runs directly.
"""
import collections
import errno
import math
import socket
import threading
from typing import Callable, Optional

from rospy.core import is_shutdown
from rospy.exceptions import TransportTerminated

_GONE = (errno.EPIPE, errno.ECONNRESET, errno.ENOTCONN, errno.EBADF)


class Backlog:
    """The connections holding bytes they could not send yet."""

    def __init__(self, timed: Optional[Callable] = None):
        """``timed``: None, or ``timed(write, data)`` that runs ``write(data)`` and returns what
        it returned (around every write of this backlog's connections: the node times them)."""
        self.timed = timed
        self._lock = threading.Lock()
        self._waiting = set()
        self.held = None  # [(connection, bytes)] while holding, else None
        self._due = collections.deque()  # (wall time, [(connection, bytes)]), in time order

    def __bool__(self) -> bool:
        return bool(self._waiting)

    def hold(self) -> None:
        """Keep what is published from now on, in order, until keep_until()."""
        self.held = []

    def keep_until(self, wall_time: float) -> None:
        """Stop holding; what was held leaves at ``wall_time`` (see send_due)."""
        if self.held:
            self._due.append((wall_time, self.held))
        self.held = None

    def next_due(self) -> Optional[float]:
        """Wall time of the first kept group of messages, None if none is kept."""
        return self._due[0][0] if self._due else None

    def send_due(self, now: float = math.inf) -> None:
        """Send the kept groups due at ``now`` or before (all by default): a subscriber's
        messages, in order, in one write. A subscriber that went away meanwhile is closed;
        rospy drops it at its next publish."""
        by_connection = {}
        while self._due and self._due[0][0] <= now:
            for connection, data in self._due.popleft()[1]:
                by_connection.setdefault(connection, []).append(data)
        for connection, chunks in by_connection.items():
            try:
                connection.write_data(chunks[0] if len(chunks) == 1 else b"".join(chunks))
            except TransportTerminated:
                if not connection.done:
                    connection.close()

    def add(self, connection: "NonBlockingConnection") -> None:
        with self._lock:
            self._waiting.add(connection)

    def flush(self) -> None:
        """Send what the kernel now takes; forget connections that are done or closed."""
        with self._lock:
            waiting = list(self._waiting)
        for connection in waiting:
            if connection.flush():
                with self._lock:
                    self._waiting.discard(connection)


class NonBlockingConnection:
    """Wraps one rospy TCPROS publisher-side transport (``.socket``, ``.done``, ``.close()``,
    ``.stat_bytes``, ``.stat_num_msg``); everything else is forwarded to it."""

    def __init__(self, connection, backlog: Backlog):
        self._connection = connection
        self._backlog = backlog
        self._lock = threading.Lock()
        self._partial: Optional[memoryview] = None  # unsent tail of a message already started
        self._next: Optional[bytes] = None          # newest whole message not started yet
        self.dropped = 0                            # messages replaced before being sent

    def __getattr__(self, name):
        if name.startswith("__"):
            raise AttributeError(name)
        return getattr(self._connection, name)

    def write_data(self, data: bytes) -> bool:
        """Send one serialized message or keep it for later; never blocks. Raises
        TransportTerminated once the subscriber has gone (rospy then drops the connection)."""
        timed = self._backlog.timed
        if timed is None:
            return self._write(data)
        return timed(self._write, data)

    def _write(self, data: bytes) -> bool:
        held = self._backlog.held
        if held is not None:  # the loop sends it when its moment is due: release()
            if self._connection.done:
                raise TransportTerminated("connection closed")
            held.append((self, data))
            return True
        with self._lock:
            if self._connection.done:
                raise TransportTerminated("connection closed")
            if self._holding():
                self._send_kept()
                if self._holding():
                    if self._next is not None:
                        self.dropped += 1
                    self._next = data
                    self._backlog.add(self)
                    return True
            self._start(data)
            if self._holding():
                self._backlog.add(self)
            return True

    def flush(self) -> bool:
        """Try to send the kept bytes; True when nothing is left (or the connection is gone)."""
        with self._lock:
            if self._connection.done:
                return True
            try:
                self._send_kept()
            except TransportTerminated:
                return True
            return not self._holding()

    def _holding(self) -> bool:
        return self._partial is not None or self._next is not None

    def _send_kept(self) -> None:
        if self._partial is not None:
            self._partial = self._send(self._partial)
        if self._partial is None and self._next is not None:
            data, self._next = self._next, None
            self._start(data)

    def _start(self, data: bytes) -> None:
        rest = self._send(memoryview(data))
        if rest is not None and len(rest) == len(data):
            self._next = data  # nothing went out: it is still a whole message
            return
        self._connection.stat_num_msg += 1
        self._partial = rest

    def _send(self, data: memoryview) -> Optional[memoryview]:
        """Send what the kernel takes now; the unsent rest, or None when all went."""
        sock = self._connection.socket
        if sock is None:
            raise TransportTerminated("connection closed")
        try:
            sent = sock.send(data, socket.MSG_DONTWAIT)
        except BlockingIOError:
            sent = 0
        except OSError as err:
            if isinstance(err, ConnectionError) or err.errno in _GONE:
                self._connection.close()
                raise TransportTerminated("subscriber %s went away: %s"
                                          % (getattr(self._connection, "endpoint_id", "?"),
                                             err)) from None
            raise
        self._connection.stat_bytes += sent
        return data[sent:] if sent < len(data) else None


def make_nonblocking(publisher, backlog: Backlog) -> None:
    """From now on every new subscriber connection of ``publisher``'s topic (in this process)
    is written by NonBlockingConnection instead of rospy's writer thread."""
    impl = publisher.impl
    if getattr(impl, "_nonblocking_backlog", None) is not None:
        return
    impl._nonblocking_backlog = backlog
    impl.queue_size = None  # rospy wraps connections in its threaded queue only with a size
    add_connection = impl.add_connection

    def add_nonblocking_connection(connection):
        sock = getattr(connection, "socket", None)
        if sock is not None:
            # Each message leaves when it is written: without this, Nagle's algorithm holds a
            # small message back until the last one is acknowledged, tens of ms with delayed ACKs.
            try:
                sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
            except OSError:
                pass  # not a TCP socket (a test's socket pair)
        return add_connection(NonBlockingConnection(connection, backlog))
    impl.add_connection = add_nonblocking_connection
    publisher.publish_packed = lambda packed: publish_packed(publisher, packed)


def publish_packed(publisher, packed) -> bool:
    """What ``publisher.publish(msg)`` does, for a message kept serialized in ``packed``
    (packed_messages.Packed): nothing without a subscriber; else the next sequence number goes
    into its header (if it has one), and its bytes to every connection. False if not sent."""
    impl = publisher.impl
    if impl is None or impl.closed or not impl.connections:
        return False
    with impl.publock:
        impl.seq += 1
        if packed.has_header:
            packed.set_header_seq(impl.seq)
        data = packed.bytes()
        gone = []
        for connection in impl.connections:
            try:
                if not is_shutdown():
                    connection.write_data(data)
            except Exception:  # as rospy: a connection that fails is closed and dropped
                gone.append(connection)
        impl.message_data_sent += len(data)
    for connection in gone:
        try:
            connection.close()
        except Exception:
            pass
    return True
