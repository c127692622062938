"""Every module that src/, scripts/ and test/ import is declared in package.xml under its rosdep
key (stdlib and the package's own modules excepted), so that `rosdep install --from-paths src
--ignore-src` installs what the code needs."""
import ast
import importlib.util
import os
import sys
import sysconfig
import xml.etree.ElementTree as ET
import unit_paths

ROOT = unit_paths.ROOT

# import name -> rosdep key (ROS packages are their own key)
KEYS = {
    "yaml": "python3-yaml", "rospkg": "python3-rospkg", "numpy": "python3-numpy",
    "PIL": "python3-pil", "tkinter": "python3-tk", "pytest": "python3-pytest",
    "collada": "python3-collada", "trimesh": "python3-trimesh-pip",
}
# From PyPI only, no rosdep key (tools/setup.sh pip-installs them; package.xml says so).
PIP_ONLY = {"pybullet", "gymnasium"}


def is_stdlib(name):
    if hasattr(sys, "stdlib_module_names"):          # Python 3.10+
        return name in sys.stdlib_module_names and name != "tkinter"
    spec = importlib.util.find_spec(name)           # Python 3.8, 3.9: where it comes from
    if spec is None or name == "tkinter":
        return False
    if name in sys.builtin_module_names:
        return True
    origin = spec.origin or ""
    stdlib = sysconfig.get_paths()["stdlib"]
    return origin in ("built-in", "frozen") or (origin.startswith(stdlib)
                                                and "-packages" not in origin)


def python_files():
    for top in ("src", "scripts", "test"):
        for folder, _, names in os.walk(os.path.join(ROOT, top)):
            for name in names:
                path = os.path.join(folder, name)
                if name.endswith(".py"):
                    yield path
                elif top == "scripts" or "rostest" in folder:
                    with open(path, "rb") as f:
                        first = f.readline()
                    if first.startswith(b"#!") and b"python" in first:
                        yield path


def imported_modules():
    found = {}
    for path in python_files():
        with open(path, encoding="utf-8") as f:
            tree = ast.parse(f.read(), path)
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names = [node.module]
            else:
                continue
            for name in names:
                found.setdefault(name.split(".")[0], set()).add(os.path.relpath(path, ROOT))
    return found


def local_modules():
    """The package's own modules, the tests' helper modules (files beside them), the
    benchmark's (bench/, which tests import too) and the tools' scripts (tools/corpus/,
    tools/peer/)."""
    names = {"tutorial_turtlebot"}
    for top in ("test/unit", "test/rostest", "test"):
        for name in os.listdir(os.path.join(ROOT, top)):
            stem = name[:-3] if name.endswith(".py") else name
            names.add(stem)
    for scripts in ("bench", os.path.join("tools", "corpus"), os.path.join("tools", "peer")):
        names.update(f[:-3] for f in os.listdir(os.path.join(ROOT, scripts))
                     if f.endswith(".py"))
    for folder, _, files in os.walk(os.path.join(ROOT, "test")):
        names.update(f[:-3] for f in files if f.endswith(".py"))
    return names


def declared():
    root = ET.parse(os.path.join(ROOT, "package.xml")).getroot()
    return {e.text.strip() for e in root if e.tag.endswith("depend") and e.text}


def test_every_import_is_declared_in_package_xml():
    deps, local = declared(), local_modules()
    missing = []
    for module, files in sorted(imported_modules().items()):
        if is_stdlib(module) or module in local or module in PIP_ONLY:
            continue
        key = KEYS.get(module, module)
        if key not in deps:
            missing.append("%s (rosdep key %s), imported by %s" % (module, key, sorted(files)[0]))
    assert not missing, "not in package.xml: " + "; ".join(missing)


def test_the_camera_viewer_and_meshes_are_declared():
    deps = declared()
    for key in ("python3-tk", "python3-pil", "python3-collada", "python3-trimesh-pip",
                "python3-yaml", "python3-rospkg", "roslib", "genmsg", "graphviz"):
        assert key in deps, key
