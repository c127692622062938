"""doc/learning.md's speed and accuracy figures are make bench's: each is in doc/benchmark.md's
latest table, in a row its line names. One source for the figures.

The rule:
- A figure is a number with a unit of speed or accuracy: steps/s, steps per (wall or CPU)
  second, a speed-up (1.91x, 1.2 times), a share of a bound (0.89 of the bound), mm, mrad.
  Ranges and lists before one unit count each number ("193 / 218 steps/s", "1 to 2 times").
- A line of doc/learning.md with a figure carries a marker ``<!-- bench: ROW -->`` (an HTML
  comment: the page shows nothing), ROW a piece of the measure column of exactly one row of
  the latest table (between ``<!-- LATEST TABLE`` and ``<!-- END LATEST TABLE -->``; backticks
  and ``&nbsp;`` ignored). Each figure of the line must be a number of the value column of one
  of the rows the line names, written as the table writes it (1.9, not 1.90).
- A table whose header speaks of speed (steps per, steps/s, speed) gives each figure its unit,
  so that no bare number escapes the rule.
- README.md is held to the same, but for its Benchmark section (test_doc_commands checks that
  one against the table). Exempt sections, each for the reason EXEMPT gives.
A figure make bench does not measure is not given: the page says it in words, or points at
benchmark.md or at the test that prints it.
"""
import os
import re
import subprocess
import sys
import textwrap

import unit_paths

ROOT = unit_paths.ROOT
PAGES = ("doc/learning.md", "README.md")
EXEMPT = {
    ("doc/learning.md", "The same numbers as ROBOTIS' clients"):
        "the equivalence rostest's own figures (test_learning_equivalence.py prints them)",
    ("doc/learning.md", "Training: make train"):
        "the figures of the training run its caption names: make bench does not train",
    ("README.md", "Benchmark"):
        "checked by test_doc_commands.test_readme_benchmark_figures_are_those_of_doc_benchmark",
}
NUMBER = r"\d+(?:,\d{3})*(?:\.\d+)?"
UNIT = (r"(?:x\b|\s+times\b|\s*steps/s\b|\s+(?:environment\s+|env\s+)?steps\s+per\s+"
        r"(?:wall\s+|CPU\s+)?second\b|\s+of\s+(?:the|its)\s+(?:physics\s+)?bound\b|\s*mm\b"
        r"|\s*mrad\b)")
FIGURE = re.compile(r"(?<![\w.])(%s(?:\s*(?:to|/|,|and)\s*%s)*)%s" % (NUMBER, NUMBER, UNIT))
MARKER = re.compile(r"<!--\s*bench:\s*(.*?)\s*-->")
SPEED_HEADER = re.compile(r"steps per|steps/s|\bspeed\b", re.I)
BARE_NUMBER = re.compile(r"^%s$" % NUMBER)


def read(name):
    with open(os.path.join(ROOT, name), encoding="utf-8") as handle:
        return handle.read()


def plain(text):
    """``text`` with backticks, ``&nbsp;`` and runs of spaces taken out, for matching."""
    return re.sub(r"\s+", " ", text.replace("`", "").replace("&nbsp;", " ")).strip()


def latest_rows(benchmark_text):
    """(measure, value) of each row of benchmark.md's latest table."""
    table = benchmark_text.split("<!-- LATEST TABLE")[1].split("<!-- END LATEST TABLE")[0]
    rows = []
    for line in table.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if not line.startswith("|") or len(cells) < 2 or set(cells[0]) <= set("-: "):
            continue
        if cells[:2] == ["measure", "value"]:
            continue
        rows.append((plain(cells[0]), cells[1]))
    return rows


def figures(line):
    """The numbers of the figures on ``line`` (markers and link targets left out)."""
    text = re.sub(r"\]\([^)]*\)", "]", MARKER.sub("", line))
    return [number for match in FIGURE.finditer(text)
            for number in re.findall(NUMBER, match.group(1))]


def sections(text):
    """(line number, the headings above it, line) of each line of ``text``."""
    headings = []
    fenced = False
    for number, line in enumerate(text.splitlines(), 1):
        if line.startswith("```"):
            fenced = not fenced
        heading = re.match(r"^(#+)\s+(.*)$", line) if not fenced else None
        if heading:
            level = len(heading.group(1))
            headings = headings[:level - 1] + [""] * (level - 1 - len(headings)) \
                + [heading.group(2).strip()]
            continue
        yield number, list(headings), line


