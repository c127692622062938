"""Reading TCPROS handshakes so that one slow or hostile client cannot hold up the others.

Replaces: rospy's TCPROS server reading every handshake in its one accept thread, unbounded.

rospy accepts every inbound connection (subscribers of the node's topics and callers of its
services share one port) in one thread, and reads each connection's handshake header there
with no time limit and no size limit. A client that sends 2 bytes and waits, or an HTTP GET,
keeps every later subscriber and service call out until it closes; a 100 MB header is read
whole into memory.

``install()`` keeps rospy's accept thread but makes it only hand the socket on: each
handshake is read in its own short-lived thread, within ``HANDSHAKE_TIMEOUT`` wall seconds
and ``MAX_HEADER_BYTES`` (the header's length field is checked before its bytes are read), and
then goes to rospy's topic or service handler exactly as rospy would pass it. A refused
connection is closed; refusals are logged in one line, at most once per ``LOG_PERIOD``, with
the peer's address and how many were refused since the last line.
"""
import socket
import struct
import threading
import time
from typing import Callable, Optional

HANDSHAKE_TIMEOUT = 2.0  # wall s from accept to the last byte of the header
# The whole header (its fields: topic or service, md5sum, type, callerid, message_definition).
# A service call's header is about 100 bytes; a topic subscriber's carries the message's full
# definition: the largest of the sim's types and of ROS's common ones (sensor_msgs/CameraInfo) is
# under 8 KB, MoveIt's largest actions tens of KB. 256 KB keeps a wide margin while a refused
# client can make the sim hold at most MAX_PENDING x 256 KB.
MAX_HEADER_BYTES = 256 * 1024
MAX_PENDING = 64         # handshakes read at once; a connection beyond is closed at once
LOG_PERIOD = 5.0         # wall s between two lines about refused connections


class HandshakeRefused(Exception):
    """A handshake that is not read: too slow, too big, cut short or not a TCPROS header."""


def read_header(sock, deadline: float, limit: int = MAX_HEADER_BYTES,
                clock: Callable[[], float] = time.monotonic, timeout: float = HANDSHAKE_TIMEOUT
                ) -> bytes:
    """The handshake header from ``sock`` (its 4-byte length field and the fields, not a byte
    more: what follows stays in the socket for the handler). HandshakeRefused unless all of it
    came by ``deadline`` (``clock``) and is at most ``limit`` bytes. ``timeout``: the time
    limit, for the message."""
    prefix = _read_exactly(sock, 4, deadline, clock, timeout)
    (size,) = struct.unpack("<I", prefix)
    if size > limit:
        raise HandshakeRefused("a header of %d bytes is over the limit of %d" % (size, limit))
    return prefix + _read_exactly(sock, size, deadline, clock, timeout)


def _read_exactly(sock, count: int, deadline: float, clock, timeout: float) -> bytes:
    data = bytearray()
    while len(data) < count:
        remaining = deadline - clock()
        if remaining <= 0:
            raise HandshakeRefused("no whole header within %.3g s (%d bytes came)"
                                   % (timeout, len(data)))
        sock.settimeout(remaining)
        try:
            chunk = sock.recv(min(count - len(data), 65536))
        except socket.timeout:     # TimeoutError from Python 3.10 on
            continue  # the deadline check above refuses it
        if not chunk:
            raise HandshakeRefused("closed after %d bytes of its header" % len(data))
        data += chunk
    return bytes(data)


def _peer(addr) -> str:
    if isinstance(addr, tuple) and len(addr) >= 2:
        host = addr[0]
        return ("[%s]:%s" if ":" in str(host) else "%s:%s") % (host, addr[1])
    return str(addr)


