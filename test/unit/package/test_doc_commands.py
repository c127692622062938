"""Every command and quoted output in README.md and doc/*.md is real.

- Blocks marked ``<!-- runnable -->`` (a fenced ```bash block right after the marker, lines
  ``$ COMMAND`` each followed by its exact output) are cheap, need no ROS master, and are run
  here in the ROS shell; their output must be what the page says.
- Every other command is checked for what it names: ``roslaunch tutorial_turtlebot FILE
  arg:=...`` (the launch file and its <arg>s), ``rosrun tutorial_turtlebot NAME _param:=...``
  (the script in scripts/ and a parameter the code reads), ``rostest tutorial_turtlebot X.test``,
  ``make TARGET`` (the Makefile), ``python3 FILE`` and ``bash FILE``, ``rosservice call
  /gazebo/NAME``, ``rostopic ... /TOPIC`` (a topic doc/gazebo_node.md lists) and
  ``dynparam set /gazebo PARAM``.
- The ROS wiki lists of doc/gazebo_node.md and doc/nodes.md (topics, services, parameters of each
  ``## Node``) name things the node's code (its ``Code:`` line) really has, with types that exist;
  the launch-file tables name real arguments.
- Every file a command reads is in the repository or written by an earlier command on the page;
  a file pasted into a single-quoted YAML string (``'$(cat FILE)'``) has no single quote.
- Blocks marked ``<!-- sim example -->`` (a fenced ```bash block: plain command lines, or ``$``
  lines with their output) run against the real sim in test/rostest/ros_shell.test. Every
  command that spawns or moves a model is in one, at a spot of its own on its page, clear of
  turtlebot3_world's pillars and walls.
- README.md's first screen shows ``make demo`` and ``make test``; its benchmark figures are
  doc/benchmark.md's.
No ROS master.
"""
import glob
import math
import os
import re
import shlex
import shutil
import subprocess
import xml.etree.ElementTree as ET

import pytest
import yaml
import unit_paths

ROOT = unit_paths.ROOT
PAGES = ["README.md"] + sorted(os.path.relpath(p, ROOT)
                               for p in glob.glob(os.path.join(ROOT, "doc", "*.md")))
RUNNABLE = re.compile(r"<!-- runnable -->\s*\n```bash\n(.*?)\n```", re.S)
SIM_EXAMPLE = re.compile(r"<!-- sim example -->\s*\n```bash\n(.*?)\n```", re.S)
WIKI_ITEM = re.compile(r"^- ((?:`[^`]+`(?:,\s*|\s+and\s+)?)+)\s*\(([^)]*)\)")
PARAM_TYPES = ("double", "int", "bool", "string")


def read(name):
    with open(os.path.join(ROOT, name), encoding="utf-8") as handle:
        return handle.read()


def launch_args(name):
    """The <arg> names of launch/NAME."""
    return {arg.get("name") for arg in ET.parse(os.path.join(ROOT, "launch", name)).iter("arg")
            if arg.get("default") is not None or arg.get("value") is None}


def make_targets():
    return set(re.findall(r"^([\w-]+):", read("Makefile"), re.M))


def source_text(paths):
    return "\n".join(read(p) for p in paths)


ALL_SOURCE = None


def all_source():
    global ALL_SOURCE
    if ALL_SOURCE is None:
        ALL_SOURCE = source_text(
            sorted(os.path.relpath(p, ROOT) for p in
                   glob.glob(os.path.join(ROOT, "src", "tutorial_turtlebot", "**", "*.py"),
                             recursive=True)))
    return ALL_SOURCE


def script_source(script):
    """The code of the module scripts/SCRIPT runs and of the sibling modules it imports."""
    module = re.search(r"^from (tutorial_turtlebot[\w.]*) import", read("scripts/" + script), re.M)
    path = os.path.join("src", *module.group(1).split(".")) + ".py"
    text = read(path)
    siblings = re.findall(r"^from \.([\w.]+) import", text, re.M)   # .x and .impl.y
    files = (os.path.join(os.path.dirname(path), *name.split(".")) + ".py" for name in siblings)
    return text + source_text(f for f in files if os.path.isfile(os.path.join(ROOT, f)))


