"""One throttled warning line per client for a malformed service request, never a traceback.

Replaces: what rospy does with a request it cannot read. ``ServiceImpl.handle`` (tcpros_service)
runs in a thread of its own per connection; a body that does not deserialize (a string length of
0xffffffff) raises out of it, and the thread dies with a 35-line traceback on stderr; a request
cut short is an "incoming connection failed" error line. Both come once per connection, with no
limit: a client sending garbage in a loop wrote 700 lines a minute.

``install()`` wraps ``handle``: an exception raised out of it closes that connection and is told
in one warning line that names the service, the client (its callerid) and the fault, at most once
per WARN_PERIOD per client (the clients last warned about are remembered, at most MAX_CLIENTS);
and rospy's "incoming connection failed" line is held to the same rule. Requests that are read
are answered as before.
"""
import collections
import threading
import time
from typing import Callable, Optional

WARN_PERIOD = 60.0      # wall s between two warnings about one client
MAX_CLIENTS = 1000      # clients whose last warning is remembered (the oldest forgotten)
MAX_FAULT = 120         # characters of the fault in a warning


class ClientWarnings:
    """At most one line per client per WARN_PERIOD; ``log(line)`` writes (rospy.logwarn by
    default), ``clock()`` tells the time in s."""

    def __init__(self, log: Optional[Callable[[str], None]] = None,
                 clock: Callable[[], float] = time.monotonic):
        self._log = log
        self._clock = clock
        self._lock = threading.Lock()
        self._last: "collections.OrderedDict[str, float]" = collections.OrderedDict()

    def warn(self, client: str, line: str) -> bool:
        """Write ``line`` unless one about ``client`` was written within WARN_PERIOD; True if
        written."""
        now = self._clock()
        with self._lock:
            last = self._last.get(client)
            if last is not None and now - last < WARN_PERIOD:
                return False
            self._last[client] = now
            self._last.move_to_end(client)
            while len(self._last) > MAX_CLIENTS:
                self._last.popitem(last=False)
        log = self._log
        if log is None:
            import rospy
            log = rospy.logwarn
        log(line)
        return True


def fault_text(err: BaseException) -> str:
    """The fault in one short line: the innermost cause rospy wrapped, cut to MAX_FAULT."""
    text = " ".join(str(err).split()) or type(err).__name__
    return text if len(text) <= MAX_FAULT else text[:MAX_FAULT - 3] + "..."


_installed: Optional[ClientWarnings] = None
_caller = threading.local()   # the callerid of the connection this thread handles


def install(warnings: Optional[ClientWarnings] = None) -> ClientWarnings:
    """Wrap rospy's service connection handler (once per process)."""
    global _installed
    if _installed is not None:
        return _installed
    import rospy.impl.tcpros_service as tcpros_service

    said = warnings if warnings is not None else ClientWarnings()
    original_handle = tcpros_service.ServiceImpl.handle
    original_logerr = tcpros_service.logerr

    def handle(self, transport, header):
        client = header.get("callerid", "?") if isinstance(header, dict) else "?"
        _caller.value = (self.resolved_name, client)
        try:
            original_handle(self, transport, header)
        except Exception as err:  # noqa: BLE001 - the connection goes, the service stays
            said.warn(client, "%s: a malformed request from %s, connection closed: %s"
                      % (self.resolved_name, client, fault_text(err)))
            try:
                transport.close()
            except Exception:  # noqa: BLE001
                pass
        finally:
            _caller.value = None

    def logerr(msg, *args, **kwargs):
        where = getattr(_caller, "value", None)
        if where is not None and str(msg).startswith("incoming connection failed"):
            service, client = where
            said.warn(client, "%s: a request from %s was cut short; connection closed"
                      % (service, client))
            return None
        return original_logerr(msg, *args, **kwargs)

    tcpros_service.ServiceImpl.handle = handle
    tcpros_service.logerr = logerr
    _installed = said
    return said
