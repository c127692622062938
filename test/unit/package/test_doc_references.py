"""Every file a comment, docstring or doc page names exists in the repository.

Scans the repository's own text (README.md, CHANGELOG.rst, doc/, src/, scripts/, launch/, urdf/,
worlds/, test/, tools/, bench/, ...) for:

- paths from the repository's root (``doc/lab.md``,
  ``src/tutorial_turtlebot/sim/devices/camera.py``),
- Markdown links (``[text](lab.md)``), relative to the page,
- bare ``*.md`` / ``*.rst`` file names and ``see FOO.py``,
- dotted module names (``tutorial_turtlebot.lab.graph_node``),
- the numbered sections of ``doc/turtlebot3.md`` that a comment cites (``doc/turtlebot3.md 4.2``),

and fails on any that does not resolve, on a relative path that leads out of the repository,
and on issue numbers (say what the thing is instead). Also: CHANGELOG.rst's newest version is
package.xml's. No ROS master.
"""
import ast
import io
import os
import re
import subprocess
import tokenize
import xml.etree.ElementTree as ET

import pytest
import unit_paths

ROOT = unit_paths.ROOT

# Top-level folders and files of the repository that a path may start with.
ROOT_DIRS = ("doc", "src", "test", "tools", "bench", "urdf", "worlds", "launch", "scripts",
             "models", "rviz", "msgs", "ros_shims", "env-hooks", "config")
SCANNED_SUFFIXES = (".py", ".md", ".rst", ".launch", ".test", ".urdf", ".world", ".sdf", ".xml",
                    ".sh", ".txt", ".in", ".cmake", ".rviz", ".cfg", ".config", ".xacro")
SCANNED_NAMES = ("Makefile", "CMakeLists.txt", "package.xml", "run")
# A relative path that may climb out of the folder it is written in.
UP_PATH = re.compile(r"(?<![\w.])((?:\.\./)+[\w./-]*[\w/])")
ISSUE = re.compile(r"\b[Ii]ssues?\s*#?\d+|\(issue\b|\bissue\s+#"
                   r"|(?<![\w/])#\d+\b(?!\s*[-:]?\s*\w*\s*\])")
ROOT_PATH = re.compile(r"(?<![\w/.$@{:-])((?:%s)/[\w./-]*[\w/])" % "|".join(ROOT_DIRS))
MD_LINK = re.compile(r"\]\(([^)\s]+)\)")
BARE_DOC = re.compile(r"(?<![\w/.-])([\w-]+\.(?:md|rst))\b")
SEE_PY = re.compile(r"\bsee\s+([\w/]+\.py)\b")
MODULE = re.compile(r"\btutorial_turtlebot((?:\.\w+)+)")
REFERENCE_SECTION = re.compile(r"doc/turtlebot3\.md(?:,?\s+sections?)?\s+(\d+(?:\.\d+)?"
                               r"(?:(?:-|,\s*|\s+and\s+)\d+(?:\.\d+)?)*)")


def repository_files(root=ROOT):
    """The repository's text files that people read: tracked and new (not ignored) files."""
    try:
        out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard"],
                             cwd=root, capture_output=True, text=True, check=True).stdout
        names = out.split()
    except (OSError, subprocess.CalledProcessError):   # not a git checkout: walk it
        names = []
        for folder, dirs, files in os.walk(root):
            dirs[:] = [d for d in dirs if not d.startswith(".")]
            names += [os.path.relpath(os.path.join(folder, f), root) for f in files]
    return sorted(n for n in names
                  if os.path.isfile(os.path.join(root, n))
                  and (n.endswith(SCANNED_SUFFIXES) or os.path.basename(n) in SCANNED_NAMES
                       or n.startswith("scripts/"))
                  and not n.startswith(("msgs/gazebo_msgs/msg/", "msgs/gazebo_msgs/srv/")))


def _exists(root, path):
    return os.path.exists(os.path.join(root, path.rstrip("/")))


def _basenames(root, files):
    return {os.path.basename(f) for f in files}


