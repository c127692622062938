"""rqt_graph's picture of a ROS 1 graph, without rqt (no rospy here).

Input: a :class:`GraphSnapshot`, the data ``rosgraph.impl.graph.Graph`` collects (what
rqt_graph reads): the nodes, the topics, the node -> node connections labelled with their
topic, the node -> topic edges of live connections ("active") and of the master's
registrations ("all"), and the nodes that did not answer. Topic vertices keep rosgraph's
convention: the topic name with a leading space (``" /cmd_vel"``), so that a topic and a node
of the same name stay apart.

Output: a :class:`View` (what is drawn: vertices, namespace boxes, edges) made with
rqt_graph's rules and defaults (doc/turtlebot3.md 8), written by graph_output as rqt_graph's
DOT text (``to_dot``; graphviz ``dot`` or ``xdot`` lay it out) or as a plain-text picture for
terminals (``to_text``).

The three modes, as rqt_graph's combo box:

- ``nodes`` (Nodes only, the default): nodes as ellipses, one edge per publisher ->
  subscriber connection, labelled with the topic;
- ``active`` (Nodes/Topics (active)): nodes and topics (boxes), edges of live connections;
- ``all`` (Nodes/Topics (all)): nodes and topics, every registration with the master.

Hidden by default: debug names (``/rosout``, ``/clock``, ``/rviz``, ...), dead sinks (topics
nobody subscribes), leaf topics (one edge), unreachable nodes, dynamic_reconfigure params.
Grouped by default: namespaces (boxes two levels deep), images, tf, actions. Dead sinks, leaf
topics, tf, params and the image/tf/action groups concern topics: the ``nodes`` mode ignores
them, as rqt_graph does.
"""
import re
from dataclasses import dataclass, field
from typing import Dict, FrozenSet, Iterable, List, NamedTuple, Optional, Sequence, Set, Tuple
from urllib.parse import quote

from ..errors import UserError

MODES = ("nodes", "active", "all")
MODE_TITLES = {"nodes": "Nodes only", "active": "Nodes/Topics (active)",
               "all": "Nodes/Topics (all)"}

HIDE_CHOICES = ("debug", "dead-sinks", "leaf-topics", "tf", "unreachable", "params")
HIDE_DEFAULT = frozenset(("debug", "dead-sinks", "leaf-topics", "unreachable", "params"))
GROUP_CHOICES = ("namespaces", "actions", "tf", "images")
GROUP_DEFAULT = frozenset(GROUP_CHOICES)
NAMESPACE_LEVEL = 2  # how many namespace levels get a box (rqt_graph's default)

OUTPUT_SUFFIXES = (".png", ".svg", ".dot")

# A node or topic whose name contains one of these is "debug" (rqt_graph's quiet names).
DEBUG_NAMES = ("/diag_agg", "/runtime_logger", "/pr2_dashboard", "/rviz", "/rosout",
               "/cpu_monitor", "/monitor", "/hd_monitor", "/rxloggerlevel", "/clock", "/rqt",
               "/statistics")
# In the nodes mode, connections over these topics are debug too.
DEBUG_EDGE_LABELS = ("/time", "/clock", "/rosout", "/statistics")

ACTION_SUFFIXES = ("/status", "/result", "/goal", "/cancel", "/feedback")
IMAGE_SUFFIXES = ("/compressed", "/compressedDepth", "/theora", "")
TF_TOPICS = ("/tf", "/tf_static")
PARAM_SUFFIXES = ("/parameter_updates", "/parameter_descriptions")

DEAD, WONKY = "DEAD", "WONKY"  # a node that does not answer; one that answered again
BAD_COLORS = {DEAD: "red", WONKY: "orange"}


class Edge(NamedTuple):
    """An edge of the snapshot, as rosgraph's Edge: names of its ends, and (node -> node
    edges only) the topic."""

    start: str
    end: str
    label: str = ""


def topic_vertex(topic: str) -> str:
    """The snapshot's vertex name of a topic (rosgraph's convention: a leading space)."""
    return " " + topic


def is_topic_vertex(name: str) -> bool:
    """True for a topic vertex (leading space), False for a node."""
    return name.startswith(" ")


