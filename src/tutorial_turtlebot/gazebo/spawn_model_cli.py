"""``spawn_model``: gazebo_ros's spawn_model script, a client of the sim's /gazebo services.

Usage (gazebo_ros's command line, so launch files written for Gazebo run unchanged)::

    rosrun tutorial_turtlebot spawn_model -sdf -file box.sdf -model box -x 1 -y 0.5 -z 0.1
    rosrun tutorial_turtlebot spawn_model -urdf -param robot_description -model r2 -Y 1.57
    rosrun tutorial_turtlebot spawn_model -sdf -stdin -model crate < crate.sdf

Required: ``-urdf`` or ``-sdf``; the XML from ``-file FILE``, ``-param PARAM`` (a relative name
resolves in the node's namespace, as rospy resolves it) or ``-stdin``; ``-model NAME``.
Optional:
    -x -y -z X (m), -R -P -Y ANGLE (rad, roll pitch yaw; default 0): the initial pose.
    -reference_frame NAME: the model or ``model::link`` the pose is relative to ("" = world).
    -gazebo_namespace NS (default /gazebo): where the world services are.
    -robot_namespace NS (default: this node's namespace, ``/`` at the root, ``/tb3_0/`` inside
        ``<group ns="tb3_0">`` or with ROS_NAMESPACE=tb3_0): the ROS namespace of the robot's
        plugins (its topics and frames).
    -unpause: call unpause_physics after the spawn.
    -wait MODEL: first wait until MODEL is listed in model_states (published while physics runs).
    -J JOINT POSITION (repeatable): after the spawn, ``<gazebo_namespace>/set_model_configuration``
        puts these joints there (rad or m; urdf_param_name is the -param name, as gazebo_ros
        sends it). gazebo_ros first sleeps 1 s against a race with its spawn queue; here the
        model exists once the spawn has answered, so there is no sleep.
    -package_to_model: accepted (gazebo_ros rewrites mesh package:// URIs for Gazebo's model
        path; meaningless here).
    -b: bond: stay until Ctrl-C (SIGINT) or SIGTERM, then delete the model.
    -database NAME: refused (there is no Gazebo model database here; use -file).
roslaunch's ``__name:=`` and ``__log:=`` and any ``from:=to`` remapping are not options.

In order: the file or stdin is read and its XML checked before any contact with ROS; the node
``spawn_model`` (anonymous) starts; ``-param`` is read and checked; ``-wait``; it waits for
``<gazebo_namespace>/spawn_{urdf,sdf}_model`` (a line every few seconds while it waits), calls
it, logs the status; ``-J`` (set_model_configuration, its status logged); ``-unpause``; ``-b``.
Every wait is on the wall clock (the sim may be paused) and ends at Ctrl-C.

Exit status: 0 spawned (with -b: spawned, and deleted at the end); 1 the spawn, a step before
it or -J failed (one line says why: the service's status_message, a missing file, bad XML, ...;
a model whose -J failed stays spawned);
2 a bad command line (one line: what is wrong, then the usage). gazebo_ros's script exits 2 on
a bad command line too (argparse), 1 when the spawn fails.
"""
import argparse
import math
import os
import signal
import sys
import threading
import time
from typing import List, Optional

import rosgraph
import rospy
from geometry_msgs.msg import Point, Pose, Quaternion
from std_srvs.srv import Empty

from ..errors import UserError
from ..node_output import line_buffered
from ..sim.files import xml_reader
from ..sim.kinematics import quat_from_rpy as quaternion_from_rpy  # noqa: F401 - its -R -P -Y

PROG = "spawn_model"
USAGE = ("spawn_model -urdf|-sdf -file FILE|-param PARAM|-stdin -model NAME [options] "
         "(spawn_model -h lists them)")
EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2
WAIT_REPORT = 5.0   # wall s between two "still waiting" lines
POLL = 0.1          # wall s between two looks at what is awaited
DELETE_WAIT = 5.0   # wall s that -b waits for delete_model at the end (the sim may be gone)


