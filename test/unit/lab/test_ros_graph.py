"""rqt_graph's picture without rqt (tutorial_turtlebot.lab.ros_graph, written by
lab.graph_output): the DOT text of each mode for fixed graphs, what is hidden and grouped by
default, the text picture, and the messages for a bad mode, output file or option. No master:
graphs are built by hand as rosgraph.impl.graph.Graph would fill them."""
import os
import shutil
import subprocess
import sys

import pytest

from tutorial_turtlebot.errors import UserError
from tutorial_turtlebot.lab import graph_node
from tutorial_turtlebot.lab import graph_output
from tutorial_turtlebot.lab import ros_graph as rg
from tutorial_turtlebot.lab.ros_graph import DEAD, WONKY, Edge, Options, topic_vertex
import unit_paths


def snapshot_from(pubs, subs, unconnected=(), bad=None):
    """A GraphSnapshot as rosgraph.impl.graph.Graph.update() leaves it for these
    registrations (topic -> node names). Every publisher/subscriber pair of a topic is
    connected except (topic, subscriber) pairs in ``unconnected``. Live edges come from the
    nodes' bus info, so a node in ``bad`` (name -> DEAD or WONKY) gives none of its own: a
    subscriber's side gives topic -> subscriber and the node -> node edge, a publisher's side
    gives publisher -> topic."""
    snap = rg.GraphSnapshot(bad_nodes=dict(bad or {}))

    def add(edges, edge):
        if edge not in edges:
            edges.append(edge)

    for registrations, publishing in ((pubs, True), (subs, False)):
        for topic, nodes in registrations.items():
            snap.nt_nodes.add(topic_vertex(topic))
            for node in nodes:
                snap.nn_nodes.add(node)
                add(snap.nt_all_edges, Edge(node, topic_vertex(topic)) if publishing
                    else Edge(topic_vertex(topic), node))
    for topic, nodes in subs.items():
        for sub in nodes:
            if (topic, sub) in unconnected:
                continue
            for pub in pubs.get(topic, ()):
                if sub not in snap.bad_nodes:
                    add(snap.nt_edges, Edge(topic_vertex(topic), sub))
                    add(snap.nn_edges, Edge(pub, sub, topic))
                if pub not in snap.bad_nodes:
                    add(snap.nt_edges, Edge(pub, topic_vertex(topic)))
    return snap


TELEOP = "/turtlebot3_teleop_keyboard"
# roslaunch tutorial_turtlebot sim.launch model:=burger + the teleop, as the master lists it
LAB_PUBS = {
    "/clock": ["/gazebo"],
    "/cmd_vel": [TELEOP],
    "/imu": ["/gazebo"],
    "/joint_states": ["/gazebo"],
    "/odom": ["/gazebo"],
    "/rosout": ["/gazebo", "/robot_state_publisher", TELEOP],
    "/rosout_agg": ["/rosout"],
    "/scan": ["/gazebo"],
    "/tf": ["/gazebo", "/robot_state_publisher"],
    "/tf_static": ["/robot_state_publisher"],
}
LAB_SUBS = {
    "/clock": ["/robot_state_publisher", "/rosout", TELEOP],
    "/cmd_vel": ["/gazebo"],
    "/joint_states": ["/robot_state_publisher"],
    "/rosout": ["/rosout"],
}
LAB = snapshot_from(LAB_PUBS, LAB_SUBS)

HEAD = """digraph graphname {
\tgraph [compound="true", rank="same", rankdir="LR", ranksep=0.2, simplify="true", \
fontname="sans", fontsize=11];
\tnode [fontname="sans", fontsize=11];
\tedge [fontname="sans", fontsize=11];
"""


LAB_NODES_DOT = HEAD + """\
\tn___gazebo [label="/gazebo", shape="ellipse", URL="/gazebo", tooltip="/gazebo"];
\tn___robot_state_publisher [label="/robot_state_publisher", shape="ellipse", \
URL="/robot_state_publisher", tooltip="/robot_state_publisher"];
\tn___turtlebot3_teleop_keyboard [label="/turtlebot3_teleop_keyboard", shape="ellipse", \
URL="/turtlebot3_teleop_keyboard", tooltip="/turtlebot3_teleop_keyboard"];
\tn___gazebo -> n___robot_state_publisher [label="/joint_states", URL="topic:/joint_states", \
penwidth=1];
\tn___turtlebot3_teleop_keyboard -> n___gazebo [label="/cmd_vel", URL="topic:/cmd_vel", \
penwidth=1];
}
"""

