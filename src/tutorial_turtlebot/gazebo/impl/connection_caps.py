"""Caps on inbound TCPROS connections, and an end to those whose subscriber has gone or stalled.

Replaces: rospy's accepting every subscriber and service caller with no limit, and its keeping
a closed or stalled subscriber's connection (and writer thread) until the next publish.

rospy gives every subscriber of a publisher with a ``queue_size`` (``/rosout``,
dynamic_reconfigure's ``parameter_updates``) a writer thread (``QueuedConnection``), and every
service connection a thread (``ServiceImpl.handle``), with no limit: 14,400 clients that never
read gave 24,279 threads, and then ``can't start new thread`` locked every client out. A
subscriber that goes away is noticed only when its topic next publishes, so its thread and fd
stay (on ``parameter_updates``, for as long as nobody reconfigures); one that stops reading
keeps its writer thread blocked in ``sendall`` forever.

``install()`` wraps the TCPROS server's ``topic_connection_handler`` and
``service_connection_handler`` (called once a handshake is read, before rospy makes the
transport or its thread) and ``ServiceImpl.handle``: a connection beyond
``MAX_SUBSCRIBERS_PER_TOPIC`` subscribers of its topic, ``MAX_CALLERS_PER_SERVICE`` open
connections to its service or ``MAX_INBOUND`` in all is sent an error header and closed. And it
starts one thread, ``ConnectionWatch``, that every ``WATCH_PERIOD`` looks at every subscriber
connection of the node's publishers: one whose peer closed is removed at once (its writer thread
ends); one with bytes unsent and no byte taken for ``STALL_TIMEOUT`` is dropped (rospy and
roscpp subscribers connect again). Each kind of refusal or drop is one warning line at most
every ``LOG_PERIOD``, with how many since the last.
"""
import fcntl
import select
import socket
import struct
import termios
import threading
import time
from typing import Callable, Dict, Optional

MAX_SUBSCRIBERS_PER_TOPIC = 64   # subscriber connections of one of the node's topics
MAX_CALLERS_PER_SERVICE = 16     # open connections (calls, persistent clients) to one service
MAX_INBOUND = 512                # subscriber and service connections in all
STALL_TIMEOUT = 30.0             # wall s with bytes unsent and none taken: dropped
WATCH_PERIOD = 0.5               # wall s between two looks at the connections
LOG_PERIOD = 5.0                 # wall s between two lines of one kind
REFUSAL_TIMEOUT = 0.5            # wall s to write the error header of a refused connection


class ThrottledLines:
    """One line per kind at most every ``period`` s, counting those held back."""

    def __init__(self, log: Optional[Callable[[str], None]] = None, period: float = LOG_PERIOD,
                 clock: Callable[[], float] = time.monotonic):
        self._log = log
        self.period = period
        self._clock = clock
        self._lock = threading.Lock()
        self._last: Dict[str, float] = {}
        self._held: Dict[str, int] = {}
        self.counts: Dict[str, int] = {}   # every event, by kind

    def line(self, kind: str, text: str) -> bool:
        """Write ``text`` unless a line of ``kind`` was written less than period ago."""
        with self._lock:
            self.counts[kind] = self.counts.get(kind, 0) + 1
            now = self._clock()
            last = self._last.get(kind)
            if last is not None and now - last < self.period:
                self._held[kind] = self._held.get(kind, 0) + 1
                return False
            self._last[kind] = now
            held = self._held.pop(kind, 0)
        log = self._log
        if log is None:
            import rospy
            log = rospy.logwarn
        log(text + (" (and %d more since the last such line)" % held if held else ""))
        return True


