"""The house rules of src/tutorial_turtlebot (doc/development.md), read from the imports of every
module: pybullet only in sim/engine/, no ROS in sim/, each sub-wing of sim/ importing only the
ones below it, the lab's nodes apart from the simulator, no import circle within a wing
(imports inside functions counted too), gazebo/impl/ apart from the node it serves and alone
reaching into rospy's internals; and from their text: a pybullet client id handed to pybullet
only by sim/engine/client.py (every other call goes through its Client), and no client id held
or passed by sim/world/ or sim/devices/."""
import ast
import io
import os
import tokenize

import pytest

import unit_paths

PACKAGE = os.path.join(unit_paths.ROOT, "src", "tutorial_turtlebot")
# what each part of the package may import of the package (besides itself and the top level:
# errors, robot_models, package_data, ros_names, node_params, node_output)
MAY_IMPORT = {
    "sim.kinematics": set(),
    "sim.files": {"sim.kinematics"},
    "sim.engine": {"sim.kinematics", "sim.files"},
    "sim.devices": {"sim.kinematics", "sim.files"},
    "sim.world": {"sim.kinematics", "sim.files", "sim.engine", "sim.devices"},
    "gazebo": {"sim"},
    "lab": set(),
    "learning": {"sim"},
}
ROS = ("rospy", "rosgraph", "roslaunch", "genpy", "rosbag", "tf2_ros", "actionlib")


def modules():
    """{dotted name below tutorial_turtlebot: file path} of every module of the package."""
    out = {}
    for folder, _, files in os.walk(PACKAGE):
        for name in files:
            if name.endswith(".py"):
                rel = os.path.relpath(os.path.join(folder, name), PACKAGE)[:-3]
                out[rel.replace(os.sep, ".")] = os.path.join(folder, name)
    return out


def imports(module, path):
    """Every module ``path`` imports, as absolute dotted names (the package's own beginning
    with ``tutorial_turtlebot.``), including imports inside functions."""
    package = ("tutorial_turtlebot." + module).split(".")
    if not path.endswith("__init__.py"):
        package = package[:-1]
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = package[:len(package) - node.level + 1] if node.level else []
            target = ".".join(base + ([node.module] if node.module else []))
            out.add(target)
            out.update(target + "." + alias.name for alias in node.names)   # modules too
    return out


def part_of(name):
    """The MAY_IMPORT key a dotted name below tutorial_turtlebot belongs to, or None."""
    for key in sorted(MAY_IMPORT, key=len, reverse=True):
        if name == key or name.startswith(key + "."):
            return key
    return None


MODULES = modules()


@pytest.mark.parametrize("module", sorted(MODULES))
def test_pybullet_is_imported_by_the_engine_alone(module):
    found = {name for name in imports(module, MODULES[module])
             if name.split(".")[0] in ("pybullet", "pybullet_data", "eglRenderer")
             or name.endswith("engine.bullet.pybullet")}
    if module.startswith("sim.engine."):
        return
    assert not found, "%s imports %s: only sim/engine/ talks to pybullet" % (module, found)


@pytest.mark.parametrize("module", sorted(m for m in MODULES if m.startswith("sim.")))
def test_the_simulator_knows_nothing_of_ros(module):
    found = {name for name in imports(module, MODULES[module])
             if name.split(".")[0] in ROS or name.split(".")[0].endswith("_msgs")
             or name.startswith(("tutorial_turtlebot.gazebo", "tutorial_turtlebot.lab"))}
    assert not found, "%s imports %s" % (module, found)


@pytest.mark.parametrize("module", sorted(m for m in MODULES if part_of(m)))
def test_each_part_imports_only_what_lies_below_it(module):
    own = part_of(module)
    allowed = MAY_IMPORT[own] | {own}
    wrong = set()
    for name in imports(module, MODULES[module]):
        if not name.startswith("tutorial_turtlebot."):
            continue
        inner = name[len("tutorial_turtlebot."):]
        target = part_of(inner)
        if target is None:
            continue   # the top level
        if target not in allowed and not any(target.startswith(a + ".") for a in allowed):
            wrong.add(inner)
    assert not wrong, "%s (%s) imports %s" % (module, own, sorted(wrong))