LAB_TOPICS_DOT = HEAD + """\
\tt___cmd_vel [label="/cmd_vel", shape="box", URL="topic:/cmd_vel", tooltip="topic:/cmd_vel"];
\tt___joint_states [label="/joint_states", shape="box", URL="topic:/joint_states", \
tooltip="topic:/joint_states"];
\tn___gazebo [label="/gazebo", shape="ellipse", URL="/gazebo", tooltip="/gazebo"];
\tn___robot_state_publisher [label="/robot_state_publisher", shape="ellipse", \
URL="/robot_state_publisher", tooltip="/robot_state_publisher"];
\tn___turtlebot3_teleop_keyboard [label="/turtlebot3_teleop_keyboard", shape="ellipse", \
URL="/turtlebot3_teleop_keyboard", tooltip="/turtlebot3_teleop_keyboard"];
\tt___cmd_vel -> n___gazebo [penwidth=1];
\tt___joint_states -> n___robot_state_publisher [penwidth=1];
\tn___gazebo -> t___joint_states [penwidth=1];
\tn___turtlebot3_teleop_keyboard -> t___cmd_vel [penwidth=1];
}
"""


def dot_of(snap, **options):
    return graph_output.to_dot(rg.build_view(snap, Options(**options)))


def text_of(snap, **options):
    return graph_output.to_text(rg.build_view(snap, Options(**options)))


def edges_of(snap, **options):
    """The drawn edges as (start label, end label, edge label)."""
    view = rg.build_view(snap, Options(**options))
    label = {v.id: v.label for v in view.vertices}
    return {(label[e.start], label[e.end], e.label) for e in view.edges}


def labels_of(snap, **options):
    return {v.label for v in rg.build_view(snap, Options(**options)).vertices}


# ---------------------------------------------------------------- the three modes, defaults

def test_nodes_mode_is_the_default_and_draws_the_lab_chain():
    assert rg.Options().mode == "nodes"
    assert dot_of(LAB) == LAB_NODES_DOT


@pytest.mark.parametrize("mode", ["active", "all"])
def test_topic_modes_draw_the_lab_chain_with_topic_boxes(mode):
    assert dot_of(LAB, mode=mode) == LAB_TOPICS_DOT


def test_active_draws_live_connections_all_draws_registrations():
    # /odom_listener has subscribed /odom but is not connected (yet)
    snap = snapshot_from({"/odom": ["/gazebo"], "/cmd_vel": [TELEOP]},
                         {"/odom": ["/odom_listener"], "/cmd_vel": ["/gazebo"]},
                         unconnected={("/odom", "/odom_listener")})
    assert ("/gazebo", "/odom", "") in edges_of(snap, mode="all")
    assert ("/odom", "/odom_listener", "") in edges_of(snap, mode="all")
    assert "/odom" not in labels_of(snap, mode="active")
    assert edges_of(snap, mode="active") == {(TELEOP, "/cmd_vel", ""), ("/cmd_vel", "/gazebo", "")}
    # nodes only: the node is drawn, alone
    assert edges_of(snap) == {(TELEOP, "/gazebo", "/cmd_vel")}
    assert "/odom_listener" in labels_of(snap)


def test_graphviz_lays_out_every_view():
    if shutil.which("dot") is None:
        pytest.skip("graphviz's dot is not installed")
    for snap in (LAB, GROUPS):
        for mode in rg.MODES:
            for hide in (rg.HIDE_DEFAULT, frozenset()):
                done = subprocess.run(["dot", "-Tsvg"], input=dot_of(snap, mode=mode,
                                                                     hide=hide).encode(),
                                      stdout=subprocess.PIPE, stderr=subprocess.PIPE)
                assert done.returncode == 0 and not done.stderr, done.stderr
                assert b"<svg" in done.stdout