# --- the commands on the pages ------------------------------------------------------------------

def code_lines(text):
    """(line number, line) of code: fenced blocks, 4-space indented blocks, inline code."""
    lines = text.splitlines()
    fenced = False
    for number, line in enumerate(lines, 1):
        if line.startswith("```"):
            fenced = not fenced
            continue
        if fenced or line.startswith("    "):
            yield number, line.strip()
        else:
            for span in re.findall(r"`([^`]+)`", line):
                yield number, span.strip()


def commands(text):
    """(line number, argv) of each simple command in the page's code."""
    for number, line in code_lines(text):
        line = re.sub(r"^\$ ", "", line)
        line = re.sub(r"\s+#.*$", "", line).rstrip("\\ ")
        for part in re.split(r"\s*(?:;|&&|\|\||\|)\s*", line):
            try:
                argv = shlex.split(part)
            except ValueError:
                continue
            while argv and re.match(r"^[A-Z_]+=", argv[0]):
                argv = argv[1:]          # ROS_NAMESPACE=tb3_1 rosrun ...
            if argv:
                yield number, argv


def documented_topics():
    """The topics doc/gazebo_node.md lists, as global names (~x is /gazebo/x)."""
    topics = {"/rosout", "/rosout_agg", "/tf_static"}
    for names, _ in wiki_items(read("doc/gazebo_node.md"), ("Published Topics",
                                                            "Subscribed Topics")):
        for name in names:
            topics.add("/gazebo/" + name[1:] if name.startswith("~") else
                       name if name.startswith("/") else "/" + name)
    return topics


def topic_problem(topic, topics):
    """None if ``topic`` (maybe in a robot's namespace, maybe with a field path) is documented."""
    parts = topic.strip("/").split("/")
    for skip in (0, 1):                     # /tb3_0/odom: a robot's namespace
        for end in range(len(parts), skip, -1):
            if "/" + "/".join(parts[skip:end]) in topics:
                return None
    return "topic %s is not one doc/gazebo_node.md lists" % topic


def check_command(argv, topics):
    """One line per thing ``argv`` names that does not exist, or []."""
    tool, args = argv[0], argv[1:]
    found = []
    if tool == "roslaunch":
        args = [a for a in args if not a.startswith("-") and not a.isdigit()]
        if len(args) >= 2 and args[0] == "tutorial_turtlebot" and args[1] != "FILE":
            name = args[1]
            if not os.path.isfile(os.path.join(ROOT, "launch", name)):
                return ["no launch file %s" % name]
            known = launch_args(name)
            for arg in args[2:]:
                if ":=" in arg and arg.split(":=")[0] not in known:
                    found.append("%s has no argument %s" % (name, arg.split(":=")[0]))
    elif tool == "rosrun" and len(args) >= 2:
        if args[0] == "tutorial_turtlebot":
            if args[1] != "NAME" and not os.path.isfile(os.path.join(ROOT, "scripts", args[1])):
                found.append("no script scripts/%s" % args[1])
            for arg in args[2:]:
                param = re.match(r"^_(\w+):=", arg)
                if param and not re.search(r"[\"'~]%s[\"']" % param.group(1),
                                           script_source(args[1])):
                    found.append("%s: no node reads ~%s" % (args[1], param.group(1)))
        elif args[:3] == ["dynamic_reconfigure", "dynparam", "set"] and len(args) >= 5:
            if '"%s"' % args[4] not in read("src/tutorial_turtlebot/gazebo/physics_config.py"):
                found.append("dynparam: /gazebo has no parameter %s" % args[4])
    elif tool == "rostest" and len(args) >= 2 and args[0] == "tutorial_turtlebot":
        if not os.path.isfile(os.path.join(ROOT, "test", "rostest", args[1])):
            found.append("no rostest test/rostest/%s" % args[1])
    elif tool == "make":
        for target in args:
            if "=" not in target and target not in make_targets():
                found.append("the Makefile has no target %s" % target)
    elif tool in ("python3", "bash") and args and not args[0].startswith("-"):
        if re.match(r"^[\w./-]+$", args[0]) and "/" in args[0] \
                and not os.path.isfile(os.path.join(ROOT, args[0])):
            found.append("no file %s" % args[0])
    elif tool == "rosservice" and args[:1] == ["call"] and len(args) >= 2:
        service = args[1].rsplit("/", 1)[-1]
        if '"%s"' % service not in all_source() and service not in all_source():
            found.append("no service %s" % args[1])
    elif tool == "rostopic" and args and args[0] != "list":
        for arg in args[1:]:
            if arg.startswith("/"):
                problem = topic_problem(arg, topics)
                if problem:
                    found.append(problem)
                break
    return found


