"""The optional extras the tests here need (tools/install_extra.sh), installed on first use."""
import importlib
import os
import subprocess

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def ensure_extra(extra: str, module: str, timeout: float):
    """``module``, installed first with extra ``extra`` if missing (imported by name: an
    extra, not in package.xml); the test is skipped, in one line, when PyPI is unreachable."""
    try:
        return importlib.import_module(module)
    except ImportError:
        pass
    done = subprocess.run(["bash", os.path.join(ROOT, "tools", "install_extra.sh"), extra],
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                          timeout=timeout)
    if done.returncode == 3:
        pytest.skip("PyPI is unreachable, so the %s extra could not be installed" % extra)
    assert done.returncode == 0, done.stdout
    importlib.invalidate_caches()
    return importlib.import_module(module)
