"""The house's lint, as a test: pycodestyle at 100 columns and pyflakes over every Python file
of the repository (src/, test/, bench/, tools/ and the thin scripts/), both clean. Both tools
are pinned in the package's venv (tools/setup_plan.py); the second unit-test pass, under
Python 3.8, leaves the lint to the first."""
import importlib
import os
import subprocess
import sys

import pytest

import unit_paths

ROOT = unit_paths.ROOT
FOLDERS = ("src", "test", "bench", "tools")
MAX_LINE = 100


def _scripts():
    """The executables of scripts/: Python files without the .py that pycodestyle looks for."""
    folder = os.path.join(ROOT, "scripts")
    return sorted(os.path.join("scripts", name) for name in os.listdir(folder)
                  if os.path.isfile(os.path.join(folder, name)))


def _lint(tool, *args):
    try:
        importlib.import_module(tool)
    except ImportError:
        if os.path.basename(sys.prefix) == "venv38":
            pytest.skip("the lint runs in the package's own venv; this is the Python 3.8 pass")
        pytest.fail("%s is not installed here: tools/setup.sh installs it in the venv" % tool)
    out = subprocess.run([sys.executable, "-m", tool] + list(args), cwd=ROOT,
                         capture_output=True, text=True, timeout=300)
    return (out.stdout + out.stderr).strip()


def test_pycodestyle_finds_nothing_at_100_columns():
    report = _lint("pycodestyle", "--max-line-length=%d" % MAX_LINE, *FOLDERS, *_scripts())
    assert report == "", "pycodestyle:\n" + report


def test_pyflakes_finds_nothing():
    report = _lint("pyflakes", *FOLDERS, *_scripts())
    assert report == "", "pyflakes:\n" + report


def test_the_lint_sees_a_fault(tmp_path):
    """The two runs report what they should: a long line, an unused import."""
    bad = tmp_path / "bad.py"
    bad.write_text("import os\nx = '%s'\n" % ("y" * MAX_LINE))
    assert "E501" in _lint("pycodestyle", "--max-line-length=%d" % MAX_LINE, str(bad))
    assert "'os' imported but unused" in _lint("pyflakes", str(bad))
