"""A bound on the publishers a subscriber connects to, and an end to retrying those that hang.

Replaces: rospy's one connect thread per publisher URI in every ``publisherUpdate``, each
retrying forever while the publisher hangs.

``publisherUpdate`` is ROS 1's unauthenticated slave API: anyone may name any number of
publishers. rospy's ``RegManager`` starts a thread per URI named (``_connect_topic``), which
calls ``requestTopic`` with a 60 s socket timeout and retries a publisher that hangs forever
(only a refused connection ends it), even after an update that no longer names it; its
TCPROS connect (``robust_connect_subscriber``) retries the same way. 1,000 hanging URIs gave
1,000 threads that never end.

``install()`` wraps ``RegManager.publisher_update`` (each update is cut to the first
``MAX_PUBLISHERS_PER_TOPIC`` URIs, those already connected first), ``ROSHandler.publisherUpdate``
(an empty update is noted too), ``ROSHandler._connect_topic`` (a URI the latest update no longer
names, or one beyond ``MAX_PUBLISHERS_PER_TOPIC`` connected or connecting, is not tried),
masterslave's ``xmlrpcapi`` (``requestTopic`` within ``REQUEST_TIMEOUT``; after
``MAX_ATTEMPTS`` failures, or once the URI is no longer named, rospy is answered a failure and
stops) and ``TCPROSTransport.connect`` of a subscriber (within ``REQUEST_TIMEOUT``, at most
``MAX_ATTEMPTS`` times while named). Install it before unreachable_publishers, whose wrappers
then see these calls. Each kind of refusal is one warning line at most every 5 s.
"""
import errno
import threading
import xmlrpc.client
from typing import Callable, Dict, Optional, Set

from .connection_caps import ThrottledLines, release

MAX_PUBLISHERS_PER_TOPIC = 32   # publishers of one topic connected or being connected
REQUEST_TIMEOUT = 10.0          # wall s for one requestTopic, and for one TCPROS connect
MAX_ATTEMPTS = 3                # tries of one publisher (rospy waits 1 s, 2 s between them)


class PublisherBudget:
    """What the latest update of each subscribed topic named, and the connects under way."""

    def __init__(self, per_topic: int = MAX_PUBLISHERS_PER_TOPIC,
                 lines: Optional[ThrottledLines] = None):
        self.per_topic = per_topic
        self.lines = lines if lines is not None else ThrottledLines()
        self._lock = threading.Lock()
        self.named: Dict[str, Set[str]] = {}      # topic: URIs of its latest update
        self.connecting: Dict[str, int] = {}      # topic: connects under way

    def update(self, topic: str, uris, connected: Callable[[str], bool]) -> list:
        """The URIs to connect to: at most per_topic, the already connected first."""
        unique = list(dict.fromkeys(u for u in uris if isinstance(u, str)))
        kept = [u for u in unique if connected(u)]
        kept += [u for u in unique if not connected(u)]
        if len(kept) > self.per_topic:
            self.lines.line("update", "publisherUpdate: %s named %d publishers; the sim "
                            "connects to %d at most" % (topic, len(unique), self.per_topic))
            kept = kept[:self.per_topic]
        with self._lock:
            self.named[topic] = set(kept)
        return kept

    def is_named(self, topic: str, uri: str) -> bool:
        """True unless the latest update of ``topic`` left ``uri`` out."""
        with self._lock:
            named = self.named.get(topic)
            return named is None or uri in named

    def start(self, topic: str, connections: int) -> bool:
        """Reserve a connect to a new publisher of ``topic`` (end it with done)."""
        with self._lock:
            under_way = self.connecting.get(topic, 0)
            if connections + under_way >= self.per_topic:
                refused = True
            else:
                refused = False
                self.connecting[topic] = under_way + 1
        if refused:
            self.lines.line("connect", "publisherUpdate: %s has %d publishers connected or "
                            "connecting, the most the sim takes" % (topic, self.per_topic))
        return not refused

    def done(self, topic: str) -> None:
        """A connect reserved by start ended."""
        with self._lock:
            release(self.connecting, topic)

    def forget(self, subscribed: Set[str]) -> None:
        """Drop what is kept about topics no longer subscribed."""
        with self._lock:
            for topic in list(self.named):
                if topic not in subscribed:
                    del self.named[topic]


class _TimeoutTransport(xmlrpc.client.Transport):
    def make_connection(self, host):
        conn = super().make_connection(host)
        conn.timeout = REQUEST_TIMEOUT
        return conn


_attempts = threading.local()   # requestTopic tries in this connect thread


