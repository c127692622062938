"""``graph``: the ROS graph as rqt_graph draws it, for machines without rqt (Debian 12).

Usage::

    rosrun tutorial_turtlebot graph                       # a live window (xdot), or text
    rosrun tutorial_turtlebot graph --mode active         # nodes and topics
    rosrun tutorial_turtlebot graph --output graph.png    # or .svg, .dot
    rosrun tutorial_turtlebot graph --text                # the picture as text

It asks the master and every node what rqt_graph asks (rosgraph.impl.graph, each node given
rosgraph's 1 s to answer) and draws rqt_graph's picture with its defaults: nodes only,
debug names (/rosout, /clock, ...), dead sinks, leaf topics, unreachable nodes and params
hidden, namespaces, images, tf and actions grouped (see tutorial_turtlebot.lab.ros_graph).

Where it goes:
    --output FILE: FILE.dot is the DOT text; FILE.png and FILE.svg are laid out by graphviz's
        ``dot``. Then it exits.
    otherwise, with a display: an ``xdot`` window on a DOT file that this command rewrites when
        the graph changes (every --interval s); xdot reloads it. Closing the window or Ctrl-C
        ends it. (rqt_graph itself redraws only when Refresh is pressed.)
    otherwise (no display, or --text): the text picture on stdout, one line per connection.

It is not a ROS node (it registers nothing, so it does not draw itself). No master, a bad
option or an unwritable file: one line on stderr and a non-zero exit status.
"""
import argparse
import contextlib
import io
import logging
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from typing import Optional

import rosgraph
import rosgraph.impl.graph

from ..errors import UserError
from . import graph_output
from . import ros_graph

PROG = "graph"
MASTER_TIMEOUT = 5.0    # s: socket timeout for the master (a node gets rosgraph's 1 s)
STALE = 5.0             # s: rqt_graph's set_master_stale / set_node_stale
INTERVAL = 2.0          # s: default time between two looks at the graph in the live window
POLL = 0.1              # s: how often the live loop checks that the window is still open


class NoMaster(UserError):
    """The ROS master does not answer (exit status 1; bad input is 2)."""


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        """One line instead of argparse's usage block."""
        raise UserError("%s (see %s --help)" % (message, PROG))


def parse_args(argv):
    """The command line (without the program name) as checked options; UserError if bad."""
    parser = _Parser(prog=PROG, description="Draw the ROS graph as rqt_graph does.")
    parser.add_argument("--mode", default="nodes",
                        help="nodes (Nodes only, the default), active (Nodes/Topics (active)) "
                             "or all (Nodes/Topics (all))")
    parser.add_argument("--output", "-o", metavar="FILE",
                        help="write FILE.png, FILE.svg or FILE.dot and exit")
    parser.add_argument("--text", action="store_true",
                        help="print the text picture even where there is a display")
    parser.add_argument("--hide", default=",".join(c for c in ros_graph.HIDE_CHOICES
                                                   if c in ros_graph.HIDE_DEFAULT),
                        help="what to hide, comma-separated, from %s; or none (default: %%("
                             "default)s)" % ", ".join(ros_graph.HIDE_CHOICES))
    parser.add_argument("--group", default=",".join(ros_graph.GROUP_CHOICES),
                        help="what to group, comma-separated, from %s; or none (default: "
                             "%%(default)s)" % ", ".join(ros_graph.GROUP_CHOICES))
    parser.add_argument("--ns-level", type=int, default=ros_graph.NAMESPACE_LEVEL,
                        metavar="N", help="namespace levels that get a box (default: "
                                          "%(default)s)")
    parser.add_argument("--nodes", default="/", metavar="FILTER",
                        help="rqt_graph's node filter: names or regular expressions, "
                             "comma-separated; -NAME excludes (write --nodes=-/rosout); "
                             "default: /, every node")
    parser.add_argument("--topics", default="/", metavar="FILTER",
                        help="the same for topics (default: /)")
    parser.add_argument("--interval", type=float, default=INTERVAL, metavar="S",
                        help="seconds between two looks at the graph in the live window "
                             "(default: %(default)s)")
    args = parser.parse_args(argv)
    ros_graph.check_mode(args.mode)
    if args.output is not None:
        ros_graph.output_format(args.output)
    if args.ns_level < 0:
        raise UserError("--ns-level must be 0 or more, got %d" % args.ns_level)
    if not args.interval > 0:
        raise UserError("--interval must be a positive number of seconds, got %g"
                        % args.interval)
    args.options = ros_graph.Options(
        mode=args.mode, node_filter=args.nodes, topic_filter=args.topics,
        hide=ros_graph.check_choices(args.hide, ros_graph.HIDE_CHOICES, "--hide"),
        group=ros_graph.check_choices(args.group, ros_graph.GROUP_CHOICES, "--group"),
        namespace_level=args.ns_level)
    return args


def _master_uri() -> str:
    try:
        return rosgraph.get_master_uri()
    except Exception as err:  # rosgraph.ROSEnvException and the like
        raise UserError("no ROS master URI: %s" % err) from None