# ---------------------------------------------------------------- what is hidden

def test_debug_hides_rosout_and_clock_nodes_topics_and_edges():
    for mode in rg.MODES:
        assert not {"/rosout", "/clock", "/rosout_agg"} & labels_of(LAB, mode=mode)
    assert "/rosout" in labels_of(LAB, hide=frozenset())
    assert ("/gazebo", "/robot_state_publisher", "/clock") in edges_of(LAB, hide=frozenset())
    assert ("/gazebo", "/rosout", "/clock") in edges_of(LAB, hide=frozenset())
    # nodes mode: an edge over /clock goes even between nodes that stay
    assert ("/gazebo", "/robot_state_publisher", "/clock") not in edges_of(LAB)


def test_dead_sinks_and_leaf_topics_are_hidden_in_topic_modes():
    everything = labels_of(LAB, mode="all", hide=frozenset({"debug"}), group=frozenset())
    assert {"/tf", "/scan", "/odom", "/imu", "/tf_static"} <= everything
    none = frozenset()
    # /tf: two publishers and no subscriber: a dead sink, not a leaf; /scan: both
    sinks_hidden = labels_of(LAB, mode="all", hide=frozenset({"debug", "dead-sinks"}), group=none)
    assert not {"/tf", "/tf_static", "/scan", "/odom", "/imu"} & sinks_hidden
    leaves_hidden = labels_of(LAB, mode="all", hide=frozenset({"debug", "leaf-topics"}),
                              group=none)
    assert "/tf" in leaves_hidden
    assert not {"/tf_static", "/scan", "/odom", "/imu"} & leaves_hidden
    for labels in (sinks_hidden, leaves_hidden):
        assert {"/cmd_vel", "/joint_states"} <= labels
    # the nodes mode draws node -> node edges: no topic vertex to hide
    assert edges_of(LAB, hide=frozenset({"debug"})) == edges_of(LAB)


def test_tf_and_params_hiding():
    assert "/tf" not in labels_of(GROUPS, mode="all", hide=rg.HIDE_DEFAULT | {"tf"})
    assert "/tf" in labels_of(GROUPS, mode="all")  # the group
    shown = labels_of(GROUPS, mode="all", hide=rg.HIDE_DEFAULT - {"params"})
    assert {"/move_base/parameter_updates", "/move_base/parameter_descriptions"} <= shown
    assert not {"/move_base/parameter_updates"} & labels_of(GROUPS, mode="all")


def test_unreachable_nodes_are_hidden_by_default_else_red_or_orange():
    snap = snapshot_from(LAB_PUBS, dict(LAB_SUBS, **{"/scan": ["/stuck"], "/odom": ["/slow"]}),
                         bad={"/stuck": DEAD, "/slow": WONKY})
    for mode in rg.MODES:
        assert not {"/stuck", "/slow"} & labels_of(snap, mode=mode)
    assert ("/gazebo", "/scan", "") in edges_of(snap, mode="all")  # as rqt_graph: /scan has
    assert ("/scan", "/stuck", "") not in edges_of(snap, mode="all")  # 2 edges, not a leaf
    shown = rg.HIDE_DEFAULT - {"unreachable"}
    dot = dot_of(snap, mode="all", hide=shown)
    assert ('\tn___stuck [label="/stuck", shape="ellipse", URL="/stuck (DEAD)", '
            'tooltip="/stuck (DEAD)", color="red"];\n') in dot
    assert 'URL="/slow (WONKY)", tooltip="/slow (WONKY)", color="orange"];' in dot
    assert "\tt___scan -> n___stuck [penwidth=1];\n" in dot
    assert "/gazebo --> [/scan] --> /stuck (DEAD)" in text_of(snap, mode="all", hide=shown)


def test_node_and_topic_filters():
    assert labels_of(LAB, node_filter="-/gazebo") == {"/robot_state_publisher", TELEOP}
    assert edges_of(LAB, node_filter="/gazebo,/robot_state_publisher") == {
        ("/gazebo", "/robot_state_publisher", "/joint_states")}
    assert edges_of(LAB, topic_filter="-/joint_states") == {(TELEOP, "/gazebo", "/cmd_vel")}
    # as in rqt_graph, leaf topics are found before the filtered nodes' edges go
    assert labels_of(LAB, mode="all", node_filter=".*teleop.*,/gazebo") == {
        "/gazebo", TELEOP, "/cmd_vel", "/joint_states"}
    with pytest.raises(UserError, match=r"bad filter pattern '\('"):
        labels_of(LAB, node_filter="(")


