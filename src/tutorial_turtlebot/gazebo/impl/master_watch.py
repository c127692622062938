"""Registering again with a ROS master that was restarted.

Replaces: rospy registers a node with the master once, at start-up, never again.

A restarted master knows nothing of the nodes that were running: their connections go on, but a
new subscriber, a service call or ``rosparam get`` finds nothing of the sim. rospy (like roscpp,
and so Gazebo) registers a node only once, at start-up.

``MasterWatch`` asks the master, from its own thread every ``PERIOD`` wall seconds, for its pid
and for this node's URI (two small XML-RPC calls; nothing in the stepping loop). When the pid
changed or the master does not know this node, it registers again every publication,
subscription and service rospy holds, through rospy's own RegManager (``reg_added``, which also
connects the subscriptions to the publishers the new master knows), and sets again the
parameters it keeps: ``/use_sim_time`` (as it was at start; true when it was unset, as Gazebo
sets it) and the robot descriptions seen while the old master ran (``/robot_description``, and
``robot_description`` in each robot's namespace). A parameter the new master already has is
left as it is. One line says so:

    ROS master restarted: registered again 21 topics, 9 services, 2 parameters
"""
import threading
import time
import xmlrpc.client
from typing import Callable, Dict, Iterable, Optional

PERIOD = 1.0          # wall s between two looks at the master
CALL_TIMEOUT = 2.0    # wall s for one answer of the master


class _Transport(xmlrpc.client.Transport):
    def make_connection(self, host):
        conn = super().make_connection(host)
        conn.timeout = CALL_TIMEOUT
        return conn


def master_proxy(uri: str) -> xmlrpc.client.ServerProxy:
    """A proxy to the master whose calls give up after CALL_TIMEOUT (a fresh connection per
    proxy: one to a master that was restarted is gone)."""
    return xmlrpc.client.ServerProxy(uri, transport=_Transport())


def rospy_registrar():
    """rospy's RegManager (the registration listener that talks to the master)."""
    from rospy.impl.registration import RegManager, get_registration_listeners
    return next((listener for listener in list(get_registration_listeners().listeners)
                 if isinstance(listener, RegManager)), None)


class MasterWatch:
    """Notices a restarted master and registers the node again (see the module's doc).
    ``robot_namespaces()`` gives the namespaces of the sim's robots ("" = the node's)."""

    def __init__(self, robot_namespaces: Callable[[], Iterable[str]] = lambda: (),
                 period: float = PERIOD, log: Optional[Callable[[str], None]] = None):
        import rosgraph
        import rospy
        self.robot_namespaces = robot_namespaces
        self.period = period
        self.master_uri = rosgraph.get_master_uri()
        self.caller_id = rospy.get_name()
        self.namespace = rospy.get_namespace()
        self._log = log if log is not None else rospy.loginfo
        self.master_pid = None       # of the master this node is registered with
        self.params: Dict[str, object] = {}   # parameter -> value to set again
        self.use_sim_time = None     # the value at start (None: unset)
        self._seen_namespaces = set()
        self.restarts = 0
        self.last_registration = None   # wall s the last registration took
        self._stop = threading.Event()
        self._thread = None

    # --- thread ----------------------------------------------------------------------------------

    def start(self) -> "MasterWatch":
        self._thread = threading.Thread(target=self._run, name="master watch", daemon=True)
        self._thread.start()
        return self

    def stop(self) -> None:
        self._stop.set()

    def _run(self) -> None:
        import rospy
        while not self._stop.wait(self.period) and not rospy.is_shutdown():
            try:
                self.check()
            except Exception as err:  # noqa: BLE001 - the watch must outlive any one failure
                rospy.logdebug("master watch: %s", err)

    # --- one look --------------------------------------------------------------------------------

    def check(self) -> bool:
        """Look at the master once; True if the node was registered again."""
        master = master_proxy(self.master_uri)
        try:
            _, _, pid = master.getPid(self.caller_id)
            code, _, _ = master.lookupNode(self.caller_id, self.caller_id)
        except (OSError, xmlrpc.client.Error):
            return False   # the master is down (or busy): look again later
        if self.master_pid is None:          # the first look: the master of the start-up
            self.master_pid = pid
            self._remember(master, first=True)
            return False
        if pid == self.master_pid and code == 1:
            self._remember(master)
            return False
        self.master_pid = pid
        self.register_again(master)
        return True

    def _remember(self, master, first: bool = False) -> None:
        """Keep what is to be set again: /use_sim_time (at start) and each robot's
        description (once per namespace, when its robot is first seen)."""
        import rosgraph.names
        if first:
            code, _, value = master.getParam(self.caller_id, "/use_sim_time")
            self.use_sim_time = value if code == 1 else None
            names = {"/robot_description"}
        else:
            names = set()
        try:
            namespaces = set(self.robot_namespaces())
        except RuntimeError:   # the robots changed while being listed: next time
            namespaces = set()
        for namespace in namespaces - self._seen_namespaces:
            self._seen_namespaces.add(namespace)
            names.add(rosgraph.names.ns_join(namespace or self.namespace, "robot_description"))
        for name in names - set(self.params):
            code, _, value = master.getParam(self.caller_id, name)
            if code == 1:
                self.params[name] = value

    def register_again(self, master) -> None:
        """Parameters, services, then topics, with the master at master_uri (a new one)."""
        from rospy.impl.registration import Registration, get_service_manager, \
            get_topic_manager
        start = time.monotonic()
        params = dict(self.params)
        params["/use_sim_time"] = True if self.use_sim_time is None else self.use_sim_time
        set_count = 0
        for name, value in params.items():
            code, _, present = master.hasParam(self.caller_id, name)
            if code == 1 and not present:
                master.setParam(self.caller_id, name, value)
                set_count += 1
        registrar = rospy_registrar()
        topics, services = set(), 0
        if registrar is not None:
            tm, sm = get_topic_manager(), get_service_manager()
            for name, service_uri in sm.get_services():
                registrar.reg_added(name, service_uri, Registration.SRV)
                services += 1
            for kind, registrations in ((Registration.PUB, tm.get_publications()),
                                        (Registration.SUB, tm.get_subscriptions())):
                for name, data_type in registrations:
                    registrar.reg_added(name, data_type, kind)
                    topics.add(name)
        self.restarts += 1
        self.last_registration = time.monotonic() - start
        self._log("ROS master restarted: registered again %d topics, %d services, "
                  "%d parameters" % (len(topics), services, set_count))