class ConnectionCaps:
    """The counts behind the caps. ``topic_count(topic)``: subscriber connections the topic
    has; ``all_topics()``: those of every topic."""

    def __init__(self, topic_count: Callable[[str], int], all_topics: Callable[[], int],
                 per_topic: int = MAX_SUBSCRIBERS_PER_TOPIC,
                 per_service: int = MAX_CALLERS_PER_SERVICE, total: int = MAX_INBOUND,
                 lines: Optional[ThrottledLines] = None):
        self.topic_count, self.all_topics = topic_count, all_topics
        self.per_topic, self.per_service, self.total = per_topic, per_service, total
        self.lines = lines if lines is not None else ThrottledLines()
        self._lock = threading.Lock()
        self._topic_pending: Dict[str, int] = {}   # being handed to rospy now
        self.services: Dict[str, int] = {}         # open service connections, by service

    def _inbound(self) -> int:
        return (self.all_topics() + sum(self._topic_pending.values())
                + sum(self.services.values()))

    def admit_topic(self, topic: str) -> Optional[str]:
        """None and a reservation (end it with topic_done), or why the subscriber is refused."""
        with self._lock:
            if self.topic_count(topic) + self._topic_pending.get(topic, 0) >= self.per_topic:
                return "%s has %d subscribers, the most it takes" % (topic, self.per_topic)
            if self._inbound() >= self.total:
                return "%d connections are open, the most the sim takes" % self.total
            self._topic_pending[topic] = self._topic_pending.get(topic, 0) + 1
        return None

    def topic_done(self, topic: str) -> None:
        """The subscriber is now in the topic's connections (or was refused by rospy)."""
        with self._lock:
            release(self._topic_pending, topic)

    def admit_service(self, service: str) -> Optional[str]:
        """None and a reservation (end it with service_done), or why the caller is refused."""
        with self._lock:
            if self.services.get(service, 0) >= self.per_service:
                return ("%s has %d open connections, the most it takes"
                        % (service, self.per_service))
            if self._inbound() >= self.total:
                return "%d connections are open, the most the sim takes" % self.total
            self.services[service] = self.services.get(service, 0) + 1
        return None

    def service_done(self, service: str) -> None:
        """A service connection ended (or never started its thread)."""
        with self._lock:
            release(self.services, service)


def release(counts: Dict[str, int], key: str) -> None:
    """One of ``counts[key]`` ended: counted down, the key dropped at 0 (callers hold the
    lock that guards ``counts``)."""
    left = counts.get(key, 0) - 1
    if left > 0:
        counts[key] = left
    else:
        counts.pop(key, None)


def refuse(sock, reason: str) -> None:
    """Send ``reason`` as a TCPROS error header (if the client takes it at once) and close."""
    from rosgraph.network import write_ros_handshake_header
    try:
        sock.settimeout(REFUSAL_TIMEOUT)
        write_ros_handshake_header(sock, {"error": reason})
    except Exception:  # noqa: BLE001 - a client that does not read is closed all the same
        pass
    try:
        sock.close()
    except OSError:
        pass


def unsent_bytes(sock) -> int:
    """Bytes in the socket's send queue not yet taken by the peer (Linux TIOCOUTQ)."""
    buf = fcntl.ioctl(sock.fileno(), termios.TIOCOUTQ, b"\0\0\0\0")
    return struct.unpack("i", buf)[0]


def peer_closed(sock) -> bool:
    """True if the peer hung up (a subscriber sends nothing after its handshake)."""
    try:
        return sock.recv(1, socket.MSG_PEEK | socket.MSG_DONTWAIT) == b""
    except BlockingIOError:
        return False
    except OSError:
        return True


class ConnectionWatch:
    """Removes subscriber connections whose peer closed, or that took no byte for
    ``stall_timeout`` with bytes unsent. ``topics()``: the node's publisher impls (each with
    ``.connections``, ``.remove_connection(c)`` and ``.resolved_name``)."""

    def __init__(self, topics: Callable[[], list], stall_timeout: float = STALL_TIMEOUT,
                 lines: Optional[ThrottledLines] = None,
                 clock: Callable[[], float] = time.monotonic):
        self.topics = topics
        self.stall_timeout = stall_timeout
        self.lines = lines if lines is not None else ThrottledLines()
        self._clock = clock
        self._progress: Dict[int, tuple] = {}   # id(connection): ((sent, unsent), since)
        self.closed = 0
        self.stalled = 0

    def scan(self) -> None:
        """One look at every connection."""
        now = self._clock()
        poller = select.poll()
        by_fd = {}
        seen = set()
        for impl in list(self.topics()):
            for conn in list(impl.connections or ()):
                sock = getattr(conn, "socket", None)
                if sock is None or getattr(conn, "done", False):
                    continue
                try:
                    fd = sock.fileno()
                except OSError:
                    continue
                if fd < 0:
                    continue
                by_fd[fd] = (impl, conn, sock)
                seen.add(id(conn))
                poller.register(fd, select.POLLIN | select.POLLRDHUP)
        gone = set()
        for fd, events in poller.poll(0):
            impl, conn, sock = by_fd[fd]
            if events & (select.POLLHUP | select.POLLERR | select.POLLRDHUP | select.POLLNVAL) \
                    or peer_closed(sock):
                gone.add(fd)
                self.closed += 1
                self._remove(impl, conn)
        for fd, (impl, conn, sock) in by_fd.items():
            if fd not in gone and self._stalled(conn, sock, now):
                self.stalled += 1
                self.lines.line("stalled", "TCPROS: dropped %s's subscriber %s: it took no byte "
                                "for %.0f s" % (impl.resolved_name,
                                                getattr(conn, "endpoint_id", "?"),
                                                self.stall_timeout))
                self._remove(impl, conn)
        for key in list(self._progress):
            if key not in seen:
                del self._progress[key]

    def _stalled(self, conn, sock, now: float) -> bool:
        try:
            unsent = unsent_bytes(sock)
        except OSError:
            return False
        key = id(conn)
        if unsent == 0:
            self._progress.pop(key, None)
            return False
        state = (getattr(conn, "stat_bytes", 0), unsent)
        last = self._progress.get(key)
        if last is None or last[0] != state:
            self._progress[key] = (state, now)
            return False
        return now - last[1] >= self.stall_timeout

    def _remove(self, impl, conn) -> None:
        self._progress.pop(id(conn), None)
        try:
            impl.remove_connection(conn)   # closes it: rospy's writer thread, if any, ends
        except Exception:  # noqa: BLE001 - never end the watch
            try:
                conn.close()
            except Exception:  # noqa: BLE001
                pass

    def run(self, period: float = WATCH_PERIOD,
            stopped: Callable[[], bool] = lambda: False) -> None:
        """Scan every ``period`` s until ``stopped()``."""
        while not stopped():
            try:
                self.scan()
            except Exception as err:  # noqa: BLE001 - a topic closed meanwhile, ...
                self.lines.line("watch", "TCPROS: connection watch: %s: %s"
                                % (type(err).__name__, err))
            time.sleep(period)