def _section_numbers(root):
    path = os.path.join(root, "doc", "turtlebot3.md")
    if not os.path.isfile(path):
        return set()
    with open(path, encoding="utf-8") as page:
        return {m.group(1) for m in re.finditer(r"^#+\s+(\d+(?:\.\d+)?)[.\s]", page.read(), re.M)}


def _keep_lines(text, spans):
    """``text`` with everything blanked but the (start, end) character spans, lines kept."""
    kept = [c if c == "\n" else " " for c in text]
    for start, end in spans:
        kept[start:end] = text[start:end]
    return "".join(kept)


def _python_prose(text):
    """Only the comments and docstrings of Python source, at their lines."""
    offsets = [0]
    for line in text.splitlines(True):
        offsets.append(offsets[-1] + len(line))

    def at(row, col):
        return offsets[row - 1] + col

    spans = []
    try:
        for tok in tokenize.generate_tokens(io.StringIO(text).readline):
            if tok.type == tokenize.COMMENT:
                spans.append((at(*tok.start), at(*tok.end)))
        for node in ast.walk(ast.parse(text)):
            body = getattr(node, "body", None)
            if (isinstance(body, list) and body and isinstance(body[0], ast.Expr)
                    and isinstance(getattr(body[0], "value", None), ast.Constant)
                    and isinstance(body[0].value.value, str)):
                first, last = body[0].lineno, getattr(body[0], "end_lineno", body[0].lineno)
                spans.append((offsets[first - 1], offsets[last]))
    except (SyntaxError, tokenize.TokenError, IndentationError):
        return text
    return _keep_lines(text, spans)


def prose(name, text):
    """The part of a file that people read as prose: all of a page, the comments and
    docstrings of code; None for data files (RViz configs)."""
    if name.endswith((".md", ".rst", ".txt")) and not name.endswith("CMakeLists.txt"):
        return text
    if name.endswith(".rviz"):
        return None
    if name.endswith(".py") or text.startswith("#!/usr/bin/env python"):
        return _python_prose(text)
    if name.endswith((".launch", ".test", ".urdf", ".world", ".sdf", ".xml", ".xacro",
                      ".config")):
        return _keep_lines(text, [m.span() for m in re.finditer(r"<!--.*?-->", text, re.S)])
    return _keep_lines(text, [m.span() for m in re.finditer(r"#[^\n]*", text)])


def problems_in(root, name, text, basenames, sections):
    """One line per bad reference in file ``name`` (relative to ``root``) with ``text``."""
    found = []
    here = os.path.dirname(name)
    for number, line in enumerate(text.splitlines(), 1):
        where = "%s:%d" % (name, number)
        for match in UP_PATH.finditer(line):
            target = os.path.normpath(os.path.join(here, match.group(1)))
            if target == ".." or target.startswith(".." + os.sep):
                found.append("%s: %s leads out of the repository" % (where, match.group(1)))
        for match in ISSUE.finditer(line):
            found.append("%s: issue number %r: say what it is instead" % (where, match.group(0)))
    readable = prose(name, text)
    for number, line in enumerate((readable or "").splitlines(), 1):
        where = "%s:%d" % (name, number)
        for match in ROOT_PATH.finditer(line):
            path, after = match.group(1).rstrip("."), line[match.end():match.end() + 1]
            if after in "<*{$" and after != "" or re.search(r"[A-Z]{3,}", path):
                continue   # a pattern or a placeholder: urdf/turtlebot3_<model>.urdf, NAME
            if not _exists(root, path):
                found.append("%s: %s does not exist" % (where, path))
        if name.endswith(".md"):
            for match in MD_LINK.finditer(line):
                target = match.group(1).split("#")[0]
                if not target or re.match(r"^[a-z]+:", target):
                    continue
                if not _exists(root, os.path.normpath(os.path.join(here, target))):
                    found.append("%s: link %s does not resolve" % (where, match.group(1)))
        for match in BARE_DOC.finditer(line):
            doc = match.group(1)
            if doc not in basenames:
                found.append("%s: %s is not in the repository" % (where, doc))
        for match in SEE_PY.finditer(line):
            target = match.group(1)
            if not (_exists(root, target) or _exists(root, os.path.join(here, target))
                    or os.path.basename(target) in basenames):
                found.append("%s: see %s: no such file" % (where, target))
        for match in MODULE.finditer(line):
            parts = match.group(1).strip(".").split(".")
            base = os.path.join("src", "tutorial_turtlebot")
            resolved = 0
            for part in parts:
                if _exists(root, os.path.join(base, part + ".py")):
                    resolved += 1
                    break
                if not os.path.isdir(os.path.join(root, base, part)):
                    break
                base = os.path.join(base, part)
                resolved += 1
            if resolved == 0 and parts[0] not in ("msg", "srv"):
                found.append("%s: module tutorial_turtlebot.%s does not exist"
                             % (where, ".".join(parts)))
        for match in REFERENCE_SECTION.finditer(line):
            for cited in re.findall(r"\d+(?:\.\d+)?", match.group(1)):
                if cited not in sections:
                    found.append("%s: doc/turtlebot3.md has no section %s" % (where, cited))
    return found