@pytest.mark.parametrize("page", PAGES)
def test_every_command_names_what_exists(page):
    topics = documented_topics()
    problems = []
    for number, argv in commands(read(page)):
        problems += ["%s:%d: %s" % (page, number, p) for p in check_command(argv, topics)]
    assert not problems, "\n".join(problems)


def test_the_command_check_catches_mistakes():
    topics = documented_topics()
    assert check_command(["roslaunch", "tutorial_turtlebot", "sim.launch", "modle:=waffle"],
                         topics) == ["sim.launch has no argument modle"]
    assert check_command(["roslaunch", "tutorial_turtlebot", "simulation.launch"], topics)
    assert check_command(["rosrun", "tutorial_turtlebot", "teleop"], topics)
    assert check_command(["rosrun", "tutorial_turtlebot", "move_turtlebot", "_speed:=1"], topics)
    assert check_command(["make", "docs"], topics)
    assert check_command(["rostopic", "echo", "/odometry"], topics)
    assert not check_command(["rostopic", "echo", "-n", "1", "/tb3_0/odom/pose/pose"], topics)
    assert check_command(["rosservice", "call", "/gazebo/teleport_model"], topics)
    assert check_command(["python3", "bench/run_benchmark.py"], topics)


# --- runnable blocks ----------------------------------------------------------------------------

def runnable_blocks():
    for page in PAGES:
        for match in RUNNABLE.finditer(read(page)):
            block, command, output = [], None, []
            for line in match.group(1).splitlines():
                if line.startswith("$ "):
                    if command is not None:
                        block.append((command, output))
                    command, output = line[2:], []
                else:
                    output.append(line)
            if command is not None:
                block.append((command, output))
            for command, output in block:
                yield pytest.param(command, "\n".join(output), id="%s: %s" % (page, command))


def ros_shell_ready():
    if not shutil.which("rosrun") or not shutil.which("rospack"):
        return False
    found = subprocess.run(["rospack", "find", "tutorial_turtlebot"], capture_output=True)
    return found.returncode == 0


def normalise(text):
    text = text.replace("optional arguments:", "options:")   # argparse before Python 3.10
    return "\n".join(line.rstrip() for line in text.strip("\n").splitlines())


@pytest.mark.parametrize("command, expected", list(runnable_blocks()))
def test_runnable_block_prints_what_the_page_says(command, expected):
    if not ros_shell_ready():
        pytest.skip("no ROS shell: source catkin_ws/devel/setup.bash first")
    env = dict(os.environ, COLUMNS="80")
    env.pop("ROS_MASTER_URI", None)
    done = subprocess.run(["bash", "-c", command], cwd=ROOT, env=env, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, timeout=120)
    assert normalise(done.stdout) == normalise(expected)


def test_there_are_runnable_blocks():
    assert len(list(runnable_blocks())) >= 4


# --- the ROS wiki lists and the tables ----------------------------------------------------------