def wrap_handlers(server, caps: ConnectionCaps) -> None:
    """Put the caps in front of ``server``'s topic and service connection handlers."""
    topic_handler = server.topic_connection_handler
    service_handler = server.service_connection_handler

    def topic_connection_handler(sock, client_addr, header):
        topic = header.get("topic", "")
        reason = caps.admit_topic(topic)
        if reason is not None:
            caps.lines.line("topic", "TCPROS: refused a subscriber of %s from %s: %s"
                            % (topic, header.get("callerid", "?"), reason))
            refuse(sock, reason)
            return None
        try:
            return topic_handler(sock, client_addr, header)
        finally:
            caps.topic_done(topic)

    def service_connection_handler(sock, client_addr, header):
        service = header.get("service", "")
        reason = caps.admit_service(service)
        if reason is not None:
            caps.lines.line("service", "TCPROS: refused a caller of %s from %s: %s"
                            % (service, header.get("callerid", "?"), reason))
            refuse(sock, reason)
            return None
        started = False
        try:
            err = service_handler(sock, client_addr, header)
            started = not err   # rospy started ServiceImpl.handle's thread
            return err
        finally:
            if not started:
                caps.service_done(service)

    topic_connection_handler.caps = caps
    server.topic_connection_handler = topic_connection_handler
    server.service_connection_handler = service_connection_handler


_installed: Optional[ConnectionCaps] = None


def install() -> ConnectionCaps:
    """Cap this process's inbound connections and start the watch (once; after
    rospy.init_node, before the first topic and service)."""
    global _installed
    if _installed is not None:
        return _installed
    import rospy.core
    from rospy.impl import registration, tcpros_base
    from rospy.impl.tcpros_service import ServiceImpl

    def publishers():
        return list(registration.get_topic_manager().pubs.values())

    def topic_count(topic):
        impl = registration.get_topic_manager().get_publisher_impl(topic)
        return len(impl.connections or ()) if impl is not None else 0

    def all_topics():
        return sum(len(impl.connections or ()) for impl in publishers())

    lines = ThrottledLines()
    caps = ConnectionCaps(topic_count, all_topics, lines=lines)
    tcpros_base.start_tcpros_server()
    wrap_handlers(tcpros_base._tcpros_server, caps)

    handle = ServiceImpl.handle

    def counted_handle(self, transport, header):
        try:
            return handle(self, transport, header)
        finally:
            caps.service_done(header.get("service", self.resolved_name))
    ServiceImpl.handle = counted_handle

    watch = ConnectionWatch(publishers, lines=lines)
    threading.Thread(target=watch.run, kwargs=dict(stopped=rospy.core.is_shutdown),
                     name="tcpros connection watch", daemon=True).start()
    caps.watch = watch
    _installed = caps
    return caps