def test_the_rules_see_every_wing():
    """The checks above would pass on an empty package: they must have modules to check."""
    parts = {part_of(m) for m in MODULES}
    assert {"sim.files", "sim.engine", "sim.devices", "sim.world", "gazebo", "lab"} <= parts
    assert any(m.startswith("sim.engine.") and "pybullet" in " ".join(imports(m, MODULES[m]))
               for m in MODULES)


# --- import circles and gazebo/impl/ ------------------------------------------------------------

# The wings whose modules must not import one another in a circle (each with its sub-folders:
# gazebo's graph holds gazebo/impl/'s modules too).
WINGS = ("sim.files", "sim.engine", "sim.devices", "sim.world", "gazebo", "gazebo.impl", "lab",
         "learning")


def module_named(name):
    """The module (a MODULES key) that the absolute dotted ``name`` an import gives is: a module,
    or a package (its __init__); None for a name inside a module, or one not of the package."""
    if not name.startswith("tutorial_turtlebot."):
        return None
    inner = name[len("tutorial_turtlebot."):]
    if inner in MODULES:
        return inner
    if inner + ".__init__" in MODULES:
        return inner + ".__init__"
    return None


def wing_graph(wing):
    """{module of ``wing``: sorted modules of ``wing`` it imports}, imports inside functions
    included (``imports`` reads every import statement of the file)."""
    members = {m for m in MODULES if m.startswith(wing + ".")}
    return {m: sorted({t for t in map(module_named, imports(m, MODULES[m]))
                       if t in members and t != m})
            for m in members}


def find_circle(graph):
    """One circle of ``graph`` ({node: [nodes it points to]}) as [a, b, ..., a], or None; the
    nodes are tried in sorted order, so the same graph always gives the same circle."""
    state = {}   # node -> "open" while on the current path, "done" after
    path = []

    def visit(node):
        state[node] = "open"
        path.append(node)
        for target in graph.get(node, ()):
            if state.get(target) == "open":
                return path[path.index(target):] + [target]
            if target not in state:
                found = visit(target)
                if found:
                    return found
        path.pop()
        state[node] = "done"
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node)
            if found:
                return found
    return None


def test_a_circle_is_found_and_named():
    """The check below would pass if find_circle never found one."""
    assert find_circle({"a": ["b"], "b": ["c"], "c": ["a"], "d": ["a"]}) == ["a", "b", "c", "a"]
    assert find_circle({"a": ["b", "c"], "b": ["c"], "c": []}) is None
    assert find_circle({"a": ["a"]}) == ["a", "a"]


@pytest.mark.parametrize("wing", WINGS)
def test_no_import_circle_within_a_wing(wing):
    """The modules of one wing import one another without a circle: counting every import
    statement of a module, those inside its functions too (as ``imports`` reads them), and a
    package's __init__ for ``from . import x``."""
    graph = wing_graph(wing)
    assert graph, "no module in %s" % wing
    circle = find_circle(graph)
    assert circle is None, "import circle in %s: %s" % (wing, " -> ".join(circle))


IMPL = "gazebo.impl"


@pytest.mark.parametrize("module", sorted(m for m in MODULES if m.startswith(IMPL + ".")))
def test_gazebo_impl_imports_nothing_of_the_package_outside_impl(module):
    """gazebo/impl/ replaces rospy behaviours for the node and knows nothing of it: of the
    package it imports only impl/ itself (not gazebo/, not the top level); the rest is ROS's
    (rospy, rosgraph, message types), numpy's and the standard library's. What the node wants
    of it (a timing hook) it passes in."""
    outside = sorted(name.split(".", 1)[-1]
                     for name in imports(module, MODULES[module])
                     if (name == "tutorial_turtlebot" or name.startswith("tutorial_turtlebot."))
                     and not name.startswith("tutorial_turtlebot.%s." % IMPL)
                     and name != "tutorial_turtlebot.%s" % IMPL)
    assert not outside, "%s imports %s: gazebo/impl/ may import only impl/" % (module, outside)