def wiki_items(text, headings):
    """(names, type) of each list item under one of ``headings`` (### level)."""
    section = None
    for line in text.splitlines():
        if line.startswith("#"):
            section = line.lstrip("#").strip()
            continue
        match = WIKI_ITEM.match(line)
        if match and section in headings:
            yield re.findall(r"`([^`]+)`", match.group(1)), match.group(2)


def node_sections(text):
    """(node heading, code files, section text) of each ``## Node`` of a wiki page."""
    for part in re.split(r"^(?=## )", text, flags=re.M):
        if part.startswith("## Node") or part.startswith("## `graph`"):
            code = re.search(r"^Code: (.*)$", part, re.M)
            files = re.findall(r"`([^`]+)`", code.group(1)) if code else []
            yield part.splitlines()[0], files, part


def message_type_exists(kind):
    package, _, name = kind.partition("/")
    if package == "gazebo_msgs":
        return any(os.path.isfile(os.path.join(ROOT, "msgs", "gazebo_msgs", folder,
                                               name + "." + folder))
                   for folder in ("msg", "srv"))
    return package in read("package.xml") and re.match(r"^[A-Z]\w*$", name) is not None


@pytest.mark.parametrize("page", ["doc/gazebo_node.md", "doc/nodes.md"])
def test_wiki_lists_name_what_the_code_has(page):
    problems = []
    sections = list(node_sections(read(page)))
    assert sections
    for heading, files, text in sections:
        assert files, "%s: %s has no Code: line" % (page, heading)
        for path in files:
            assert os.path.isfile(os.path.join(ROOT, path)), path
        code = source_text(files) + source_text(
            os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, "urdf", "*.urdf")))
        for names, kind in wiki_items(text, ("Subscribed Topics", "Published Topics",
                                             "Services")):
            type_name = kind.split(")")[0].strip()
            if not message_type_exists(type_name):
                problems.append("%s %s: no type %s" % (heading, names, type_name))
            for name in names:
                last = name.rstrip("/").rsplit("/", 1)[-1].lstrip("~")
                if last not in code:
                    problems.append("%s: %s is not in %s" % (heading, name, files))
        for names, kind in wiki_items(text, ("Parameters",)):
            if kind.split(",")[0].strip() not in PARAM_TYPES:
                problems.append("%s %s: type %r" % (heading, names, kind))
            for name in names:
                param = name.lstrip("~")
                if not re.search(r"[\"'~]%s[\"']" % re.escape(param), code):
                    problems.append("%s: no code reads %s" % (heading, name))
    assert not problems, "\n".join(problems)


def test_launch_tables_name_real_arguments():
    problems = []
    for line in read("README.md").splitlines():
        cells = line.split("|")
        launches = re.findall(r"`([\w.]+\.launch)`", cells[1]) if len(cells) == 5 else []
        for launch in launches:
            for arg in re.findall(r"`(\w+)`", cells[3]):
                if arg not in launch_args(launch):
                    problems.append("README: %s has no argument %s" % (launch, arg))
    sim_args = launch_args("sim.launch")
    table = read("doc/gazebo_node.md").split("## Launch arguments")[1].split("\n## ")[0]
    for line in table.splitlines():
        if line.startswith("| `"):
            for arg in re.findall(r"`(\w+)`", line.split("|")[1]):
                if arg not in sim_args:
                    problems.append("doc/gazebo_node.md: sim.launch has no argument %s" % arg)
    assert not problems, "\n".join(problems)


def test_readme_lists_every_script_and_links_every_page():
    text = read("README.md")
    table = text.split("## Nodes and commands")[1].split("\n## ")[0]
    listed = set(re.findall(r"^\| `(\w+)", table, re.M))
    assert listed == set(os.listdir(os.path.join(ROOT, "scripts")))
    links = {link.split("#")[0] for link in re.findall(r"\]\(([^)\s]+)\)", text)}
    pages = {p for p in PAGES if p.startswith("doc/")}
    assert pages <= links
    for link in links:
        if not re.match(r"^[a-z]+:", link):
            assert os.path.exists(os.path.join(ROOT, link)), link