def check_master() -> None:
    """UserError unless the master answers."""
    uri = _master_uri()
    try:
        rosgraph.Master("/rosgraph_picture", master_uri=uri).getSystemState()
    except ValueError as err:
        raise UserError("bad ROS_MASTER_URI %r: %s" % (uri, err)) from None
    except (OSError, rosgraph.MasterException) as err:
        raise NoMaster("cannot reach the ROS master at %s (%s): start one with roscore or "
                       "roslaunch, or set ROS_MASTER_URI" % (uri, err)) from None


def snapshot() -> ros_graph.GraphSnapshot:
    """The graph now, as rqt_graph fetches it when it opens or on Refresh (a new
    rosgraph.impl.graph.Graph each time); UserError if the master does not answer."""
    socket.setdefaulttimeout(MASTER_TIMEOUT)
    check_master()
    graph = rosgraph.impl.graph.Graph()
    graph.set_master_stale(STALE)
    graph.set_node_stale(STALE)
    with contextlib.redirect_stderr(io.StringIO()):  # its print when the master just went
        graph.update()
    return ros_graph.GraphSnapshot.from_rosgraph(graph)


def write_output(path: str, dot: str) -> None:
    """``dot`` into ``path``: as it is for .dot, laid out by graphviz for .png and .svg."""
    fmt = ros_graph.output_format(path)
    if fmt == "dot":
        try:
            with open(path, "w") as out:
                out.write(dot)
        except OSError as err:
            raise UserError("cannot write %s: %s" % (path, err.strerror or err)) from None
        return
    program = shutil.which("dot")
    if program is None:
        raise UserError("writing .%s needs graphviz's dot, which is not installed "
                        "(apt-get install graphviz); .dot files need nothing" % fmt)
    done = subprocess.run([program, "-T" + fmt, "-o", path], input=dot.encode(),
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    if done.returncode != 0:
        lines = done.stderr.decode("utf-8", "replace").strip().splitlines()
        raise UserError("dot could not write %s: %s" % (path, lines[-1] if lines
                                                        else "exit status %d"
                                                        % done.returncode))


def _replace(path: str, text: str) -> None:
    """Write ``text`` to ``path`` in one step (xdot never reads half a file)."""
    partial = path + ".partial"
    with open(path + ".partial", "w") as out:
        out.write(text)
    os.replace(partial, path)


def live_window(options: ros_graph.Options, interval: float, first: str) -> int:
    """An xdot window on a DOT file kept up to date; returns when the window is closed."""
    folder = tempfile.mkdtemp(prefix="ros_graph_")
    path = os.path.join(folder, "ros_graph.dot")
    window: Optional[subprocess.Popen] = None
    try:
        _replace(path, first)
        window = subprocess.Popen(["xdot", path], stdin=subprocess.DEVNULL)
        print("%s: showing the graph in an xdot window, updated every %g s; close the "
              "window or press Ctrl-C to end" % (PROG, interval), flush=True)
        shown, lost = first, False
        while window.poll() is None:
            deadline = time.monotonic() + interval
            while window.poll() is None and time.monotonic() < deadline:
                time.sleep(POLL)
            if window.poll() is not None:
                break
            try:
                dot = graph_output.to_dot(ros_graph.build_view(snapshot(), options))
            except UserError as err:
                if not lost:
                    sys.stderr.write("%s: %s; showing the last graph until it is back\n"
                                     % (PROG, err))
                lost = True
                continue
            if lost:
                sys.stderr.write("%s: the master is back\n" % PROG)
                lost = False
            if dot != shown:
                _replace(path, dot)
                shown = dot
        return 0
    except KeyboardInterrupt:
        return 0
    finally:
        if window is not None and window.poll() is None:
            window.terminate()
            try:
                window.wait(5.0)
            except subprocess.TimeoutExpired:
                window.kill()
        shutil.rmtree(folder, ignore_errors=True)


def _on_sigterm(signum, frame):
    raise KeyboardInterrupt


def run(argv) -> int:
    """The command; UserError for bad input. Returns the exit status."""
    args = parse_args(argv)
    snap = snapshot()
    view = ros_graph.build_view(snap, args.options)
    if args.output is not None:
        write_output(args.output, graph_output.to_dot(view))
        print("%s: wrote %s (%s)" % (PROG, args.output,
                                     graph_output.to_text(view).splitlines()[0]))
        return 0
    has_display = bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))
    if has_display and not args.text:
        if shutil.which("xdot") is not None:
            signal.signal(signal.SIGTERM, _on_sigterm)
            return live_window(args.options, args.interval, graph_output.to_dot(view))
        sys.stderr.write("%s: no xdot for a window (apt-get install xdot); the graph as "
                         "text:\n" % PROG)
    sys.stdout.write(graph_output.to_text(view))
    return 0


def main(argv=None) -> None:
    """Entry point of scripts/graph."""
    argv = sys.argv[1:] if argv is None else argv
    # rosgraph logs a traceback for each node that does not answer: the picture says it
    logging.getLogger("rosgraph.graph").addHandler(logging.NullHandler())
    logging.getLogger("rosgraph.graph").propagate = False
    try:
        status = run(argv)
    except UserError as err:
        sys.stderr.write("%s: error: %s\n" % (PROG, err))
        status = 1 if isinstance(err, NoMaster) else 2
    except KeyboardInterrupt:
        status = 130
    sys.exit(status)