def figure_problems(page, text, rows):
    """Each figure of ``text`` (the page ``page``) that the rule does not find in ``rows``
    ((measure, value) of the latest table), and each marker that names no single row."""
    problems = []
    header = None
    for number, headings, line in sections(text):
        where = "%s:%d" % (page, number)
        if any((page, heading) in EXEMPT for heading in headings):
            continue
        named = []
        for key in MARKER.findall(line):
            matching = [value for measure, value in rows if plain(key) in measure]
            if len(matching) != 1:
                problems.append("%s: <!-- bench: %s --> names %d rows of benchmark.md's latest "
                                "table (one wanted)" % (where, key, len(matching)))
            named.extend(matching)
        row_numbers = {n.replace(",", "") for value in named for n in re.findall(NUMBER, value)}
        for figure in figures(line):
            if not named:
                problems.append("%s: %s is a measured figure with no <!-- bench: ROW --> marker: "
                                "take it from benchmark.md's latest table and name the row, or "
                                "point there" % (where, figure))
            elif figure.replace(",", "") not in row_numbers:
                problems.append("%s: %s is not in the row(s) of benchmark.md's latest table the "
                                "line names (%s)" % (where, figure, "; ".join(named)))
        header = table_header(line, header)
        if header and SPEED_HEADER.search(header) and line.startswith("|"):
            for cell in line.strip().strip("|").split("|"):
                if BARE_NUMBER.match(MARKER.sub("", cell).strip()):
                    problems.append("%s: a bare number (%s) in a table of speeds: give its unit"
                                    % (where, cell.strip()))
    return problems


def table_header(line, header):
    """The header line of the table ``line`` belongs to (None outside tables)."""
    if not line.startswith("|"):
        return None
    return header if header is not None else line


def test_every_measured_figure_is_make_benchs():
    rows = latest_rows(read("doc/benchmark.md"))
    assert len(rows) > 20 and any(m.startswith("learning stage 1") for m, _ in rows)
    problems = [p for page in PAGES for p in figure_problems(page, read(page), rows)]
    assert not problems, "\n".join(problems)


def test_the_learning_page_takes_its_speeds_from_the_table_and_points_there():
    text = read("doc/learning.md")
    assert len(MARKER.findall(text)) >= 8
    assert "(benchmark.md#the-latest-table)" in text


def vector_example(text):
    """The first indented code block of the section "Many environments at once", dedented."""
    section = text.split("\n## Many environments at once\n")[1].split("\n## ")[0]
    block = re.search(r"((?:^(?:    .*)?\n)+)", section[section.index("\n    "):], re.M)
    return textwrap.dedent(block.group(1)).strip("\n") + "\n"


def test_the_vector_example_guards_its_main_and_runs_when_spawned(tmp_path):
    """make_vector_env's workers are processes: started by spawn (or forkserver, Python 3.14's
    default on Linux), each imports the main file, so the example needs its __main__ guard."""
    code = vector_example(read("doc/learning.md"))
    guard = 'if __name__ == "__main__":'
    assert guard in code, "doc/learning.md's make_vector_env example lacks %r" % guard
    spawned = re.sub(r"^(if __name__ == \"__main__\":.*)$",
                     r"\1\n    import multiprocessing\n"
                     r"    multiprocessing.set_start_method('spawn')", code, count=1, flags=re.M)
    script = tmp_path / "example.py"
    script.write_text(spawned + "    print(observations.shape, rewards.shape)\n")
    done = subprocess.run([sys.executable, str(script)], stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, timeout=120)
    assert done.returncode == 0 and done.stdout.strip() == "(8, 28) (8,)", done.stdout


def test_the_exempt_sections_exist():
    for page, heading in EXEMPT:
        assert re.search(r"^#+ %s$" % re.escape(heading), read(page), re.M), (page, heading)


ROWS = [("learning stage 1, one StageEnv (no ROS): environment steps per wall second", "356"),
        ("its physics bound: bare pybullet, the same steps and rays", "399 (0.89 of it)"),
        ("learning stage 3, one StageEnv / its physics bound", "193 / 218 steps/s (0.88)")]


def test_the_rule_catches_mistakes():
    def problems(text):
        return figure_problems("p", text, ROWS)

    assert not problems("one env: 356 steps/s <!-- bench: learning stage 1, one `StageEnv` -->")
    assert not problems("stage 3: 193 / 218 steps/s, 0.88 of its bound "
                        "<!-- bench: learning stage 3 -->")
    assert not problems("| one | 356 steps/s <!-- bench: stage 1, one --> | 0.89 of the bound "
                        "<!-- bench: its physics bound: bare --> |")
    assert not problems("5 workers x 4 environments, 2 Burgers in 4 m x 4 m, 320x240 pixels")
    unmarked = problems("one environment gave about 500 steps/s")
    assert unmarked and "500 is a measured figure with no" in unmarked[0]
    stale = problems("two workers give 1.75x <!-- bench: learning stage 1, one -->")
    assert stale and "1.75 is not in the row" in stale[0]
    assert len(problems("from 1.66 to 1.74x and 1.3 mm, 1.3 mrad <!-- bench: stage 3 -->")) == 4
    ambiguous = problems("356 steps/s <!-- bench: learning stage -->")
    assert ambiguous and "names 2 rows" in ambiguous[0]
    assert problems("| | speed against 2.5 ms |\n|---|---|\n| 5 ms | 1.73 |") == [
        "p:3: a bare number (1.73) in a table of speeds: give its unit"]
    training = "## Training: make train\n\n346 steps/s\n\n## Speed\n\n346 steps/s\n"
    assert figure_problems("doc/learning.md", training, ROWS) == [
        "doc/learning.md:7: 346 is a measured figure with no <!-- bench: ROW --> marker: take it "
        "from benchmark.md's latest table and name the row, or point there"]