# --- files the commands read --------------------------------------------------------------------

# The commands whose arguments may name files (the first word of a command line).
FILE_TOOLS = {"rosrun", "roslaunch", "rostest", "rosservice", "rostopic", "rosbag", "python3",
              "bash", "source", "cat", "sed", "head", "tail", "cp", "ign", "catkin_make", "xacro"}
FILE_NAME = re.compile(r"(?<![\w./$~)-])(/?[\w.-]+(?:/[\w.-]+)*\.(?:sdf|urdf|world|xacro|xml|yaml"
                       r"|py|sh|rviz|stl|dae|obj|bag))(?![\w/])")
PASTED_IN_QUOTES = re.compile(r"'\$\(cat\s+([^)\s]+)\)'")


def written_files(argv):
    """The files ``argv`` writes: > FILE, >> FILE, tee FILE, -O FILE (rosbag), --output FILE."""
    found = []
    for before, word in zip(argv, argv[1:]):
        if before in (">", ">>", "tee", "-O", "--output"):
            found.append(word)
    found += [word.lstrip(">") for word in argv if re.match(r"^>>?[^>&]", word)]
    return found


def file_problems(page, text):
    """One line per file that a command on the page reads and that is neither in the repository
    nor written by an earlier command on the page."""
    problems, written = [], set()
    for number, argv in commands(text):
        outputs = written_files(argv)
        if argv[0] in FILE_TOOLS:
            for word in argv[1:]:
                if word in outputs:
                    continue
                for name in FILE_NAME.findall(word):
                    if name.endswith(".launch") or re.search(r"[A-Z]{3,}", name) \
                            or name in written:
                        continue
                    if name.startswith("/") or not os.path.isfile(os.path.join(ROOT, name)):
                        problems.append("%s:%d: %s is not in the repository nor written by an "
                                        "earlier command" % (page, number, name))
        written.update(outputs)
    for number, line in code_lines(text):
        for name in PASTED_IN_QUOTES.findall(line):
            path = os.path.join(ROOT, name)
            if os.path.isfile(path) and "'" in read(name):
                problems.append("%s:%d: %s is pasted inside single quotes but has a single quote "
                                "(line %d)" % (page, number, name,
                                               read(name).split("'")[0].count("\n") + 1))
    return problems


@pytest.mark.parametrize("page", PAGES)
def test_every_file_a_command_reads_is_there(page):
    problems = file_problems(page, read(page))
    assert not problems, "\n".join(problems)


def test_the_file_check_catches_mistakes(tmp_path):
    assert file_problems("p", "    rosrun tutorial_turtlebot spawn_model -sdf -file box.sdf "
                              "-model box\n") == [
        "p:1: box.sdf is not in the repository nor written by an earlier command"]
    assert file_problems("p", "    rosrun tutorial_turtlebot spawn_model -urdf -file /tmp/a.urdf"
                              " -model a\n")
    assert not file_problems("p", "    cat urdf/turtlebot3_burger.urdf > /tmp/a.urdf\n"
                                  "    rosrun tutorial_turtlebot spawn_model -urdf"
                                  " -file /tmp/a.urdf -model a\n")
    assert file_problems("p", "    rosservice call /gazebo/spawn_sdf_model "
                              "\"{model_xml: '$(cat models/nothing/model.sdf)'}\"\n")
    assert not file_problems("p", "    rosservice call /gazebo/spawn_sdf_model "
                                  "\"{model_xml: '$(cat models/goal_box/model.sdf)'}\"\n")
    quoted = os.path.relpath(str(tmp_path / "quoted.sdf"), ROOT)
    (tmp_path / "quoted.sdf").write_text("<sdf>\n<!-- the robot's -->\n</sdf>\n")
    assert file_problems("p", "    rosservice call /gazebo/spawn_sdf_model "
                              "\"{model_xml: '$(cat %s)'}\"\n" % quoted) == [
        "p:1: %s is pasted inside single quotes but has a single quote (line 2)" % quoted]


