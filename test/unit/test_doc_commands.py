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
No ROS master.
"""
import glob
import os
import re
import shlex
import shutil
import subprocess
import xml.etree.ElementTree as ET

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
PAGES = ["README.md"] + sorted(os.path.relpath(p, ROOT)
                               for p in glob.glob(os.path.join(ROOT, "doc", "*.md")))
RUNNABLE = re.compile(r"<!-- runnable -->\s*\n```bash\n(.*?)\n```", re.S)
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
    siblings = re.findall(r"^from \.(\w+) import", text, re.M)
    return text + source_text(os.path.join(os.path.dirname(path), name + ".py")
                              for name in siblings)


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