@dataclass
class GraphSnapshot:
    """What rosgraph.impl.graph.Graph knows after ``update()``, as plain data.

    nn_nodes: node names. nt_nodes: topic vertices (``topic_vertex``). nn_edges: publisher
    node -> subscriber node, label = topic (from the subscribers' live connections).
    nt_edges: node -> topic (publishes) and topic -> node (subscribes) of live connections.
    nt_all_edges: the same for every registration with the master. bad_nodes: node name ->
    DEAD or WONKY.
    """

    nn_nodes: Set[str] = field(default_factory=set)
    nt_nodes: Set[str] = field(default_factory=set)
    nn_edges: List[Edge] = field(default_factory=list)
    nt_edges: List[Edge] = field(default_factory=list)
    nt_all_edges: List[Edge] = field(default_factory=list)
    bad_nodes: Dict[str, str] = field(default_factory=dict)

    @classmethod
    def from_rosgraph(cls, graph) -> "GraphSnapshot":
        """A copy of a ``rosgraph.impl.graph.Graph`` (duck-typed: no rosgraph import here)."""
        def edges(edge_list):
            return [Edge(e.start, e.end, e.label or "") for e in edge_list]
        return cls(nn_nodes=set(graph.nn_nodes), nt_nodes=set(graph.nt_nodes),
                   nn_edges=edges(graph.nn_edges), nt_edges=edges(graph.nt_edges),
                   nt_all_edges=edges(graph.nt_all_edges),
                   bad_nodes={name: DEAD if bad.type == bad.DEAD else WONKY
                              for name, bad in dict(graph.bad_nodes).items()})


@dataclass
class Options:
    """rqt_graph's settings; the defaults are those of its first start."""

    mode: str = "nodes"
    node_filter: str = "/"
    topic_filter: str = "/"
    hide: FrozenSet[str] = HIDE_DEFAULT
    group: FrozenSet[str] = GROUP_DEFAULT
    namespace_level: int = NAMESPACE_LEVEL


@dataclass
class Vertex:
    """A drawn vertex: a node (ellipse), a topic (box) or a group of topics (box3d)."""

    id: str
    label: str
    shape: str
    url: str
    color: Optional[str] = None
    cluster: Optional[str] = None  # the innermost namespace box it sits in, e.g. "/camera"
    status: Optional[str] = None   # DEAD or WONKY: a node that did not answer

    @property
    def is_node(self) -> bool:
        return self.shape == "ellipse"


class ViewEdge(NamedTuple):
    """A drawn edge between two vertex ids; label and url only in the nodes mode."""

    start: str
    end: str
    label: str = ""
    url: str = ""


@dataclass
class View:
    """What rqt_graph draws for one snapshot and one set of options."""

    mode: str
    clusters: List[str]      # namespace boxes, parents before children ("/a" then "/a/b")
    vertices: List[Vertex]
    edges: List[ViewEdge]


# ------------------------------------------------------------------------ checked user input

def check_mode(mode: str) -> str:
    """``mode`` if it is one of MODES, else UserError naming the valid ones."""
    if mode not in MODES:
        raise UserError("unknown mode %r: the modes are %s (nodes: %s; active: %s; all: %s)"
                        % (mode, ", ".join(MODES), MODE_TITLES["nodes"],
                           MODE_TITLES["active"], MODE_TITLES["all"]))
    return mode


def output_format(path: str) -> str:
    """The format of an output file from its suffix ("png", "svg" or "dot"), else UserError
    naming the valid suffixes."""
    suffix = path[path.rfind("."):].lower() if "." in path.rsplit("/", 1)[-1] else ""
    if suffix not in OUTPUT_SUFFIXES:
        raise UserError("cannot write %r: the output file must end in %s"
                        % (path, ", ".join(OUTPUT_SUFFIXES[:-1]) + " or "
                           + OUTPUT_SUFFIXES[-1]))
    return suffix[1:]


def check_choices(text: str, valid: Sequence[str], option: str) -> FrozenSet[str]:
    """A comma-separated list of ``valid`` words (or "none") as a set, else UserError."""
    words = [w.strip() for w in text.split(",") if w.strip()]
    if words == ["none"]:
        return frozenset()
    bad = [w for w in words if w not in valid]
    if bad or not words:
        raise UserError("%s: unknown item %r: use a comma-separated list of %s, or none"
                        % (option, bad[0] if bad else text, ", ".join(valid)))
    return frozenset(words)


# ------------------------------------------------------------------------ rqt_graph's rules