# ---------------------------------------------------------------- grouping

GROUPS = snapshot_from(
    {"/move_base/status": ["/move_base"], "/move_base/result": ["/move_base"],
     "/move_base/feedback": ["/move_base"], "/move_base/goal": ["/explore"],
     "/move_base/cancel": ["/explore"],
     "/move_base/parameter_updates": ["/move_base"],
     "/move_base/parameter_descriptions": ["/move_base"],
     "/camera/rgb/image_raw": ["/camera/driver"],
     "/camera/rgb/image_raw/compressed": ["/camera/driver"],
     "/camera/rgb/image_raw/theora": ["/camera/driver"],
     "/tf": ["/gazebo", "/robot_state_publisher"], "/tf_static": ["/robot_state_publisher"],
     "/robot1/cmd_vel": ["/explore"]},
    {"/move_base/status": ["/explore"], "/move_base/result": ["/explore"],
     "/move_base/feedback": ["/explore"], "/move_base/goal": ["/move_base"],
     "/move_base/cancel": ["/move_base"],
     "/move_base/parameter_updates": ["/dyn_client"],
     "/move_base/parameter_descriptions": ["/dyn_client"],
     "/camera/rgb/image_raw": ["/camera/viewer"],
     "/camera/rgb/image_raw/compressed": ["/camera/viewer"],
     "/camera/rgb/image_raw/theora": ["/camera/viewer"],
     "/tf": ["/tf_listener"], "/tf_static": ["/tf_listener"],
     "/robot1/cmd_vel": ["/robot1/base/driver"]})

GROUPS_ALL_DOT = HEAD + """\
\tsubgraph cluster___robot1 {
\t\tgraph [label="/robot1", compound="true", rank="same", rankdir="LR", ranksep=0.2, \
simplify="true", style="bold"];
\t\tsubgraph cluster___robot1__base {
\t\t\tgraph [label="/robot1/base", compound="true", rank="same", rankdir="LR", \
ranksep=0.2, simplify="true", style="bold"];
\t\t\tn___robot1__base__driver [label="/robot1/base/driver", shape="ellipse", \
URL="/robot1/base/driver", tooltip="/robot1/base/driver"];
\t\t}
\t\tt___robot1__cmd_vel [label="/robot1/cmd_vel", shape="box", URL="topic:/robot1/cmd_vel", \
tooltip="topic:/robot1/cmd_vel"];
\t}
\tsubgraph cluster___move_base {
\t\tgraph [label="/move_base", compound="true", rank="same", rankdir="LR", ranksep=0.2, \
simplify="true", style="bold"];
\t\tn___move_base__action_topics [label="/move_base/action_topics", shape="box3d", \
URL="topic:/move_base/action_topics", tooltip="topic:/move_base/action_topics"];
\t}
\tsubgraph cluster___camera {
\t\tgraph [label="/camera", compound="true", rank="same", rankdir="LR", ranksep=0.2, \
simplify="true", style="bold"];
\t\tsubgraph cluster___camera__rgb {
\t\t\tgraph [label="/camera/rgb", compound="true", rank="same", rankdir="LR", ranksep=0.2, \
simplify="true", style="bold"];
\t\t\tn___camera__rgb__image_raw__image_topics [label="/camera/rgb/image_raw/image_topics", \
shape="box3d", URL="topic:/camera/rgb/image_raw/image_topics", \
tooltip="topic:/camera/rgb/image_raw/image_topics"];
\t\t}
\t\tn___camera__driver [label="/camera/driver", shape="ellipse", URL="/camera/driver", \
tooltip="/camera/driver"];
\t\tn___camera__viewer [label="/camera/viewer", shape="ellipse", URL="/camera/viewer", \
tooltip="/camera/viewer"];
\t}
\tn___tf [label="/tf", shape="box3d", URL="topic:/tf", tooltip="topic:/tf"];
\tn___dyn_client [label="/dyn_client", shape="ellipse", URL="/dyn_client", \
tooltip="/dyn_client"];
\tn___explore [label="/explore", shape="ellipse", URL="/explore", tooltip="/explore"];
\tn___gazebo [label="/gazebo", shape="ellipse", URL="/gazebo", tooltip="/gazebo"];
\tn___move_base [label="/move_base", shape="ellipse", URL="/move_base", tooltip="/move_base"];
\tn___robot_state_publisher [label="/robot_state_publisher", shape="ellipse", \
URL="/robot_state_publisher", tooltip="/robot_state_publisher"];
\tn___tf_listener [label="/tf_listener", shape="ellipse", URL="/tf_listener", \
tooltip="/tf_listener"];
\tt___robot1__cmd_vel -> n___robot1__base__driver [penwidth=1];
\tn___explore -> t___robot1__cmd_vel [penwidth=1];
\tn___move_base -> n___move_base__action_topics [penwidth=1];
\tn___explore -> n___move_base__action_topics [penwidth=1];
\tn___move_base__action_topics -> n___explore [penwidth=1];
\tn___move_base__action_topics -> n___move_base [penwidth=1];
\tn___camera__driver -> n___camera__rgb__image_raw__image_topics [penwidth=1];
\tn___camera__rgb__image_raw__image_topics -> n___camera__viewer [penwidth=1];
\tn___gazebo -> n___tf [penwidth=1];
\tn___robot_state_publisher -> n___tf [penwidth=1];
\tn___tf -> n___tf_listener [penwidth=1];
}
"""


