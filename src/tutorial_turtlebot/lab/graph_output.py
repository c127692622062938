"""The two outputs of a ros_graph View: rqt_graph's DOT text (:func:`to_dot`; graphviz
``dot`` or ``xdot`` lay it out) and a plain-text picture for terminals (:func:`to_text`).
No rospy here; the View is made by ``ros_graph.build_view``.
"""
import re
from typing import Dict, List, Sequence, Tuple

from .ros_graph import MODE_TITLES, Vertex, View, dot_id

FONT_NAME = "sans"  # rqt_graph draws its labels in Qt's "sans", 11 px
FONT_SIZE = 11


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


def _connection_lines(view: View, name, order) -> List[str]:
    """One line per connection: ``/a --/topic--> /b`` in the nodes mode, else one per topic
    (``/a, /b --> [/topic] --> /c``); ``name`` and ``order`` give a vertex id's text and
    place."""
    if view.mode == "nodes":
        return ["%s --%s--> %s" % (name(e.start), e.label, name(e.end)) for e in
                sorted(view.edges, key=lambda e: (order(e.start), e.label, order(e.end)))]
    lines = []
    for v in sorted((v for v in view.vertices if not v.is_node), key=lambda v: order(v.id)):
        pubs = sorted({e.start for e in view.edges if e.end == v.id}, key=order)
        subs = sorted({e.end for e in view.edges if e.start == v.id}, key=order)
        line = "[%s]" % v.label
        if pubs:
            line = "%s --> %s" % (", ".join(name(p) for p in pubs), line)
        if subs:
            line = "%s --> %s" % (line, ", ".join(name(s) for s in subs))
        lines.append(line)
    return lines


def _text_header(view: View) -> str:
    """The picture's first line: the mode's title, how many nodes and edges."""
    nodes = sum(1 for v in view.vertices if v.is_node)
    return "%s: %d node%s, %d edge%s" % (MODE_TITLES[view.mode], nodes,
                                         "" if nodes == 1 else "s", len(view.edges),
                                         "" if len(view.edges) == 1 else "s")


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

    lines = _connection_lines(view, name, order)
    linked = {e.start for e in view.edges} | {e.end for e in view.edges}
    alone = sorted(name(v.id) for v in view.vertices if v.is_node and v.id not in linked)
    lines.extend("%s   (no connection shown)" % n for n in alone)
    return "\n".join([_text_header(view)] + ["  " + line for line in lines]) + "\n"
