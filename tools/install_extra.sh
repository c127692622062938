#!/usr/bin/env bash
# Install an optional extra into the project's venv (catkin_ws/venv), on first use.
#
#   bash tools/install_extra.sh ray     # Ray, for learning/ray_actors.py (about 250 MB)
#   bash tools/install_extra.sh train   # stable-baselines3, CPU-only torch, matplotlib
#                                       # for tools/train_stage1.py (about 800 MB)
#   bash tools/install_extra.sh nav     # gmapping, amcl, map_server, move_base, built from
#                                       # source in catkin_ws/nav (tools/nav_extra/build.sh)
#
# None is part of tools/setup.sh: the simulator, the lab and the unit tests need none.
# Versions are pinned. A second run checks the pins and installs nothing.
# Exit status: 0 installed (or already there), 2 usage, 3 PyPI unreachable, 1 any other failure.
#
# torch: PyPI's Linux x86_64 wheels of torch are CUDA builds that pull several GB of nvidia-*
# packages. The extra asks for torch 2.13.0, which pip takes from the CPU build that lies in
# pip's find-links folder where the machine has one (190 MB wheel); elsewhere pip takes PyPI's
# 2.13.0 and its CUDA packages. It is installed without its setuptools>=77 requirement (only
# torch's C++ extension builder needs it), so that the venv's setuptools, which catkin uses,
# stays as it is.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="${TUTORIAL_TURTLEBOT_VENV:-$ROOT/catkin_ws/venv}"
PY="$VENV/bin/python3"

# Pinned: what each extra installs (top-level and, for train, every dependency the venv lacks).
RAY_PINS=(ray==2.58.0)
TRAIN_PINS=(stable-baselines3==2.9.2 torch==2.13.0 matplotlib==3.11.2
            filelock==4.3.1 sympy==1.14.0 mpmath==1.3.0 networkx==3.6.1 jinja2==3.1.6
            markupsafe==3.0.4 fsspec==2026.9.0 contourpy==1.3.3 cycler==0.12.1
            fonttools==4.68.0 kiwisolver==1.5.1)
# What must import afterwards.
RAY_CHECK="import ray"
TRAIN_CHECK="import torch, stable_baselines3, matplotlib"

usage() {
    echo "usage: bash tools/install_extra.sh ray|train|nav" >&2
    exit 2
}

[ $# -eq 1 ] || usage
# nav is no pip extra: ROS packages built from source (tools/nav_extra/build.sh says how).
[ "$1" != nav ] || exec bash "$ROOT/tools/nav_extra/build.sh"
case "$1" in
    ray) pins=("${RAY_PINS[@]}"); check="$RAY_CHECK"; nodeps=() ;;
    train) pins=("${TRAIN_PINS[@]}"); check="$TRAIN_CHECK"; nodeps=(--no-deps) ;;
    *) usage ;;
esac
extra="$1"

if [ ! -x "$PY" ]; then
    echo "install_extra: no venv at $VENV: run 'make setup' (tools/setup.sh) first" >&2
    exit 1
fi

# Already there at the pinned versions? (a local label such as +cpu matches its version)
if "$PY" - "${pins[@]}" <<'EOF'
import sys
from importlib import metadata
for pin in sys.argv[1:]:
    name, version = pin.split("==")
    try:
        have = metadata.version(name)
    except metadata.PackageNotFoundError:
        sys.exit(1)
    if have.split("+")[0] != version:
        sys.exit(1)
EOF
then
    if "$PY" -c "$check" 2>/dev/null; then
        echo "install_extra: $extra is installed (${pins[*]})"
        exit 0
    fi
fi

site_size() {
    du -sm "$VENV/lib" 2>/dev/null | cut -f1
}

before=$(site_size)
started=$(date +%s)
echo "install_extra: installing $extra into $VENV: ${pins[*]}"
if ! "$PY" -m pip install --quiet --disable-pip-version-check "${nodeps[@]}" "${pins[@]}"; then
    if ! "$PY" -c "import socket; socket.create_connection(('pypi.org', 443), 10).close()" \
            2>/dev/null; then
        echo "install_extra: PyPI (pypi.org:443) is unreachable; $extra not installed" >&2
        exit 3
    fi
    echo "install_extra: pip failed to install $extra" >&2
    exit 1
fi
if ! "$PY" -c "$check"; then
    echo "install_extra: $extra installed but '$check' fails" >&2
    exit 1
fi
echo "install_extra: $extra installed in $(( $(date +%s) - started )) s," \
     "+$(( $(site_size) - before )) MB in the venv"