class UsageError(UserError):
    """A bad command line (exit status 2)."""


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        """One line instead of argparse's usage block and exit status 2."""
        raise UsageError(message)


def _finite(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError("must be a number, got %r" % text) from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError("must be a finite number, got %r" % text)
    return value


def parse_args(args: List[str], default_robot_namespace: str = "/") -> argparse.Namespace:
    """gazebo_ros spawn_model's command line (``args`` without the program name and without
    roslaunch's ``__name:=`` style arguments) as checked options: ``urdf``/``sdf``,
    ``file``/``param``/``stdin``, ``model``, ``x`` ... ``Y``, ``reference_frame``,
    ``gazebo_namespace``, ``robot_namespace``, ``unpause``, ``wait``, ``joints`` (a list of
    (name, float) pairs), ``package_to_model``, ``bond``. UsageError for a bad command line;
    UserError for ``-database`` (not available here)."""
    parser = _Parser(prog=PROG, description="Spawn a model in the simulator through the "
                                            "/gazebo services (gazebo_ros's spawn_model).")
    kind = parser.add_mutually_exclusive_group(required=True)
    kind.add_argument("-urdf", action="store_true", help="the XML is a URDF (<robot>)")
    kind.add_argument("-sdf", action="store_true", help="the XML is an SDF (<sdf>)")
    source = parser.add_mutually_exclusive_group(required=True)
    source.add_argument("-file", metavar="FILE", help="read the XML from FILE")
    source.add_argument("-param", metavar="PARAM", help="read the XML from ROS parameter PARAM")
    source.add_argument("-database", metavar="MODEL",
                        help="not available: there is no Gazebo model database here")
    source.add_argument("-stdin", action="store_true", help="read the XML from standard input")
    parser.add_argument("-model", required=True, metavar="NAME",
                        help="the model's name in the world")
    parser.add_argument("-reference_frame", default="", metavar="FRAME",
                        help="model or model::link the pose is relative to (default: world)")
    parser.add_argument("-gazebo_namespace", default="/gazebo", metavar="NS",
                        help="namespace of the world services (default: /gazebo)")
    parser.add_argument("-robot_namespace", default=default_robot_namespace, metavar="NS",
                        help="ROS namespace of the robot's plugins (default: this node's "
                             "namespace, %s)" % default_robot_namespace)
    parser.add_argument("-unpause", action="store_true",
                        help="unpause physics after the spawn")
    parser.add_argument("-wait", metavar="MODEL",
                        help="first wait until MODEL is in model_states")
    for name, what in (("x", "x (m)"), ("y", "y (m)"), ("z", "z (m)"), ("R", "roll (rad)"),
                       ("P", "pitch (rad)"), ("Y", "yaw (rad)")):
        parser.add_argument("-" + name, type=_finite, default=0.0,
                            help="initial %s, default 0" % what)
    parser.add_argument("-J", dest="joints", default=[], action="append", nargs=2,
                        metavar=("JOINT", "POSITION"),
                        help="a joint's initial position (rad or m), set after the spawn "
                             "with set_model_configuration")
    parser.add_argument("-package_to_model", action="store_true",
                        help="accepted for gazebo_ros's sake (meaningless here)")
    parser.add_argument("-b", dest="bond", action="store_true",
                        help="stay until Ctrl-C, then delete the model")
    parsed = parser.parse_args(args)
    joints = []
    for joint, position in parsed.joints:
        try:
            joints.append((joint, _finite(position)))
        except argparse.ArgumentTypeError as err:
            raise UsageError("argument -J: position of joint %r %s" % (joint, err)) from None
    parsed.joints = joints
    if not parsed.model:
        raise UsageError("argument -model: the model name must not be empty")
    if parsed.database is not None:
        raise UserError("-database %s: not supported here: there is no Gazebo model database; "
                        "use -file with the model's SDF file" % parsed.database)
    return parsed


def check_xml(text: str, where: str) -> str:
    """``text`` if it is well-formed XML, else UserError naming ``where`` it came from."""
    if not text.strip():
        raise UserError("%s is empty: no model XML" % where)
    xml_reader.parse(text, where)   # UserError in xml_reader's one-line form
    return text


def read_file(path: str) -> str:
    """The model XML of ``path``, checked; UserError if it cannot be read or is not XML."""
    try:
        with open(path, encoding="utf-8") as f:
            text = f.read()
    except FileNotFoundError:
        raise UserError("specified file %s does not exist" % path) from None
    except IsADirectoryError:
        raise UserError("specified file %s is not a file" % path) from None
    except (OSError, UnicodeDecodeError) as err:
        raise UserError("cannot read %s: %s" % (path, err)) from None
    return check_xml(text, "file %s" % path)


def read_stream(stream, where: str = "stdin") -> str:
    """The model XML read from ``stream`` to its end, checked."""
    try:
        text = stream.read()
    except (OSError, UnicodeDecodeError) as err:
        raise UserError("cannot read %s: %s" % (where, err)) from None
    return check_xml(text, where)


def param_xml(value, name: str, resolved: str) -> str:
    """The model XML of parameter ``name`` (``resolved``: its full name), given its ``value``
    (None if it is not set), checked."""
    if value is None:
        raise UserError("parameter %s (%s) does not exist" % (name, resolved))
    if not isinstance(value, str):
        raise UserError("parameter %s (%s) is a %s, not model XML"
                        % (name, resolved, type(value).__name__))
    return check_xml(value, "parameter %s" % resolved)


def service_name(gazebo_namespace: str, service: str) -> str:
    """``/gazebo`` + ``spawn_sdf_model`` -> ``/gazebo/spawn_sdf_model`` (a trailing slash
    or none)."""
    return gazebo_namespace.rstrip("/") + "/" + service


def pre_ros(argv: List[str], default_robot_namespace: str, stdin=None):
    """What is done before any contact with ROS: the options (``argv`` as rospy.myargv leaves
    it, program name first) and, for -file and -stdin, the checked XML (None for -param)."""
    args = parse_args(argv[1:], default_robot_namespace)
    if args.file is not None:
        return args, read_file(args.file)
    if args.stdin:
        return args, read_stream(sys.stdin if stdin is None else stdin)
    return args, None


class Interrupted(Exception):
    """Ctrl-C or SIGTERM came while waiting."""


class Spawner:
    """The ROS side: waits, service calls and the bond. Runs after rospy.init_node.
    (gazebo_msgs is imported where it is used: the unit tests import this module where only
    ROS's own message packages exist.)"""

    def __init__(self, args: argparse.Namespace, model_xml: Optional[str]):
        self.args = args
        self.model_xml = model_xml
        self.stop = threading.Event()  # set by SIGINT / SIGTERM
        self.in_init = False           # inside rospy.init_node

    def on_signal(self, _signum, _frame) -> None:
        """Ctrl-C, SIGTERM: the waits end (-b deletes the model first). Inside
        rospy.init_node (the master went away just then) nothing is spawned or registered
        yet, and rospy's shutdown from a handler can deadlock with its registration: exit."""
        self.stop.set()
        if self.in_init:
            sys.stdout.flush()
            sys.stderr.write("%s: interrupted while registering with the ROS master at %s: "
                             "model %s not spawned\n"
                             % (PROG, rosgraph.get_master_uri(), self.args.model))
            sys.stderr.flush()
            os._exit(EXIT_FAILED)

    def wait_for_master(self) -> bool:
        """Wait (wall clock) until the ROS master answers, with a line every WAIT_REPORT s;
        False at Ctrl-C."""
        uri = rosgraph.get_master_uri()
        start = time.monotonic()
        next_report = start
        while not rosgraph.is_master_online(uri):
            if time.monotonic() >= next_report:
                next_report += WAIT_REPORT
                sys.stderr.write("%s: waiting for the ROS master at %s (%.0f s): start it with "
                                 "roscore or roslaunch, or set ROS_MASTER_URI\n"
                                 % (PROG, uri, time.monotonic() - start))
            if self.stop.wait(0.5):
                return False
        return True

    def wait_until(self, ready, what: str, hint: str = "") -> None:
        """Poll ``ready()`` on the wall clock until true; a line every WAIT_REPORT s; raises
        Interrupted at Ctrl-C."""
        start = time.monotonic()
        next_report = start + WAIT_REPORT
        while not ready():
            if self.stop.wait(POLL) or rospy.is_shutdown():
                raise Interrupted()
            if time.monotonic() >= next_report:
                next_report += WAIT_REPORT
                rospy.loginfo("Still waiting for %s (%.0f s)%s"
                              % (what, time.monotonic() - start, hint))

    def wait_for_service(self, name: str) -> None:
        def exists() -> bool:
            try:
                rospy.wait_for_service(name, timeout=POLL)
            except rospy.ROSException:
                return False
            return True
        if not exists():
            rospy.loginfo("Waiting for service %s" % name)
            self.wait_until(exists, "service %s" % name,
                            ": is the simulator running? (roslaunch tutorial_turtlebot "
                            "sim.launch)")

    def load_param(self) -> str:
        name = self.args.param
        rospy.loginfo("Loading model XML from ros parameter %s" % name)
        resolved = rospy.resolve_name(name)
        return param_xml(rospy.get_param(name, None), name, resolved)

    def wait_for_model(self, model: str) -> None:
        from gazebo_msgs.msg import ModelStates
        topic = service_name(self.args.gazebo_namespace, "model_states")
        seen = threading.Event()

        def on_states(msg) -> None:
            if model in msg.name:
                seen.set()
        sub = rospy.Subscriber(topic, ModelStates, on_states, queue_size=1)
        rospy.loginfo("Waiting for model %s before proceeding." % model)
        try:
            self.wait_until(seen.is_set, "model %s in %s" % (model, topic),
                            " (it is published while the physics runs)")
        finally:
            sub.unregister()

    def spawn(self) -> None:
        """Call the spawn service; UserError with its status if it fails."""
        from gazebo_msgs.srv import SpawnModel
        args = self.args
        kind = "urdf" if args.urdf else "sdf"
        name = service_name(args.gazebo_namespace, "spawn_%s_model" % kind)
        self.wait_for_service(name)
        pose = Pose(position=Point(args.x, args.y, args.z),
                    orientation=Quaternion(*quaternion_from_rpy(args.R, args.P, args.Y)))
        rospy.loginfo("Calling service %s" % name)
        rospy.loginfo("model %s at x %g y %g z %g roll %g pitch %g yaw %g in %s, robot "
                      "namespace %s" % (args.model, args.x, args.y, args.z, args.R, args.P,
                                        args.Y, args.reference_frame or "world",
                                        args.robot_namespace))
        try:
            resp = rospy.ServiceProxy(name, SpawnModel)(
                model_name=args.model, model_xml=self.model_xml,
                robot_namespace=args.robot_namespace, initial_pose=pose,
                reference_frame=args.reference_frame)
        except (rospy.ServiceException, rospy.ROSException) as err:
            raise UserError("Service call %s failed: %s" % (name, err)) from None
        if not resp.success:
            raise UserError("Spawn failed: %s" % resp.status_message)
        rospy.loginfo("Spawn status: %s" % resp.status_message)

    def set_joints(self) -> None:
        """-J: set_model_configuration of the spawned model; UserError if it fails."""
        from gazebo_msgs.srv import SetModelConfiguration
        args = self.args
        name = service_name(args.gazebo_namespace, "set_model_configuration")
        self.wait_for_service(name)
        rospy.loginfo("Setting joints of %s: %s" % (args.model, ", ".join(
            "%s %g" % joint for joint in args.joints)))
        try:
            resp = rospy.ServiceProxy(name, SetModelConfiguration)(
                model_name=args.model, urdf_param_name=args.param or "",
                joint_names=[joint for joint, _ in args.joints],
                joint_positions=[position for _, position in args.joints])
        except (rospy.ServiceException, rospy.ROSException) as err:
            raise UserError("Service call %s failed: %s" % (name, err)) from None
        if not resp.success:
            raise UserError("Set model configuration failed: %s" % resp.status_message)
        rospy.loginfo("Set model configuration status: %s" % resp.status_message)

    def unpause(self) -> None:
        name = service_name(self.args.gazebo_namespace, "unpause_physics")
        rospy.loginfo("Unpausing physics")
        self.wait_for_service(name)
        try:
            rospy.ServiceProxy(name, Empty)()
        except (rospy.ServiceException, rospy.ROSException) as err:
            raise UserError("Unpause physics service call failed: %s" % err) from None

    def bond(self) -> None:
        """Wait for Ctrl-C or SIGTERM, then delete the model."""
        from gazebo_msgs.srv import DeleteModel
        model = self.args.model
        rospy.loginfo("Waiting for shutdown to delete model %s" % model)
        while not self.stop.wait(0.5) and not rospy.is_shutdown():
            pass
        rospy.loginfo("Deleting model %s" % model)
        name = service_name(self.args.gazebo_namespace, "delete_model")
        try:
            rospy.wait_for_service(name, timeout=DELETE_WAIT)
            resp = rospy.ServiceProxy(name, DeleteModel)(model_name=model)
        except (rospy.ServiceException, rospy.ROSException) as err:
            rospy.logwarn("Delete model service call failed: %s" % err)
            return
        if not resp.success:
            rospy.logwarn("Delete model %s: %s" % (model, resp.status_message))

    def run(self) -> int:
        """Everything after rospy.init_node; the exit status."""
        args = self.args
        try:
            self._spawn_steps()
        except Interrupted:
            rospy.logerr("Interrupted: model %s not spawned" % args.model)
            return EXIT_FAILED
        except UserError as err:
            rospy.logerr(str(err))
            return EXIT_FAILED
        except OSError as err:  # the master went away (connection refused, ...)
            rospy.logerr("cannot reach the ROS master at %s: %s"
                         % (rosgraph.get_master_uri(), err))
            return EXIT_FAILED
        if args.bond:
            self.bond()
        return EXIT_OK

    def _spawn_steps(self) -> None:
        """The model's text, the wait for -wait's model, the spawn, then -J's joints and
        -unpause (each raises Interrupted, UserError or OSError to run)."""
        args = self.args
        if args.file is not None:
            rospy.loginfo("Loading model XML from file %s" % args.file)
        elif args.stdin:
            rospy.loginfo("Loading model XML from stdin")
        else:
            self.model_xml = self.load_param()
        if args.wait:
            self.wait_for_model(args.wait)
        self.spawn()
        if args.joints:
            self.set_joints()
        if args.unpause:
            self.unpause()


def main(argv: Optional[List[str]] = None) -> None:
    """Entry point of scripts/spawn_model."""
    line_buffered()
    argv = rospy.myargv(sys.argv if argv is None else argv)
    try:
        args, model_xml = pre_ros(argv, rospy.get_namespace())
    except UsageError as err:
        sys.stderr.write("%s: error: %s; usage: %s\n" % (PROG, err, USAGE))
        sys.exit(EXIT_USAGE)
    except UserError as err:
        sys.stderr.write("%s: error: %s\n" % (PROG, err))
        sys.exit(EXIT_FAILED)
    spawner = Spawner(args, model_xml)
    signal.signal(signal.SIGINT, spawner.on_signal)
    signal.signal(signal.SIGTERM, spawner.on_signal)
    if not spawner.wait_for_master():
        sys.stderr.write("%s: interrupted while waiting for the ROS master: model %s not "
                         "spawned\n" % (PROG, args.model))
        sys.exit(EXIT_FAILED)
    spawner.in_init = True
    rospy.init_node(PROG, anonymous=True, disable_signals=True)
    spawner.in_init = False
    status = spawner.run()
    rospy.signal_shutdown("done")
    sys.exit(status)