# The one module that hands pybullet a client id (engine.client.Client binds it).
CLIENT_MODULE = "sim.engine.client"
# Names of a bare pybullet client id (an int) that sim/world/ and sim/devices/ must not hold:
# they pass the engine's Client (or the WorldPhysics) instead.
CLIENT_ID_NAMES = {"cid", "client_id", "physicsClientId"}


def names_and_attributes(path):
    """Every name token of ``path``'s code (not its strings or comments), and every attribute
    read after a dot, as (name, attribute or None) pairs: ``client.id`` gives ("client",
    "id")."""
    with open(path, encoding="utf-8") as f:
        tokens = [t for t in tokenize.generate_tokens(io.StringIO(f.read()).readline)
                  if t.type in (tokenize.NAME, tokenize.OP)]
    out = []
    for i, token in enumerate(tokens):
        if token.type != tokenize.NAME:
            continue
        dotted = i + 2 < len(tokens) and tokens[i + 1].string == "."
        out.append((token.string, tokens[i + 2].string if dotted else None))
    return out


@pytest.mark.parametrize("module", sorted(MODULES))
def test_only_the_client_module_hands_pybullet_a_client_id(module):
    with open(MODULES[module], encoding="utf-8") as f:
        text = f.read()
    if module == CLIENT_MODULE:
        assert "physicsClientId=" in text     # (the rule below would pass on a renamed module)
        return
    assert "physicsClientId=" not in text, (
        "%s calls pybullet with physicsClientId=: call the function on the engine's Client "
        "(sim/engine/client.py), which binds the id" % module)


@pytest.mark.parametrize("module", sorted(m for m in MODULES
                                          if m.startswith(("sim.world.", "sim.devices."))))
def test_the_world_and_the_devices_hold_no_client_id(module):
    pairs = names_and_attributes(MODULES[module])
    found = sorted({name for name, _ in pairs if name in CLIENT_ID_NAMES}
                   | {"%s.id" % name for name, attribute in pairs
                      if attribute == "id" and name == "client"})
    assert not found, ("%s uses %s: sim/world/ and sim/devices/ pass the engine's Client (or the "
                       "WorldPhysics), never a pybullet client id" % (module, found))


# rospy's internals: only gazebo/impl/ reaches into them, each module for one behaviour.
ROSPY_INTERNALS = ("rospy.impl", "rospy.rostime")


@pytest.mark.parametrize("module", sorted(m for m in MODULES if not m.startswith(IMPL + ".")))
def test_only_gazebo_impl_reaches_into_rospy(module):
    """Imported (``import rospy.impl.simtime``, ``from rospy.rostime import _set_rostime``) or
    reached through ``rospy.`` (``rospy.impl.simtime._clock_sub``)."""
    found = {name for name in imports(module, MODULES[module])
             if any(name == p or name.startswith(p + ".") for p in ROSPY_INTERNALS)}
    found |= {"%s.%s" % pair for pair in names_and_attributes(MODULES[module])
              if "%s.%s" % pair in ROSPY_INTERNALS}
    assert not found, "%s uses %s: rospy's internals are gazebo/impl/'s" % (module, sorted(found))


def test_setup_py_installs_every_package():
    """catkin_make install installs the packages setup.py names: a folder of src/ missing there
    would be missing from every install space."""
    folders = {os.path.relpath(folder, os.path.dirname(PACKAGE)).replace(os.sep, ".")
               for folder, _, files in os.walk(PACKAGE) if "__init__.py" in files}
    with open(os.path.join(unit_paths.ROOT, "setup.py"), encoding="utf-8") as f:
        tree = ast.parse(f.read())
    listed = {node.value for node in ast.walk(tree)
              if isinstance(node, ast.Constant) and isinstance(node.value, str)
              and node.value.startswith("tutorial_turtlebot")}
    assert folders <= listed, sorted(folders - listed)


@pytest.mark.parametrize("module", sorted(m for m in MODULES
                                          if m.startswith(("sim.", "lab.", "gazebo."))))
def test_no_wing_but_learning_needs_the_learning_libraries(module):
    found = {name for name in imports(module, MODULES[module])
             if name.split(".")[0] in ("gymnasium", "ray", "stable_baselines3", "torch")}
    assert not found, "%s imports %s: only learning/ may" % (module, found)
