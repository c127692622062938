#!/usr/bin/env bash
# Set up everything tutorial_turtlebot needs, idempotently: system packages, the Python venv
# (Debian's rospy + PyPI's pybullet and numpy>=2) and the catkin workspace .catkin_ws/.
# Usage: tools/setup.sh               (what `make demo` and `make test` run first)
#        tools/setup.sh --deps-only   (packages and venv only: for use from your own
#                                      ~/catkin_ws, see README)
# Uses /opt/ros/noetic where it exists (Ubuntu 20.04), Debian's ROS packages in /usr otherwise.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
WS="$ROOT/.catkin_ws"
VENV="$WS/venv"
NOETIC=/opt/ros/noetic/setup.bash
PYBULLET_VERSION=3.2.7

say() { printf '[setup] %s\n' "$*"; }
fail() { printf '[setup] ERROR: %s\n' "$*" >&2; exit 1; }

if [ "$(id -u)" -eq 0 ]; then SUDO=(); else SUDO=(sudo); fi

debian_packages() {
  if [ -f "$NOETIC" ]; then
    echo ros-noetic-ros-base ros-noetic-robot-state-publisher ros-noetic-tf2-ros \
         ros-noetic-rostest ros-noetic-image-view ros-noetic-rviz python3-venv python3-pip python3-pytest \
         python3-pil libegl1 libgl1-mesa-dri build-essential cmake
  else
    echo ros-core python3-rospy python3-roslaunch python3-rostest librostest-dev rosbash catkin \
         python3-catkin-pkg python3-geometry-msgs python3-sensor-msgs python3-nav-msgs \
         python3-std-srvs python3-rosgraph-msgs python3-tf2-ros python3-tf2-msgs \
         ros-robot-state-publisher python3-venv python3-pip python3-pytest \
         python3-pil libegl1 libgl1-mesa-dri ros-image-view rviz \
         libgeometry-msgs-dev libnav-msgs-dev libsensor-msgs-dev \
         build-essential cmake ignition-tools libsdformat-dev
  fi
}

install_system() {
  local missing=()
  for pkg in $(debian_packages); do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" \
      || missing+=("$pkg")
  done
  if [ ${#missing[@]} -eq 0 ]; then
    say "system packages: all present"
    return
  fi
  command -v apt-get >/dev/null || fail "apt-get not found; install by hand: ${missing[*]}"
  say "installing system packages: ${missing[*]}"
  "${SUDO[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${SUDO[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
}

install_python() {
  local stamp="$VENV/.tutorial_turtlebot-$PYBULLET_VERSION"
  if [ -f "$stamp" ] && "$VENV/bin/python3" -c 'import rospy, pybullet, numpy' 2>/dev/null; then
    say "python venv: ready ($VENV)"
    return
  fi
  say "creating python venv $VENV (system site packages + pybullet $PYBULLET_VERSION)"
  mkdir -p "$WS"
  /usr/bin/python3 -m venv --system-site-packages --clear "$VENV"
  local numpy="numpy>=2"
  /usr/bin/python3 -c 'import sys; sys.exit(sys.version_info < (3, 9))' || numpy="numpy"
  "$VENV/bin/python3" -m pip install -q --disable-pip-version-check \
    "pybullet==$PYBULLET_VERSION" "$numpy"
  "$VENV/bin/python3" -c 'import rospy, pybullet, numpy; assert pybullet.isNumpyEnabled(), "pybullet built without numpy"' \
    || fail "the venv cannot import rospy, pybullet and numpy together"
  touch "$stamp"
}

link_package() {
  # The workspace's copy of the package: a folder of links to the repository's entries, all
  # but .catkin_ws itself (a link to the whole repository would let rosrun find every script
  # a second time inside .catkin_ws and refuse to pick).
  local pkg="$WS/src/tutorial_turtlebot" entry
  [ -L "$pkg" ] && rm "$pkg"
  mkdir -p "$pkg"
  find "$pkg" -maxdepth 1 -type l ! -exec test -e {} \; -delete   # entries since removed
  for entry in "$ROOT"/* "$ROOT"/.ci; do
    [ -e "$entry" ] || continue
    ln -sfn "$entry" "$pkg/$(basename "$entry")"
  done
}

build_workspace() {
  link_package
  # shellcheck disable=SC1090
  if [ -f "$NOETIC" ]; then set +u; source "$NOETIC"; set -u; fi
  say "building catkin workspace $WS"
  local log="$WS/build.log"
  if ! catkin_make -C "$WS" -DPYTHON_EXECUTABLE="$VENV/bin/python3" \
        -DTUTORIAL_TURTLEBOT_VENV="$VENV" -DCATKIN_ENABLE_TESTING=ON >"$log" 2>&1; then
    tail -n 30 "$log" >&2
    fail "catkin_make failed (whole log: $log)"
  fi
}

case "${1:-}" in
  --deps-only) install_system; install_python
               say "done: packages and $VENV ready; build your workspace as the README says" ;;
  "") install_system; install_python; build_workspace
      say "done: run 'source $WS/devel/setup.bash' for a shell with rosrun/roslaunch/rostest" ;;
  *) fail "usage: tools/setup.sh [--deps-only]" ;;
esac