def _split_filter(text: str) -> Tuple[List[str], List[str]]:
    """rqt_graph's filter field: comma-separated; a leading ``-`` excludes; empty or ``/``
    includes everything."""
    includes, excludes = [], []
    for word in (w.strip() for w in text.split(",")):
        if word.startswith("-"):
            excludes.append(word[1:])
        else:
            includes.append(word)
    if includes in ([], ["/"], [""]):
        includes = [".*"]
    return includes, excludes


def _matches_any(name: str, patterns: Iterable[str]) -> bool:
    """An exact name, or a pattern that is not a plain name used as a regular expression."""
    name = name.strip()
    for pattern in patterns:
        if name == pattern:
            return True
        if not re.match(r"^[a-zA-Z0-9_/]+$", pattern):
            try:
                if re.match(pattern, name):
                    return True
            except re.error as err:
                raise UserError("bad filter pattern %r: %s" % (pattern, err)) from None
    return False


def _wanted(name: str, filters: Tuple[List[str], List[str]]) -> bool:
    includes, excludes = filters
    return _matches_any(name, includes) and not _matches_any(name, excludes)


def _not_debug(name: str) -> bool:
    return not any(debug in name for debug in DEBUG_NAMES)


def _connections(edges: Sequence[Edge]) -> Dict[str, Tuple[List[Edge], List[Edge]]]:
    """vertex -> (incoming edges, outgoing edges)."""
    result = {}  # type: Dict[str, Tuple[List[Edge], List[Edge]]]
    for edge in edges:
        result.setdefault(edge.start, ([], []))[1].append(edge)
        result.setdefault(edge.end, ([], []))[0].append(edge)
    return result


def _without(edges: List[Edge], gone: Iterable[Edge]) -> List[Edge]:
    gone = set(gone)
    return [e for e in edges if e not in gone]


def _hide_leaves(topics, edges, conns, leaf_topics: bool, dead_sinks: bool):
    """Drop leaf topics (fewer than 2 edges) and dead sinks (no outgoing edge)."""
    removed, gone = set(), []
    for topic in topics:
        if topic not in conns:
            continue
        incoming, outgoing = conns[topic]
        if (leaf_topics and len(incoming) + len(outgoing) < 2) or (dead_sinks and not outgoing):
            removed.add(topic)
            gone.extend(incoming + outgoing)
    return [t for t in topics if t not in removed], _without(edges, gone)


def _hide_tf_and_params(topics, edges, conns, hide_tf: bool, hide_params: bool):
    """Drop /tf and /tf_static; drop each X/parameter_updates + X/parameter_descriptions pair."""
    names = {t.strip(): t for t in topics}
    removed = set()
    for topic in topics:
        name = topic.strip()
        if hide_params and name.endswith(PARAM_SUFFIXES[0]):
            prefix = name[:-len(PARAM_SUFFIXES[0])]
            pair = [names.get(prefix + s) for s in PARAM_SUFFIXES]
            if all(pair):
                removed.update(pair)
        if hide_tf and name in TF_TOPICS:
            removed.add(topic)
    gone = [e for t in removed for e in sum(conns.get(t, ([], [])), [])]
    return [t for t in topics if t not in removed], _without(edges, gone)


def _member_edges(members, conns):
    """(incoming edges, outgoing edges) of a group's member topics."""
    incoming = [e for m in members for e in conns.get(m, ([], []))[0]]
    outgoing = [e for m in members for e in conns.get(m, ([], []))[1]]
    return incoming, outgoing


def _group_topics(topics, edges, conns, key_suffix: str, suffixes: Sequence[str],
                  at_least: int, group_suffix: str):
    """Topics ``P + s`` (s in ``suffixes``, at least ``at_least`` of them, ``P + key_suffix``
    among them) become one vertex ``P + group_suffix``; returns (topics, edges, groups), groups
    being group name -> (incoming edges, outgoing edges) of its members."""
    names = {t.strip(): t for t in topics}
    removed, groups = set(), {}
    for topic in topics:
        name = topic.strip()
        if not name.endswith(key_suffix) or topic in removed:
            continue
        prefix = name[:-len(key_suffix)]
        members = [names[prefix + s] for s in suffixes if prefix + s in names]
        if len(members) < at_least:
            continue
        removed.update(members)
        groups[prefix + group_suffix] = _member_edges(members, conns)
    gone = [e for (inc, out) in groups.values() for e in inc + out]
    return [t for t in topics if t not in removed], _without(edges, gone), groups