class HandshakeGuard:
    """A TCPServer ``inbound_handler(sock, addr)`` that never blocks: it starts a thread that
    reads the header under the limits and then calls ``dispatch(sock, addr, header)`` with the
    socket blocking again, as rospy's own handler leaves it."""

    def __init__(self, dispatch: Callable, timeout: float = HANDSHAKE_TIMEOUT,
                 limit: int = MAX_HEADER_BYTES, max_pending: int = MAX_PENDING,
                 log: Optional[Callable[[str], None]] = None, log_period: float = LOG_PERIOD,
                 clock: Callable[[], float] = time.monotonic):
        self.dispatch = dispatch
        self.timeout = timeout
        self.limit = limit
        self.max_pending = max_pending
        self._log = log
        self.log_period = log_period
        self._clock = clock
        self._lock = threading.Lock()
        self.pending = 0
        self.refused = 0           # in all
        self._unlogged = 0         # refused since the last line
        self._last_line = None     # clock of the last line

    def __call__(self, sock, addr) -> None:
        with self._lock:
            full = self.pending >= self.max_pending
            if not full:
                self.pending += 1
        if full:
            self.refuse(sock, addr, "%d handshakes are already being read" % self.max_pending)
            return
        try:
            threading.Thread(target=self._handshake, args=(sock, addr, self._clock()),
                             name="tcpros handshake %s" % _peer(addr), daemon=True).start()
        except RuntimeError as err:  # no thread to be had
            self._done()
            self.refuse(sock, addr, str(err))

    def _done(self) -> None:
        with self._lock:
            self.pending -= 1

    def _handshake(self, sock, addr, accepted: float) -> None:
        try:
            from rosgraph.network import decode_ros_handshake_header
            raw = read_header(sock, accepted + self.timeout, self.limit, self._clock,
                              self.timeout)
            header = decode_ros_handshake_header(raw)
            sock.settimeout(None)
        except HandshakeRefused as err:
            self.refuse(sock, addr, str(err))
            return
        except Exception as err:  # noqa: BLE001 - garbage fields, a reset, ...: never raise here
            self.refuse(sock, addr, "%s: %s" % (type(err).__name__, err))
            return
        finally:
            self._done()
        self.dispatch(sock, addr, header)

    def refuse(self, sock, addr, reason: str) -> None:
        """Close ``sock``; a line about it unless one was written less than log_period ago."""
        with self._lock:
            self.refused += 1
            self._unlogged += 1
            now = self._clock()
            quiet = self._last_line is not None and now - self._last_line < self.log_period
            if not quiet:
                self._last_line, count, self._unlogged = now, self._unlogged, 0
        if not quiet:
            log = self._log
            if log is None:
                import rospy
                log = rospy.logwarn
            log("TCPROS: refused a connection from %s: %s%s"
                % (_peer(addr), reason,
                   " (%d refused since the last such line)" % count if count > 1 else ""))
        try:
            sock.close()
        except OSError:
            pass


def rospy_dispatch(server) -> Callable:
    """What rospy's TCPROSServer does with a header it has read (tcpros_base
    ``_tcp_server_callback`` after read_ros_handshake_header): a topic or service handler, or
    an error header back and the connection closed."""
    import rospy
    import rospy.core
    from rosgraph.network import write_ros_handshake_header
    from rospy.exceptions import TransportInitError

    def dispatch(sock, addr, header) -> None:
        try:
            if "topic" in header:
                err_msg = server.topic_connection_handler(sock, addr, header)
            elif "service" in header:
                err_msg = server.service_connection_handler(sock, addr, header)
            else:
                err_msg = "no topic or service name detected"
            if err_msg:
                if rospy.core.is_shutdown_requested():
                    write_ros_handshake_header(sock, {"error": "node shutting down"})
                    return
                write_ros_handshake_header(sock, {"error": err_msg})
                raise TransportInitError("Could not process inbound connection: " + err_msg
                                         + str(header))
        except TransportInitError as err:
            rospy.logwarn(str(err))
            sock.close()
        except Exception as err:  # noqa: BLE001 - as rospy: log, close, keep accepting
            if not rospy.core.is_shutdown_requested():
                rospy.logwarn("Inbound TCP/IP connection failed: %s", err)
            sock.close()
    return dispatch


def install() -> Optional[HandshakeGuard]:
    """Guard this process's TCPROS server (started here if rospy has not yet): from the next
    connection on. Call after rospy.init_node. The guard, or None if there is no server."""
    from rospy.impl import tcpros_base
    tcpros_base.start_tcpros_server()
    server = tcpros_base._tcpros_server
    tcp = getattr(server, "tcp_ros_server", None)
    if tcp is None:
        return None
    if isinstance(tcp.inbound_handler, HandshakeGuard):
        return tcp.inbound_handler
    guard = HandshakeGuard(rospy_dispatch(server))
    tcp.inbound_handler = guard  # TCPServer.run looks it up for every connection it accepts
    return guard
