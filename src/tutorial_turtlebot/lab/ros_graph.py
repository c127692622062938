"""rqt_graph's picture of a ROS 1 graph, without rqt (no rospy here).

Input: a :class:`GraphSnapshot`, the data ``rosgraph.impl.graph.Graph`` collects (what
rqt_graph reads): the nodes, the topics, the node -> node connections labelled with their
topic, the node -> topic edges of live connections ("active") and of the master's
registrations ("all"), and the nodes that did not answer. Topic vertices keep rosgraph's
convention: the topic name with a leading space (``" /cmd_vel"``), so that a topic and a node
of the same name stay apart.

Output: a :class:`View` (what is drawn: vertices, namespace boxes, edges) made with
rqt_graph's rules and defaults (doc/turtlebot3.md 8), written as rqt_graph's DOT text
(:func:`to_dot`; graphviz ``dot`` or ``xdot`` lay it out) or as a plain-text picture for
terminals (:func:`to_text`).

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

FONT_NAME = "sans"  # rqt_graph draws its labels in Qt's "sans", 11 px
FONT_SIZE = 11

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
        incoming = [e for m in members for e in conns.get(m, ([], []))[0]]
        outgoing = [e for m in members for e in conns.get(m, ([], []))[1]]
        groups[prefix + group_suffix] = (incoming, outgoing)
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


def build_view(snapshot: GraphSnapshot, options: Optional[Options] = None) -> View:
    """What rqt_graph draws for ``snapshot`` with ``options`` (default: rqt_graph's)."""
    options = options or Options()
    mode = check_mode(options.mode)
    hide, group = options.hide, options.group
    node_filter = _split_filter(options.node_filter)
    topic_filter = _split_filter(options.topic_filter)

    nodes = [n for n in sorted(snapshot.nn_nodes) if _wanted(n, node_filter)]
    if mode == "nodes":
        topics = []  # type: List[str]
        edges = [e for e in snapshot.nn_edges if _wanted(e.label, topic_filter)]
    else:
        topics = [t for t in sorted(snapshot.nt_nodes) if _wanted(t, topic_filter)]
        edges = list(snapshot.nt_edges if mode == "active" else snapshot.nt_all_edges)
    edges = sorted(set(edges))

    if "debug" in hide:
        nodes = [n for n in nodes if _not_debug(n)]
        topics = [t for t in topics if _not_debug(t)]
        if mode == "nodes":
            edges = [e for e in edges if e.label not in DEBUG_EDGE_LABELS
                     and _not_debug(e.start) and _not_debug(e.end)]
    if "unreachable" in hide:  # rqt_graph leaves their edges; here they go with the node
        nodes = [n for n in nodes if n not in snapshot.bad_nodes]

    groups = []  # (group name, incoming edges, outgoing edges, namespace box allowed)
    if mode != "nodes":
        conns = _connections(edges)
        topics, edges = _hide_leaves(topics, edges, conns, "leaf-topics" in hide,
                                     "dead-sinks" in hide)
        topics, edges = _hide_tf_and_params(topics, edges, conns, "tf" in hide,
                                            "params" in hide)
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

    present = set(nodes) | set(topics)
    edges = [e for e in edges if e.start in present and e.end in present]
    linked = {e.start for e in edges} | {e.end for e in edges}
    topics = [t for t in topics if t in linked]

    level = options.namespace_level if "namespaces" in group else 0
    names = [t.strip() for t in topics] + [g[0] for g in groups if g[3]] + nodes
    clusters = _namespace_boxes(names, level) if level > 0 else []

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
    return View(mode, clusters, vertices, view_edges)


# ------------------------------------------------------------------------ DOT

def _quoted(value) -> str:
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return "%g" % value
    return '"%s"' % str(value).replace("\\", "\\\\").replace('"', '\\"')


def _attributes(pairs: Sequence[Tuple[str, object]]) -> str:
    return "[%s]" % ", ".join("%s=%s" % (k, _quoted(v)) for k, v in pairs if v is not None)


def _id(text: str) -> str:
    return text if re.match(r"^[A-Za-z_][A-Za-z0-9_]*$", text) else _quoted(text)


# graph attributes of rqt_graph's PydotFactory, for the graph and each namespace box
_RANK = (("compound", "true"), ("rank", "same"), ("rankdir", "LR"), ("ranksep", 0.2),
         ("simplify", "true"))


def to_dot(view: View) -> str:
    """rqt_graph's DOT text for ``view`` (lay it out with graphviz ``dot`` or ``xdot``)."""
    lines = ["digraph graphname {",
             "\tgraph %s;" % _attributes(_RANK + (("fontname", FONT_NAME),
                                                   ("fontsize", FONT_SIZE))),
             "\tnode %s;" % _attributes((("fontname", FONT_NAME), ("fontsize", FONT_SIZE))),
             "\tedge %s;" % _attributes((("fontname", FONT_NAME), ("fontsize", FONT_SIZE)))]

    def vertex_line(v: Vertex, indent: str) -> str:
        return "%s%s %s;" % (indent, _id(v.id), _attributes(
            (("label", v.label), ("shape", v.shape), ("URL", v.url), ("tooltip", v.url),
             ("color", v.color))))

    def box(namespace: str, indent: str) -> None:
        lines.append("%ssubgraph %s {" % (indent, _id(dot_id("cluster_" + namespace))))
        lines.append("%s\tgraph %s;" % (indent, _attributes(
            (("label", namespace),) + _RANK + (("style", "bold"),))))
        for child in view.clusters:
            if child.rsplit("/", 1)[0] == namespace:
                box(child, indent + "\t")
        lines.extend(vertex_line(v, indent + "\t") for v in view.vertices
                     if v.cluster == namespace)
        lines.append("%s}" % indent)

    for namespace in view.clusters:
        if namespace.count("/") == 1:
            box(namespace, "\t")
    lines.extend(vertex_line(v, "\t") for v in view.vertices if v.cluster is None)
    for edge in view.edges:
        lines.append("\t%s -> %s %s;" % (_id(edge.start), _id(edge.end), _attributes(
            (("label", edge.label or None), ("URL", edge.url or None), ("penwidth", 1)))))
    lines.append("}")
    return "\n".join(lines) + "\n"


# ------------------------------------------------------------------------ text

def _ranks(view: View) -> Dict[str, int]:
    """Each vertex id's distance along the arrows from the sources of the graph (vertices
    nothing points to), so that the text reads along the arrows. Where a cycle leaves no
    source (every node subscribes /clock when nothing is hidden), the node with the fewest
    incoming edges starts the count."""
    into = {v.id: 0 for v in view.vertices}
    for e in view.edges:
        into[e.end] = into.get(e.end, 0) + 1
    rank = {}  # type: Dict[str, int]
    frontier = sorted(vid for vid, n in into.items() if n == 0)
    base = 0
    while True:
        for vid in frontier:
            rank[vid] = base
        while frontier:
            step = []
            for e in view.edges:
                if e.start in frontier and e.end not in rank:
                    rank[e.end] = rank[e.start] + 1
                    step.append(e.end)
            frontier = step
        left = [v for v in view.vertices if v.id not in rank]
        if not left:
            return rank
        base = max(rank.values(), default=-1) + 1
        frontier = [min(left, key=lambda v: (not v.is_node, into[v.id], v.label)).id]


def to_text(view: View) -> str:
    """The picture for a terminal: one line per connection (``/a --/topic--> /b`` in the
    nodes mode, ``/a, /b --> [/topic] --> /c`` with topics), then the nodes drawn without
    an edge. Unreachable nodes, when shown, carry "(DEAD)" or "(WONKY)"."""
    by_id = {v.id: v for v in view.vertices}
    rank = _ranks(view)
    far = len(view.vertices) + 1

    def name(vid: str) -> str:
        v = by_id[vid]
        return v.label + (" (%s)" % v.status if v.status else "")

    def order(vid: str):
        return (rank.get(vid, far), name(vid))

    lines = []
    if view.mode == "nodes":
        for e in sorted(view.edges, key=lambda e: (order(e.start), e.label, order(e.end))):
            lines.append("%s --%s--> %s" % (name(e.start), e.label, name(e.end)))
    else:
        for v in sorted((v for v in view.vertices if not v.is_node), key=lambda v: order(v.id)):
            pubs = sorted({e.start for e in view.edges if e.end == v.id}, key=order)
            subs = sorted({e.end for e in view.edges if e.start == v.id}, key=order)
            line = "[%s]" % v.label
            if pubs:
                line = "%s --> %s" % (", ".join(name(p) for p in pubs), line)
            if subs:
                line = "%s --> %s" % (line, ", ".join(name(s) for s in subs))
            lines.append(line)
    linked = {e.start for e in view.edges} | {e.end for e in view.edges}
    alone = sorted(name(v.id) for v in view.vertices if v.is_node and v.id not in linked)
    lines.extend("%s   (no connection shown)" % n for n in alone)
    nodes = sum(1 for v in view.vertices if v.is_node)
    header = "%s: %d node%s, %d edge%s" % (MODE_TITLES[view.mode], nodes,
                                            "" if nodes == 1 else "s", len(view.edges),
                                            "" if len(view.edges) == 1 else "s")
    return "\n".join([header] + ["  " + line for line in lines]) + "\n"