def _group_tf(topics, edges, conns):
    """/tf and /tf_static become one vertex "/tf" when they have edges."""
    members = [t for t in topics if t.strip() in TF_TOPICS and t in conns]
    incoming = [e for m in members for e in conns[m][0] if e in edges]
    outgoing = [e for m in members for e in conns[m][1] if e in edges]
    topics = [t for t in topics if t not in members]
    edges = _without(edges, incoming + outgoing)
    if not incoming and not outgoing:
        return topics, edges, None
    return topics, edges, (incoming, outgoing)


def dot_id(name: str) -> str:
    """rqt_graph's DOT id for a name: URL-quoted, ``/`` -> ``__``, ``%`` and ``-`` -> ``_``."""
    return quote(name.strip()).replace("/", "__").replace("%", "_").replace("-", "_")


def node_id(node: str) -> str:
    """The DOT id of a node or a group vertex, e.g. ``n___gazebo``."""
    return dot_id("n_" + node)


def topic_id(topic: str) -> str:
    """The DOT id of a topic, e.g. ``t___cmd_vel``."""
    return dot_id("t_" + topic)


def _vertex_id(name: str) -> str:
    return topic_id(name[1:]) if is_topic_vertex(name) else node_id(name)


def _namespace_boxes(names: Iterable[str], level: int) -> List[str]:
    """The namespace boxes for these names, parents first: a name with two slashes or more
    gets boxes for up to ``level`` leading namespaces (``/camera/rgb/image_raw`` at level 2:
    ``/camera`` and, inside it, ``/camera/rgb``)."""
    boxes = []  # type: List[str]
    for name in names:
        parts = name.strip().split("/")
        if name.count("/") > 2:
            for i in range(2, min(2 + level, len(parts))):
                box, parent = "/".join(parts[:i]), "/".join(parts[:i - 1])
                if box not in boxes and (parent == "" or parent in boxes):
                    boxes.append(box)
        elif name.count("/") == 2:
            box = "/".join(parts[:2])
            if box not in boxes:
                boxes.append(box)
    return boxes


def _box_of(name: str, level: int) -> Optional[str]:
    """The innermost namespace box a vertex sits in (None: outside every box)."""
    name = name.strip()
    parts = name.split("/")
    if level <= 0 or name.count("/") <= 1 or not parts[1]:
        return None
    if name.count("/") <= level:
        return "/".join(parts[:-1])
    return "/".join(parts[:level + 1])


def _selected(snapshot: GraphSnapshot, mode: str, options: Options):
    """The mode's nodes, topics and edges that pass the node and topic filters (the nodes mode
    has no topic vertex: its filter applies to the edges' labels)."""
    node_filter = _split_filter(options.node_filter)
    topic_filter = _split_filter(options.topic_filter)
    nodes = [n for n in sorted(snapshot.nn_nodes) if _wanted(n, node_filter)]
    if mode == "nodes":
        topics = []  # type: List[str]
        edges = [e for e in snapshot.nn_edges if _wanted(e.label, topic_filter)]
    else:
        topics = [t for t in sorted(snapshot.nt_nodes) if _wanted(t, topic_filter)]
        edges = list(snapshot.nt_edges if mode == "active" else snapshot.nt_all_edges)
    return nodes, topics, sorted(set(edges))


def _hide_debug_and_unreachable(snapshot: GraphSnapshot, mode: str, hide: FrozenSet[str],
                                nodes, topics, edges):
    """Drop debug nodes and topics (and, in the nodes mode, debug edges); drop unreachable
    nodes."""
    if "debug" in hide:
        nodes = [n for n in nodes if _not_debug(n)]
        topics = [t for t in topics if _not_debug(t)]
        if mode == "nodes":
            edges = [e for e in edges if e.label not in DEBUG_EDGE_LABELS
                     and _not_debug(e.start) and _not_debug(e.end)]
    if "unreachable" in hide:  # rqt_graph leaves their edges; here they go with the node
        nodes = [n for n in nodes if n not in snapshot.bad_nodes]
    return nodes, topics, edges


