"""model_tree: which joints make trees, and each tree's links in the engine's order (the base,
then the links depth first, as pybullet numbers them; an anchor's massless base; a two-axis
joint's light link)."""
from tutorial_turtlebot.sim.files.model_tree import forest, trees
from tutorial_turtlebot.sim.files.world_types import WORLD_LINK, Joint, Link, Model

ZERO = (0.0,) * 6


def j(name, parent, child, kind="revolute"):
    return Joint(name, kind, parent, child, ZERO)


def model(links, joints):
    return Model("m", ZERO, False, tuple(Link(name, name, ZERO) for name in links),
                 tuple(x.name for x in joints), tuple(x.kind for x in joints), tuple(joints))


def test_forest_drops_a_second_parent_and_a_loop_in_file_order():
    kept, dropped = forest([j("ab", "a", "b"), j("bc", "b", "c"), j("ca", "c", "a"),
                            j("xb", "x", "b")])
    assert [x.name for x in kept] == ["ab", "bc"]
    assert [x.name for x in dropped] == ["ca", "xb"]


def test_a_chain_is_one_tree_in_parent_order():
    [tree] = trees(model("abc", [j("bc", "b", "c"), j("ab", "a", "b")]))
    assert tree.root == "a" and tree.links == ("a", "b", "c")
    entries = tree.body_links()
    assert [(e.link, e.parent) for e in entries] == [("a", -1), ("b", -1), ("c", 0)]
    assert not tree.single and not tree.fixed_base


def test_a_branching_tree_is_listed_depth_first():
    """pybullet numbers a multibody's links depth first, whatever the order they are given
    in: a fork's steered wheel comes right after the fork, before the rear wheels."""
    [tree] = trees(model(["base", "fork", "left", "right", "front"], [
        j("steer", "base", "fork"), j("left", "base", "left"), j("right", "base", "right"),
        j("spin", "fork", "front")]))
    assert [(e.link, e.parent) for e in tree.body_links()] == [
        ("base", -1), ("fork", -1), ("front", 0), ("left", -1), ("right", -1)]


def test_lone_links_are_single_trees():
    out = trees(model("ab", []))
    assert [t.root for t in out] == ["a", "b"] and all(t.single for t in out)


def test_a_fixed_joint_to_the_world_fixes_the_root_as_base():
    [tree] = trees(model("a", [j("pin", WORLD_LINK, "a", "fixed")]))
    assert tree.fixed_base and not tree.anchor_base
    assert [e.link for e in tree.body_links()] == ["a"]


def test_a_hinge_to_the_world_moves_the_root_about_a_massless_base():
    [tree] = trees(model("ab", [j("hinge", WORLD_LINK, "a"), j("ab", "a", "b")]))
    assert tree.anchor_base
    entries = tree.body_links()
    assert [(e.link, e.parent) for e in entries] == [(None, -1), ("a", -1), ("b", 0)]
    assert entries[1].joint.name == "hinge"


def test_a_universal_joint_is_two_axes_through_a_light_link():
    [tree] = trees(model("abc", [j("cross", "a", "b", "universal"), j("bc", "b", "c")]))
    entries = tree.body_links()
    assert [(e.link, e.axis, e.parent) for e in entries] == [
        ("a", 1, -1), (None, 1, -1), ("b", 2, 0), ("c", 1, 1)]