class BoundedRequest:
    """A publisher's XML-RPC API whose ``requestTopic`` is timed and tried MAX_ATTEMPTS times:
    then (or once ``is_named`` says no) it answers rospy a failure, which stops its retries."""

    def __init__(self, uri: str, is_named: Callable[[str, str], bool], proxy=None):
        self._uri = uri
        self._is_named = is_named
        self._proxy = proxy if proxy is not None else xmlrpc.client.ServerProxy(
            uri, transport=_TimeoutTransport())

    def requestTopic(self, caller_id, topic, protocols):  # noqa: N802 - the XML-RPC name
        tries = getattr(_attempts, "count", 0) + 1
        _attempts.count = tries
        try:
            return self._proxy.requestTopic(caller_id, topic, protocols)
        except Exception as err:
            if getattr(err, "errno", None) == errno.ECONNREFUSED:
                raise   # rospy stops at once
            if tries >= MAX_ATTEMPTS:
                return [0, "gave up on %s after %d tries: %s" % (self._uri, tries, err), []]
            if not self._is_named(topic, self._uri):
                return [0, "%s is no longer a publisher of %s" % (self._uri, topic), []]
            raise   # rospy waits and tries again

    def __getattr__(self, name):
        return getattr(self._proxy, name)


_installed: Optional[PublisherBudget] = None


def install() -> PublisherBudget:
    """Wrap rospy's publisher connects (once per process; before unreachable_publishers)."""
    global _installed
    if _installed is not None:
        return _installed
    import rospy.impl.masterslave as masterslave
    from rospy.impl.registration import RegManager, get_topic_manager
    from rospy.impl.tcpros_base import TCPROSTransport
    from rospy.impl.tcpros_pubsub import TCPROSSub

    budget = PublisherBudget()

    def subscriber(topic):
        return get_topic_manager().get_subscriber_impl(topic)

    publisher_update = RegManager.publisher_update

    def bounded_publisher_update(self, resolved_name, uris):
        sub = subscriber(resolved_name)
        if sub is not None and isinstance(uris, list):
            uris = budget.update(resolved_name, uris, sub.has_connection)
        return publisher_update(self, resolved_name, uris)
    RegManager.publisher_update = bounded_publisher_update

    handler_update = masterslave.ROSHandler.publisherUpdate

    def publisherUpdate(self, caller_id, topic, publishers):  # noqa: N802 - the XML-RPC name
        if publishers == [] and isinstance(topic, str) and subscriber(topic) is not None:
            budget.update(topic, [], lambda uri: False)   # rospy itself never looks at it
        subs = get_topic_manager().subs
        budget.forget(set(subs))
        return handler_update(self, caller_id, topic, publishers)
    masterslave.ROSHandler.publisherUpdate = publisherUpdate

    connect_topic = masterslave.ROSHandler._connect_topic

    def bounded_connect_topic(self, topic, pub_uri):
        sub = subscriber(topic)
        if sub is None or sub.has_connection(pub_uri):
            return connect_topic(self, topic, pub_uri)   # rospy's answer, at once
        if not budget.is_named(topic, pub_uri):
            return 0, "%s is no longer a publisher of %s" % (pub_uri, topic), 0
        if not budget.start(topic, len(sub.connections or ())):
            return 0, "%s has %d publishers already" % (topic, budget.per_topic), 0
        _attempts.count = 0
        try:
            return connect_topic(self, topic, pub_uri)
        finally:
            budget.done(topic)
    masterslave.ROSHandler._connect_topic = bounded_connect_topic

    original_api = masterslave.xmlrpcapi   # used there only by _connect_topic

    def xmlrpcapi(uri, cache=True):
        proxy = original_api(uri, cache=cache)
        if proxy is None or cache:
            return proxy
        return BoundedRequest(uri, budget.is_named)
    masterslave.xmlrpcapi = xmlrpcapi

    original_connect = TCPROSTransport.connect

    def connect(self, dest_addr, dest_port, endpoint_id, timeout=None):
        if not isinstance(self.protocol, TCPROSSub):
            return original_connect(self, dest_addr, dest_port, endpoint_id, timeout=timeout)
        tries = getattr(self, "_bounded_tries", 0) + 1
        self._bounded_tries = tries
        limit = REQUEST_TIMEOUT if timeout is None else min(timeout, REQUEST_TIMEOUT)
        try:
            return original_connect(self, dest_addr, dest_port, endpoint_id, timeout=limit)
        except Exception:
            if self.protocol is not None and (
                    tries >= MAX_ATTEMPTS or not budget.is_named(self.name, endpoint_id)):
                self.close()   # robust_connect_subscriber stops when the protocol is gone
            raise
    TCPROSTransport.connect = connect
    _installed = budget
    return budget