def _hide_and_group_topics(topics, edges, hide: FrozenSet[str], group: FrozenSet[str]):
    """The topic modes' rules: hide leaves, dead sinks, tf and params, then group actions,
    images and tf; returns (topics, edges, groups), groups as (group name, incoming edges,
    outgoing edges, namespace box allowed)."""
    groups = []
    conns = _connections(edges)
    topics, edges = _hide_leaves(topics, edges, conns, "leaf-topics" in hide,
                                 "dead-sinks" in hide)
    topics, edges = _hide_tf_and_params(topics, edges, conns, "tf" in hide, "params" in hide)
    if "actions" in group:
        topics, edges, actions = _group_topics(topics, edges, conns, "/feedback",
                                               ACTION_SUFFIXES, 5, "/action_topics")
        groups += [(name, inc, out, True) for name, (inc, out) in actions.items()]
    if "images" in group:
        topics, edges, images = _group_topics(topics, edges, conns, "/compressed",
                                              IMAGE_SUFFIXES, 3, "/image_topics")
        groups += [(name, inc, out, True) for name, (inc, out) in images.items()]
    if "tf" in group and "tf" not in hide:
        topics, edges, tf = _group_tf(topics, edges, conns)
        if tf is not None:
            groups.append(("/tf", tf[0], tf[1], False))
    return topics, edges, groups


def _drop_unlinked(nodes, topics, edges):
    """Edges whose ends are both still drawn, and the topics left with an edge."""
    present = set(nodes) | set(topics)
    edges = [e for e in edges if e.start in present and e.end in present]
    linked = {e.start for e in edges} | {e.end for e in edges}
    return [t for t in topics if t in linked], edges


def _clusters(nodes, topics, groups, level: int) -> List[str]:
    """The namespace boxes of the drawn topics, boxable groups and nodes (none at level 0)."""
    names = [t.strip() for t in topics] + [g[0] for g in groups if g[3]] + nodes
    return _namespace_boxes(names, level) if level > 0 else []


def _vertices(snapshot: GraphSnapshot, nodes, topics, groups, level: int) -> List[Vertex]:
    """The drawn vertices: topics, then topic groups, then nodes, each in its namespace box."""
    vertices = []
    for topic in topics:
        name = topic.strip()
        vertices.append(Vertex(topic_id(name), name, "box", "topic:" + name,
                               cluster=_box_of(name, level)))
    for name, _, _, boxed in groups:
        vertices.append(Vertex(node_id(name), name, "box3d", "topic:" + name,
                               cluster=_box_of(name, level) if boxed else None))
    for node in nodes:
        bad = snapshot.bad_nodes.get(node)
        vertices.append(Vertex(node_id(node), node, "ellipse",
                               node + (" (%s)" % bad if bad else ""),
                               color=BAD_COLORS.get(bad), cluster=_box_of(node, level),
                               status=bad))
    return vertices


def _view_edges(mode: str, nodes, edges, groups) -> List[ViewEdge]:
    """The drawn edges: labelled node -> node in the nodes mode, else between nodes and
    topics; then each group's edges to and from the drawn nodes, once each."""
    if mode == "nodes":
        view_edges = [ViewEdge(node_id(e.start), node_id(e.end), e.label, "topic:" + e.label)
                      for e in edges]
    else:
        view_edges = [ViewEdge(_vertex_id(e.start), _vertex_id(e.end)) for e in edges]
    for name, incoming, outgoing, _ in groups:
        group_edges = ([ViewEdge(node_id(e.start), node_id(name))
                        for e in incoming if e.start in nodes]
                       + [ViewEdge(node_id(name), node_id(e.end))
                          for e in outgoing if e.end in nodes])
        view_edges += [e for i, e in enumerate(group_edges) if e not in group_edges[:i]]
    return view_edges


def build_view(snapshot: GraphSnapshot, options: Optional[Options] = None) -> View:
    """What rqt_graph draws for ``snapshot`` with ``options`` (default: rqt_graph's)."""
    options = options or Options()
    mode = check_mode(options.mode)
    hide, group = options.hide, options.group
    nodes, topics, edges = _selected(snapshot, mode, options)
    nodes, topics, edges = _hide_debug_and_unreachable(snapshot, mode, hide, nodes, topics,
                                                       edges)
    groups = []  # (group name, incoming edges, outgoing edges, namespace box allowed)
    if mode != "nodes":
        topics, edges, groups = _hide_and_group_topics(topics, edges, hide, group)
    topics, edges = _drop_unlinked(nodes, topics, edges)

    level = options.namespace_level if "namespaces" in group else 0
    return View(mode, _clusters(nodes, topics, groups, level),
                _vertices(snapshot, nodes, topics, groups, level),
                _view_edges(mode, nodes, edges, groups))