# --- the examples that run against the sim ------------------------------------------------------

SPAWN_SERVICES = ("/gazebo/spawn_sdf_model", "/gazebo/spawn_urdf_model")
# m: the largest TurtleBot3's turning radius, the farthest corner of the Waffle's footprint
# (doc/turtlebot3.md 1.1); every spot is taken as a robot that wide.
FOOTPRINT_RADIUS = 0.26
# turtlebot3_world's own robot, at turtlebot3_gazebo's spawn (doc/turtlebot3.md 4.1).
OWN_ROBOT = ("the robot of sim.launch", -2.0, -0.5)


def sim_example_lines(text):
    """The line numbers (from 1) of the lines inside ``<!-- sim example -->`` blocks."""
    lines = set()
    for match in SIM_EXAMPLE.finditer(text):
        first = text.count("\n", 0, match.start(1)) + 1
        lines.update(range(first, first + match.group(1).count("\n") + 1))
    return lines


def _option(argv, name, default="0"):
    return argv[argv.index(name) + 1] if name in argv[:-1] else default


def _yaml_position(text, *keys):
    data = yaml.safe_load(re.sub(r"\$\(cat [^)]*\)", "", text)) or {}
    for key in keys:
        data = data.get(key) or {}
    return float(data.get("x", 0.0)), float(data.get("y", 0.0))


def spawn_spots(text):
    """(line, model name, x, y) of each command on the page that spawns or teleports a model."""
    for number, argv in commands(text):
        if argv[:1] == ["rosrun"] and argv[2:3] == ["spawn_model"] and "-model" in argv:
            yield (number, _option(argv, "-model", "?"), float(_option(argv, "-x")),
                   float(_option(argv, "-y")))
        elif argv[:2] == ["rosservice", "call"] and len(argv) >= 4:
            if argv[2] in SPAWN_SERVICES:
                name = (yaml.safe_load(re.sub(r"\$\(cat [^)]*\)", "", argv[3])) or {}).get(
                    "model_name", "?")
                yield (number, name) + _yaml_position(argv[3], "initial_pose", "position")
            elif argv[2] == "/gazebo/set_model_state":
                state = (yaml.safe_load(argv[3]) or {}).get("model_state") or {}
                name = state.get("model_name", "?")
                if re.match(r"^turtlebot3_(burger|waffle|waffle_pi)$", name):
                    name = OWN_ROBOT[0]
                yield (number, name) + _yaml_position(argv[3], "model_state", "pose", "position")


def spot_problems(page, text, world):
    """Spawns or teleports on the page that are not in a sim example block, that share a spot
    with another model of the page, or that stand in one of ``world``'s obstacles."""
    from tutorial_turtlebot.sim.world.spawn_check import find_obstacle

    problems = []
    marked = sim_example_lines(text)
    spots = [(0, OWN_ROBOT[0]) + OWN_ROBOT[1:]]
    for number, name, x, y in spawn_spots(text):
        if number not in marked:
            problems.append("%s:%d: %s: not in a <!-- sim example --> block, so no test runs it"
                            % (page, number, name))
        hit = find_obstacle(world, x, y, FOOTPRINT_RADIUS)
        if hit is not None:
            problems.append("%s:%d: %s at (%g, %g) is within %.2f m of %s"
                            % (page, number, name, x, y, FOOTPRINT_RADIUS, hit[0].name))
        for _, other, ox, oy in spots:
            if other != name and math.hypot(x - ox, y - oy) < 2 * FOOTPRINT_RADIUS:
                problems.append("%s:%d: %s at (%g, %g) is within %.2f m of %s at (%g, %g)"
                                % (page, number, name, x, y, 2 * FOOTPRINT_RADIUS, other, ox, oy))
        spots.append((number, name, x, y))
    return problems


@pytest.fixture(scope="module")
def turtlebot3_world():
    from tutorial_turtlebot.sim.files.sdf.world_catalogue import resolve_world
    from tutorial_turtlebot.sim.files.sdf.world_sdf import load_world

    return load_world(resolve_world("turtlebot3_world")[0])


