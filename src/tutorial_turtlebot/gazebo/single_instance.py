"""One simulator per ROS master: find a ``/gazebo`` that already runs, before starting another.

A second node registering as ``/gazebo`` makes the master shut the first one down, and with it
its roslaunch (the sim is ``required``) and often the master itself. So the sim, and sim.launch
while it is still parsing (through ``robot_description --new-sim``, before roslaunch sets a
parameter or starts a node), look first and refuse with one line naming what runs.
"""
import os
import socket
import sys
import urllib.parse
from typing import Optional

from ..errors import UserError

SIM_NODE = "/gazebo"
ANSWER_TIMEOUT = 2.0  # s: a registered node that does not answer within this is stale


def _no_master_listens(master_uri: Optional[str]) -> bool:
    """Whether nothing takes a connection where the master would be (``master_uri``, else a
    ``__master:=`` argument, else ROS_MASTER_URI): then no simulator runs there either. Found
    without rosgraph and XML-RPC, 40 ms of imports on the way of every sim.launch, whose
    robot_description --new-sim runs before roscore starts. False when it cannot tell."""
    remapped = [arg.split(":=", 1)[1] for arg in sys.argv if arg.startswith("__master:=")]
    uri = master_uri or (remapped[-1] if remapped else os.environ.get("ROS_MASTER_URI"))
    try:
        address = urllib.parse.urlsplit(uri or "")
        host, port = address.hostname, address.port
    except ValueError:
        return False
    if not host or not port:
        return False
    try:
        socket.create_connection((host, port), timeout=ANSWER_TIMEOUT).close()
    except OSError:
        return True
    return False


def running_simulator(node: str = SIM_NODE, master_uri: Optional[str] = None) -> Optional[str]:
    """A description ("/gazebo at URI, pid N") of the node ``node`` when it is registered with
    the master at ``master_uri`` (default: ROS_MASTER_URI) and answers; None when there is no
    master, no such node, or only a stale registration of one that is gone."""
    if _no_master_listens(master_uri):
        return None
    import xmlrpc.client   # only with a master there (_no_master_listens)
    import rosgraph
    previous = socket.getdefaulttimeout()
    socket.setdefaulttimeout(ANSWER_TIMEOUT)
    try:
        master = rosgraph.Master("/tutorial_turtlebot_sim_check", master_uri=master_uri)
        try:
            uri = master.lookupNode(node)
        except rosgraph.MasterException:
            return None  # not registered
        except (OSError, xmlrpc.client.Error):
            return None  # no master there
        try:
            code, _msg, pid = xmlrpc.client.ServerProxy(uri).getPid("/tutorial_turtlebot")
        except (OSError, xmlrpc.client.Error):
            return None  # registered, but gone
        return "%s at %s, pid %s" % (node, uri, pid) if code == 1 else "%s at %s" % (node, uri)
    finally:
        socket.setdefaulttimeout(previous)


def refuse_if_running(node: str = SIM_NODE) -> None:
    """UserError (one line) when a simulator already runs on this ROS master."""
    running = running_simulator(node)
    if running is not None:
        raise UserError(
            "a simulator is already running on this ROS master (%s, ROS_MASTER_URI=%s): it is "
            "left as it is; stop it first (Ctrl-C in its terminal), or start this one on "
            "another master (roslaunch -p 11312 ...)"
            % (running, os.environ.get("ROS_MASTER_URI", "http://localhost:11311")))