def test_grouping_actions_images_tf_and_namespace_boxes():
    assert dot_of(GROUPS, mode="all") == GROUPS_ALL_DOT
    assert dot_of(GROUPS, mode="active") == GROUPS_ALL_DOT  # everything is connected


def test_without_grouping_the_member_topics_come_back():
    labels = labels_of(GROUPS, mode="all", group=frozenset())
    assert {"/move_base/goal", "/move_base/cancel", "/move_base/status", "/move_base/result",
            "/move_base/feedback", "/camera/rgb/image_raw", "/camera/rgb/image_raw/compressed",
            "/camera/rgb/image_raw/theora", "/tf", "/tf_static"} <= labels
    assert not [label for label in labels if label.endswith("_topics")]
    dot = dot_of(GROUPS, mode="all", group=frozenset())
    assert "subgraph" not in dot and "box3d" not in dot


def test_images_need_three_of_the_four_topics():
    two = snapshot_from({"/cam/image": ["/drv"], "/cam/image/compressed": ["/drv"]},
                        {"/cam/image": ["/view"], "/cam/image/compressed": ["/view"]})
    assert "/cam/image/image_topics" not in labels_of(two, mode="all")
    assert {"/cam/image", "/cam/image/compressed"} <= labels_of(two, mode="all")


def test_namespace_level_and_the_nodes_mode():
    one = dot_of(GROUPS, mode="all", namespace_level=1)
    assert "cluster___robot1 " in one and "cluster___robot1__base" not in one
    assert "subgraph" not in dot_of(GROUPS, mode="all", namespace_level=0)
    assert "subgraph" not in dot_of(GROUPS, mode="all", group=frozenset({"tf"}))
    nodes = dot_of(GROUPS)  # boxes for nodes; no topic groups in the nodes mode
    assert "subgraph cluster___robot1 {" in nodes and "subgraph cluster___camera {" in nodes
    assert "box3d" not in nodes and "cluster___move_base" not in nodes
    assert ("\tn___explore -> n___move_base [label=\"/move_base/goal\", "
            "URL=\"topic:/move_base/goal\", penwidth=1];\n") in nodes