@pytest.mark.parametrize("page", PAGES)
def test_every_spawn_example_runs_at_a_free_spot(page, turtlebot3_world):
    problems = spot_problems(page, read(page), turtlebot3_world)
    assert not problems, "\n".join(problems)


def test_the_spawn_examples_are_found():
    spots = {page: [spot[1:] for spot in spawn_spots(read(page))] for page in PAGES}
    assert ("goal", -0.5, -0.5) in spots["doc/gazebo_node.md"]
    assert ("box", -0.5, 0.5) in spots["doc/gazebo_node.md"]
    assert [s[0] for s in spots["doc/robots.md"]] == ["my_burger", "tb3"]


def test_the_spot_check_catches_mistakes(turtlebot3_world):
    block = "<!-- sim example -->\n```bash\n%s\n```\n"
    same = block % ("rosrun tutorial_turtlebot spawn_model -urdf -file a.urdf -model a -x 0.5\n"
                    "rosrun tutorial_turtlebot spawn_model -urdf -file b.urdf -model b -x 0.6")
    assert spot_problems("p", same, turtlebot3_world) == [
        "p:4: b at (0.6, 0) is within 0.52 m of a at (0.5, 0)"]
    pillar = block % "rosrun tutorial_turtlebot spawn_model -urdf -file a.urdf -model a -x 1"
    problems = spot_problems("p", pillar, turtlebot3_world)
    assert len(problems) == 1 and "a at (1, 0) is within 0.26 m of ros_symbol::" in problems[0]
    unmarked = ("    rosservice call /gazebo/spawn_sdf_model \"{model_name: goal, model_xml: "
                "'$(cat models/goal_box/model.sdf)', initial_pose: {position: {x: -0.5}}}\"\n")
    assert spot_problems("p", unmarked, turtlebot3_world) == [
        "p:1: goal: not in a <!-- sim example --> block, so no test runs it"]
    teleport = block % ("rosservice call /gazebo/set_model_state '{model_state: {model_name: "
                        "turtlebot3_waffle, pose: {position: {x: -1.9, y: -0.5}}}}'")
    assert not spot_problems("p", teleport, turtlebot3_world)


def test_there_are_sim_examples():
    blocks = [match.group(1) for page in PAGES for match in SIM_EXAMPLE.finditer(read(page))]
    assert any("$(cat models/goal_box/model.sdf)" in block for block in blocks)
    assert any("-file doc/examples/box.sdf" in block for block in blocks)


# --- the README's first screen and its benchmark ------------------------------------------------

def test_readme_shows_the_two_commands_in_its_first_25_lines():
    first = "\n".join(read("README.md").splitlines()[:25])
    for command in ("make demo", "make test"):
        assert re.search(r"^\s+%s\b" % command, first, re.M), \
            "README.md: %r is not in the first 25 lines" % command


def test_readme_benchmark_figures_are_those_of_doc_benchmark():
    section = read("README.md").split("\n## Benchmark\n")[1].split("\n## ")[0]
    table = read("doc/benchmark.md").split("<!-- LATEST TABLE")[1].split("<!-- END LATEST TABLE")[0]
    figures = re.findall(r"\d+(?:\.\d+)?(?:x| %| s\b| ms\b| MB\b)", section)
    assert figures, "README.md's Benchmark section gives no headline figure"
    for figure in figures:
        assert figure in table, "README.md's benchmark figure %s is not in doc/benchmark.md's " \
                                "latest table" % figure
    assert not re.search(r"\bminutes?\b", section), \
        "README.md's Benchmark section says how long make bench takes: link doc/benchmark.md"
    for jargon in ("physics bound", "floor", "ceiling", "stage 1 client"):
        assert jargon not in section, "README.md's Benchmark section says %r: plain words, " \
                                      "the details in doc/benchmark.md" % jargon
    assert "(doc/benchmark.md)" in section
