"""One line about a publisher the sim cannot reach, instead of a robot that silently ignores it.

Replaces: rospy's silence (debug-level logs) about a publisher it cannot connect to.

A node on another host that has neither ``ROS_IP`` nor ``ROS_HOSTNAME`` set advertises its
topics at an address (its hostname, often) that this host cannot resolve or reach. rospy's
subscriber then fails quietly: the publisher's XML-RPC ``requestTopic`` fails in
``ROSHandler._connect_topic`` (masterslave; the failure is logged at debug level and retried
or dropped), or the TCPROS address it answers cannot be connected to in
``TCPROSTransport.connect`` (tcpros_base; logged to rospy's internal log only, and retried).

``install()`` wraps those two calls (rospy's behaviour is unchanged: the same results, the same
exceptions, the same retries) and writes one warning per (topic, publisher URI):

    cannot reach /teleop's publisher of /cmd_vel at http://badhost:4567/: [Errno -2] Name or
    service not known; is ROS_IP or ROS_HOSTNAME set on its machine?

with ``(TCPROS host:port)`` after the URI when it is the TCPROS address that failed. The
publisher's node name is looked up at the master (best effort) only when a line is written.
"""
import errno
import socket
import threading
from typing import Callable, Optional

HINT = "is ROS_IP or ROS_HOSTNAME set on its machine?"
LOOKUP_TIMEOUT = 2.0  # wall s for the master's answer when naming the publisher's node
MAX_REPORTED = 256    # (topic, URI) pairs remembered as already named


def describe_error(err: BaseException) -> str:
    """A short reason for a failed connection: 'connection refused', 'timed out', ..."""
    while isinstance(err, Exception) and not isinstance(err, OSError) and err.__context__:
        err = err.__context__   # TransportInitError re-raises the socket error's text
    if isinstance(err, socket.timeout):
        return "timed out"
    if isinstance(err, OSError) and err.strerror:
        text = err.strerror
        return text[:1].lower() + text[1:]
    return str(err) or type(err).__name__


class UnreachableLog:
    """Writes the line once per (topic, publisher URI). ``name_of(topic, uri)`` gives the
    publisher's node name or None; ``log(line)`` writes (rospy.logwarn by default)."""

    def __init__(self, log: Optional[Callable[[str], None]] = None,
                 name_of: Optional[Callable[[str, str], Optional[str]]] = None):
        self._log = log
        self._name_of = name_of if name_of is not None else publisher_node
        self._lock = threading.Lock()
        self.reported = {}        # (topic, uri): None, oldest first; at most MAX_REPORTED

    def report(self, topic: str, uri: str, error: BaseException, tcpros=None) -> bool:
        """Write the line unless one was written for (topic, uri); True if written.
        ``tcpros``: the (host, port) that failed, None when it was the XML-RPC URI."""
        key = (topic, uri)
        with self._lock:
            if key in self.reported:
                return False
            if len(self.reported) >= MAX_REPORTED:   # a flood of URIs: forget the oldest
                del self.reported[next(iter(self.reported))]
            self.reported[key] = None
        try:
            node = self._name_of(topic, uri)
        except Exception:  # noqa: BLE001 - naming the node is a courtesy, never a failure
            node = None
        line = "cannot reach %s of %s at %s%s: %s; %s" % (
            "%s's publisher" % node if node else "a publisher", topic, uri,
            " (TCPROS %s:%s)" % tuple(tcpros) if tcpros else "", describe_error(error), HINT)
        log = self._log
        if log is None:
            import rospy
            log = rospy.logwarn
        log(line)
        return True


def publisher_node(topic: str, uri: str) -> Optional[str]:
    """The name of the node at ``uri`` among the master's publishers of ``topic`` (or None)."""
    import xmlrpc.client

    import rosgraph
    import rospy

    class _Transport(xmlrpc.client.Transport):
        def make_connection(self, host):
            conn = super().make_connection(host)
            conn.timeout = LOOKUP_TIMEOUT
            return conn

    master = xmlrpc.client.ServerProxy(rosgraph.get_master_uri(), transport=_Transport())
    caller_id = rospy.get_name()
    code, _, state = master.getSystemState(caller_id)
    if code != 1:
        return None
    for name, nodes in state[0]:
        if name == topic:
            for node in nodes:
                code, _, node_uri = master.lookupNode(caller_id, node)
                if code == 1 and node_uri.rstrip("/") == uri.rstrip("/"):
                    return node
    return None


class _WatchedProxy:
    """An XML-RPC proxy whose ``requestTopic`` reports a failure before raising it."""

    def __init__(self, proxy, uri: str, log: UnreachableLog):
        self._proxy, self._uri, self._log = proxy, uri, log

    def requestTopic(self, caller_id, topic, protocols):  # noqa: N802 - the XML-RPC name
        try:
            return self._proxy.requestTopic(caller_id, topic, protocols)
        except Exception as err:
            self._log.report(topic, self._uri, err)
            raise

    def __getattr__(self, name):
        return getattr(self._proxy, name)


_installed: Optional[UnreachableLog] = None


def install(log: Optional[UnreachableLog] = None) -> UnreachableLog:
    """Wrap rospy's requestTopic call and TCPROS subscriber connect (once per process)."""
    global _installed
    if _installed is not None:
        return _installed
    import rospy.impl.masterslave as masterslave
    from rospy.impl.tcpros_base import TCPROSTransport
    from rospy.impl.tcpros_pubsub import TCPROSSub

    unreachable = log if log is not None else UnreachableLog()
    original_api = masterslave.xmlrpcapi   # used there only by _connect_topic

    def xmlrpcapi(uri, cache=True):
        proxy = original_api(uri, cache=cache)
        return None if proxy is None else _WatchedProxy(proxy, uri, unreachable)
    masterslave.xmlrpcapi = xmlrpcapi

    original_connect = TCPROSTransport.connect

    def connect(self, dest_addr, dest_port, endpoint_id, timeout=None):
        subscriber = isinstance(self.protocol, TCPROSSub)   # close() clears it on failure
        try:
            return original_connect(self, dest_addr, dest_port, endpoint_id, timeout=timeout)
        except Exception as err:
            # A subscriber's connection that failed at the socket (not a refused handshake,
            # not a publisher that hung up in the middle of it).
            cause = err.__context__
            if (subscriber and isinstance(cause, OSError)
                    and getattr(cause, "errno", None) not in (errno.ECONNRESET, errno.EPIPE)):
                unreachable.report(getattr(self, "name", "?"), endpoint_id, cause,
                                   (dest_addr, dest_port))
            raise
    TCPROSTransport.connect = connect
    _installed = unreachable
    return unreachable