def test_whole_view_of_a_small_graph():
    """Every field of the view, through each step: filters, hiding, groups, boxes, edges."""
    snap = snapshot_from({"/ns/a/chatter": ["/ns/talker"], "/rosout": ["/ns/talker"],
                          "/tf": ["/ns/talker"]},
                         {"/ns/a/chatter": ["/listener", "/dead"], "/tf": ["/listener"]},
                         bad={"/dead": DEAD})
    dead = rg.Vertex("n___dead", "/dead", "ellipse", "/dead (DEAD)", color="red",
                     status=DEAD)
    listener = rg.Vertex("n___listener", "/listener", "ellipse", "/listener")
    talker = rg.Vertex("n___ns__talker", "/ns/talker", "ellipse", "/ns/talker", cluster="/ns")
    view = rg.build_view(snap, Options(mode="active", hide=frozenset({"leaf-topics"})))
    assert view == rg.View("active", ["/ns", "/ns/a"], [
        rg.Vertex("t___ns__a__chatter", "/ns/a/chatter", "box", "topic:/ns/a/chatter",
                  cluster="/ns/a"),
        rg.Vertex("n___tf", "/tf", "box3d", "topic:/tf"), dead, listener, talker], [
        rg.ViewEdge("t___ns__a__chatter", "n___listener"),
        rg.ViewEdge("n___ns__talker", "t___ns__a__chatter"),
        rg.ViewEdge("n___ns__talker", "n___tf"), rg.ViewEdge("n___tf", "n___listener")])
    assert rg.build_view(snap, Options(hide=frozenset())) == rg.View("nodes", ["/ns"], [
        dead, listener, talker], [
        rg.ViewEdge("n___ns__talker", "n___listener", "/ns/a/chatter", "topic:/ns/a/chatter"),
        rg.ViewEdge("n___ns__talker", "n___listener", "/tf", "topic:/tf")])


def test_ids_follow_rqt_graph():
    assert rg.node_id("/gazebo") == "n___gazebo"
    assert rg.topic_id("/cmd_vel") == "t___cmd_vel"
    assert rg.node_id("/camera/rgb-1") == "n___camera__rgb_1"
    assert rg.dot_id("cluster_/camera") == "cluster___camera"


def test_from_rosgraph_copies_a_graph():
    class Bad:
        DEAD, WONKY = 0, 1

        def __init__(self, kind):
            self.type = kind

    class Graph:
        nn_nodes = {"/a", "/b", "/c"}
        nt_nodes = {" /t"}
        nn_edges = [Edge("/a", "/b", "/t")]
        nt_edges = [Edge("/a", " /t", ""), Edge(" /t", "/b", "")]
        nt_all_edges = nt_edges
        bad_nodes = {"/c": Bad(0), "/d": Bad(1)}

    snap = rg.GraphSnapshot.from_rosgraph(Graph())
    assert snap.nn_edges == [Edge("/a", "/b", "/t")]
    assert snap.bad_nodes == {"/c": DEAD, "/d": WONKY}
    assert edges_of(snap) == {("/a", "/b", "/t")}


# ---------------------------------------------------------------- text picture

def test_text_picture_nodes_mode():
    assert text_of(LAB) == (
        "Nodes only: 3 nodes, 2 edges\n"
        "  /turtlebot3_teleop_keyboard --/cmd_vel--> /gazebo\n"
        "  /gazebo --/joint_states--> /robot_state_publisher\n")


@pytest.mark.parametrize("mode, title", [("active", "Nodes/Topics (active)"),
                                         ("all", "Nodes/Topics (all)")])
def test_text_picture_topic_modes(mode, title):
    assert text_of(LAB, mode=mode) == (
        "%s: 3 nodes, 4 edges\n"
        "  /turtlebot3_teleop_keyboard --> [/cmd_vel] --> /gazebo\n"
        "  /gazebo --> [/joint_states] --> /robot_state_publisher\n" % title)


def test_text_picture_lists_lone_nodes_and_shared_topics():
    snap = snapshot_from({"/chatter": ["/talker_a", "/talker_b"]},
                         {"/chatter": ["/listener"], "/other": ["/idle"]})
    assert text_of(snap) == (
        "Nodes only: 4 nodes, 2 edges\n"
        "  /talker_a --/chatter--> /listener\n"
        "  /talker_b --/chatter--> /listener\n"
        "  /idle   (no connection shown)\n")
    assert text_of(snap, mode="all").splitlines()[1] == (
        "  /talker_a, /talker_b --> [/chatter] --> /listener")
    assert text_of(rg.GraphSnapshot()) == "Nodes only: 0 nodes, 0 edges\n"