def all_problems(root=ROOT):
    files = repository_files(root)
    basenames = _basenames(root, files) | {"README.md", "CHANGELOG.rst"}
    sections = _section_numbers(root)
    found = []
    for name in files:
        if name == os.path.relpath(__file__, ROOT).replace(os.sep, "/"):
            continue   # this file plants bad references on purpose
        with open(os.path.join(root, name), encoding="utf-8", errors="replace") as handle:
            found += problems_in(root, name, handle.read(), basenames, sections)
    return found


def test_every_reference_in_the_repository_resolves():
    problems = all_problems()
    assert not problems, "\n".join(problems)


def _tree(tmp_path, files):
    for name, text in files.items():
        path = tmp_path / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return str(tmp_path)


GOOD = {
    "README.md": "See [the lab](doc/lab.md) and doc/turtlebot3.md 4.2.\n",
    "doc/lab.md": "Back to [the README](../README.md#top).\n",
    "doc/turtlebot3.md": "# Ref\n## 4. Worlds\n### 4.2 The arena\n",
    "src/tutorial_turtlebot/__init__.py": "",
    "src/tutorial_turtlebot/sim/__init__.py": "",
    "src/tutorial_turtlebot/sim/devices/camera.py":
        '"""See doc/turtlebot3.md 4.2 and 4 and lab.md."""\n',
}


@pytest.mark.parametrize("bad, expected", [
    ("# numbers from notes.md 2.4\n", "not in the repository"),
    ("# see doc/gazebo_node.md\n", "doc/gazebo_node.md does not exist"),
    ('"""The lab fixes (issue 13)."""\n', "issue number"),
    ("# as issue #7 asked\n", "issue number"),
    ("# the rows of Issue 11\n", "issue number"),
    ("# the rules in ../../../../notes/rules.txt\n", "leads out of the repository"),
    ("# see world_api_helpers.py for the rules\n", "no such file"),
    ("# the arena, doc/turtlebot3.md 4.3\n", "no section 4.3"),
    ("# tutorial_turtlebot.sim.nowhere is gone\n", None),
    ("# tutorial_turtlebot.nowhere.camera\n", "module tutorial_turtlebot.nowhere.camera"),
])
def test_a_planted_bad_reference_fails(tmp_path, bad, expected):
    root = _tree(tmp_path, dict(GOOD))
    assert all_problems_in_tree(root) == []
    (tmp_path / "src" / "tutorial_turtlebot" / "sim" / "bad.py").write_text(bad)
    problems = all_problems_in_tree(root)
    if expected is None:        # a submodule that is gone: the package resolves, the rest not
        return
    assert problems and expected in problems[0], problems


def test_a_broken_markdown_link_fails(tmp_path):
    root = _tree(tmp_path, dict(GOOD, **{"doc/lab.md": "See [nodes](nodes.md).\n"}))
    problems = all_problems_in_tree(root)
    assert any("link nodes.md does not resolve" in p for p in problems), problems


def all_problems_in_tree(root):
    """all_problems for a tree that is not a git checkout (a tmp_path)."""
    files = []
    for folder, dirs, names in os.walk(root):
        files += [os.path.relpath(os.path.join(folder, f), root) for f in names]
    basenames = _basenames(root, files) | {"README.md", "CHANGELOG.rst"}
    sections = _section_numbers(root)
    found = []
    for name in sorted(files):
        with open(os.path.join(root, name), encoding="utf-8") as handle:
            found += problems_in(root, name, handle.read(), basenames, sections)
    return found


