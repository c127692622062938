"""tools/try_platform.sh's own words: a wrong call gets one line. (The whole run, a Debian 13
root with `make test` inside, is CI's second pass: .ci/run.)"""
import os
import subprocess
import unit_paths

ROOT = unit_paths.ROOT
SCRIPT = os.path.join(ROOT, "tools", "try_platform.sh")


def run(*args):
    return subprocess.run(["bash", SCRIPT] + list(args), stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, universal_newlines=True, timeout=60)


def test_an_unknown_platform_is_one_line_naming_the_known_ones():
    done = run("debian99")
    assert done.returncode == 1 and done.stdout == ""
    (line,) = done.stderr.splitlines()
    assert "unknown platform 'debian99'" in line and "debian13" in line


def test_an_unknown_option_is_one_line():
    done = run("debian13", "--frobnicate")
    assert done.returncode == 1
    (line,) = done.stderr.splitlines()
    assert "unknown option '--frobnicate'" in line


def test_help_says_how_to_call_it():
    done = run("--help")
    assert done.returncode == 0
    assert "tools/try_platform.sh debian13" in done.stdout and "--root-only" in done.stdout