# ---------------------------------------------------------------- bad input

@pytest.mark.parametrize("mode", ["", "node", "Nodes", "topics", "rqt"])
def test_bad_mode_names_the_valid_ones(mode):
    with pytest.raises(UserError, match="unknown mode %r: the modes are nodes, active, all"
                       % mode):
        rg.check_mode(mode)
    with pytest.raises(UserError, match="unknown mode"):
        rg.build_view(LAB, Options(mode=mode))


@pytest.mark.parametrize("path, fmt", [("g.png", "png"), ("out/G.SVG", "svg"),
                                       ("/tmp/a.b/graph.dot", "dot")])
def test_output_format(path, fmt):
    assert rg.output_format(path) == fmt


@pytest.mark.parametrize("path", ["g.jpg", "graph", "g.png.txt", "dir.png/graph", ".dot/x"])
def test_bad_output_suffix_names_the_valid_ones(path):
    with pytest.raises(UserError) as err:
        rg.output_format(path)
    assert str(err.value) == ("cannot write %r: the output file must end in .png, .svg or .dot"
                              % path)


def test_hide_and_group_lists():
    assert rg.check_choices("debug, tf", rg.HIDE_CHOICES, "--hide") == {"debug", "tf"}
    assert rg.check_choices("none", rg.HIDE_CHOICES, "--hide") == frozenset()
    with pytest.raises(UserError) as err:
        rg.check_choices("debug,rosout", rg.HIDE_CHOICES, "--hide")
    assert str(err.value) == ("--hide: unknown item 'rosout': use a comma-separated list of "
                              "debug, dead-sinks, leaf-topics, tf, unreachable, params, or none")
    with pytest.raises(UserError, match="--group: unknown item ''"):
        rg.check_choices("", rg.GROUP_CHOICES, "--group")


def test_command_line_defaults_are_rqt_graphs():
    args = graph_node.parse_args([])
    assert args.options == Options()
    assert args.output is None and not args.text
    args = graph_node.parse_args(["--mode", "all", "--hide", "none", "--group", "tf,images",
                                  "--ns-level", "1", "--nodes=-/rosout", "-o", "g.svg"])
    assert args.options == Options(mode="all", hide=frozenset(),
                                   group=frozenset({"tf", "images"}), namespace_level=1,
                                   node_filter="-/rosout")
    assert args.output == "g.svg"


@pytest.mark.parametrize("argv, message", [
    (["--mode", "rqt"], "unknown mode 'rqt': the modes are nodes, active, all"),
    (["--output", "g.gif"], "cannot write 'g.gif': the output file must end in .png, .svg "
                            "or .dot"),
    (["--bogus"], "unrecognized arguments: --bogus (see graph --help)"),
    (["--ns-level", "-1"], "--ns-level must be 0 or more, got -1"),
    (["--interval", "0"], "--interval must be a positive number of seconds, got 0"),
    (["--group", "topics"], "--group: unknown item 'topics'")])
def test_command_line_errors(argv, message):
    with pytest.raises(UserError) as err:
        graph_node.parse_args(argv)
    assert str(err.value).startswith(message)


ROOT = unit_paths.ROOT


def run_script(*args):
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "src"),
               ROS_MASTER_URI="http://127.0.0.1:1")  # no master there
    return subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "graph")]
                          + list(args), env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, universal_newlines=True, timeout=30)


@pytest.mark.parametrize("args, status, start", [
    (["--mode", "x"], 2, "graph: error: unknown mode 'x': the modes are nodes, active, all"),
    (["-o", "g.jpg"], 2, "graph: error: cannot write 'g.jpg': the output file must end in"),
    ([], 1, "graph: error: cannot reach the ROS master at http://127.0.0.1:1 "),
    (["--text", "--mode", "all"], 1, "graph: error: cannot reach the ROS master")])
def test_script_says_one_line_and_fails(args, status, start):
    done = run_script(*args)
    assert done.returncode == status
    assert done.stderr.startswith(start), done.stderr
    assert len(done.stderr.splitlines()) == 1
    assert done.stdout == ""