def _newest_changelog_version(text):
    match = re.search(r"^(\d+\.\d+\.\d+) \((\d{4}-\d{2}-\d{2})\)\n-+$", text, re.M)
    return match.group(1) if match else None


def test_changelog_is_catkins_format_and_matches_package_xml():
    with open(os.path.join(ROOT, "CHANGELOG.rst"), encoding="utf-8") as handle:
        text = handle.read()
    lines = text.splitlines()
    assert lines[1] == "Changelog for package tutorial_turtlebot"
    assert set(lines[0]) == {"^"} and len(lines[0]) >= len(lines[1]) and lines[2] == lines[0]
    for title, underline in zip(lines, lines[1:]):
        if re.match(r"^\d+\.\d+\.\d+ \(", title):
            assert re.match(r"^\d+\.\d+\.\d+ \(\d{4}-\d{2}-\d{2}\)$", title), title
            assert underline == "-" * len(title), title
    version = ET.parse(os.path.join(ROOT, "package.xml")).getroot().findtext("version")
    assert _newest_changelog_version(text) == version


def test_every_doc_page_is_linked_from_the_readme():
    with open(os.path.join(ROOT, "README.md"), encoding="utf-8") as handle:
        links = set(MD_LINK.findall(handle.read()))
    pages = {"doc/" + f for f in os.listdir(os.path.join(ROOT, "doc")) if f.endswith(".md")}
    assert pages and not pages - {link.split("#")[0] for link in links}


# --- numbered sections --------------------------------------------------------------------------

NUMBERED_HEADING = re.compile(r"^(#+)\s+(\d+(?:\.\d+)*)\.?\s", re.M)


def numbering_problems(text):
    """One line per numbered heading that does not follow the one before: 1, 1.1, 1.2, 2, 2.1..."""
    found, last = [], []
    for match in NUMBERED_HEADING.finditer(text):
        number = [int(part) for part in match.group(2).split(".")]
        depth = len(number)
        expected = (last[:depth - 1] + [last[depth - 1] + 1] if len(last) >= depth
                    else last + [1] * (depth - len(last)))
        if number != expected:
            found.append("section %s follows %s: expected %s" % (
                match.group(2), ".".join(map(str, last)) or "the start",
                ".".join(map(str, expected))))
        last = number
    return found


def test_numbered_sections_are_consecutive_on_every_page():
    pages = ["README.md"] + ["doc/" + f for f in sorted(os.listdir(os.path.join(ROOT, "doc")))
                             if f.endswith(".md")]
    numbered, problems = [], []
    for page in pages:
        with open(os.path.join(ROOT, page), encoding="utf-8") as handle:
            text = handle.read()
        if NUMBERED_HEADING.search(text):
            numbered.append(page)
            problems += ["%s: %s" % (page, p) for p in numbering_problems(text)]
    assert "doc/turtlebot3.md" in numbered and "doc/lab.md" in numbered, numbered
    assert not problems, "\n".join(problems)


@pytest.mark.parametrize("headings, expected", [
    ("## 1. A\n### 1.1 B\n### 1.2 C\n## 2. D\n## 3. E\n### 3.1 F\n", None),
    ("## 1. A\n## 3. C\n", "section 3 follows 1: expected 2"),
    ("## 1. A\n## 2. B\n### 2.2 C\n", "section 2.2 follows 2: expected 2.1"),
    ("## 1. A\n### 1.1 B\n### 1.3 C\n", "section 1.3 follows 1.1: expected 1.2"),
    ("## 1. A\n### 1.1 B\n### 2.1 C\n", "section 2.1 follows 1.1: expected 1.2"),
    ("## 2. A\n", "section 2 follows the start: expected 1"),
])
def test_a_numbering_gap_fails(headings, expected):
    problems = numbering_problems("# Page\n\nText.\n\n" + headings)
    assert problems == ([expected] if expected else []), problems
