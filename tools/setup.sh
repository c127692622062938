#!/usr/bin/env bash
# Set up everything tutorial_turtlebot needs, idempotently: system packages, the Python venv
# (the system's rospy + PyPI's pybullet and numpy) and the catkin workspace catkin_ws/.
# Usage: tools/setup.sh               (what `make demo` runs first)
#        tools/setup.sh --test        (the same plus the Python 3.8 venv for the unit tests:
#                                      what `make test` runs first)
#        tools/setup.sh --deps-only   (packages and venv only: for use from your own
#                                      ~/catkin_ws, see README)
# What to install is decided first, before anything is installed, by tools/setup_plan.py
# (`python3 tools/setup_plan.py` shows it): Debian's ROS 1 packages in /usr on Debian 12+ and
# Ubuntu 22.04+, ROS Noetic's own packages where /opt/ros/noetic exists; anything else is
# refused with one line saying what is needed.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# The workspace, catkin_ws/ in the clone (not hidden: rosbash's tab completion skips every path
# with a hidden folder in it). TUTORIAL_TURTLEBOT_WS moves it: for the set-up's own tests.
WS="${TUTORIAL_TURTLEBOT_WS:-$ROOT/catkin_ws}"
VENV="$WS/venv"
VENV38="$WS/venv38"
SYS_PYTHON=/usr/bin/python3
STAMP_NAME=.tutorial_turtlebot-stamp

say() { printf '[setup] %s\n' "$*"; }
fail() { printf '[setup] ERROR: %s\n' "$*" >&2; exit 1; }

mode=${1:-}
case "$mode" in
  ""|--test|--deps-only) ;;
  *) fail "usage: tools/setup.sh [--test|--deps-only]" ;;
esac

if [ "$(id -u)" -eq 0 ]; then
  SUDO=()
elif command -v sudo >/dev/null; then
  SUDO=(sudo)
else
  SUDO=(false)   # fails at the first install with the message below
fi

apt_run() {
  # apt-get through sudo where needed; its output goes to a log shown only when it fails.
  local log="${TMPDIR:-/tmp}/tutorial_turtlebot-apt.$$.log"
  if [ "${SUDO[0]:-}" = false ]; then
    fail "not root and no sudo: run as root, or install sudo, to let the set-up use apt-get"
  fi
  if ! "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get "$@" >"$log" 2>&1; then
    tail -n 20 "$log" >&2
    rm -f "$log"
    fail "apt-get $1 failed (its last lines are above)"
  fi
  rm -f "$log"
}

if [ -d "$ROOT/.catkin_ws" ] && [ "$mode" != --deps-only ]; then
  # Earlier versions kept the workspace in the hidden .catkin_ws/, where rosbash's completion never looks.
  say "removing the old workspace .catkin_ws/ (it is catkin_ws/ now, where tab completion finds it)"
  rm -rf "$ROOT/.catkin_ws"
fi

# --- the plan ------------------------------------------------------------------------------------

if [ ! -x "$SYS_PYTHON" ]; then
  # The plan is a Python program; a bare container may lack Python itself.
  command -v apt-get >/dev/null \
    || fail "no $SYS_PYTHON and no apt-get: tools/setup.sh needs Debian 12+, Ubuntu 22.04+, or Ubuntu 20.04 with ROS Noetic"
  say "installing python3 (the set-up's plan is a Python program)"
  apt_run update -qq
  apt_run install -y -qq --no-install-recommends python3
fi

APT_UPDATED=0
has_candidate() {
  [[ "$(apt-cache policy "$1" 2>/dev/null || true)" == *"Candidate: "[0-9]* ]]
}
# TUTORIAL_TURTLEBOT_PLAN_ARGS: setup_plan.py options that pretend to be another machine
# (--os-release FILE --noetic yes|no --python X.Y ...): for the tests of the refusals.
read -r -a PLAN_ARGS <<<"${TUTORIAL_TURTLEBOT_PLAN_ARGS:-}"
plan() { "$SYS_PYTHON" "$ROOT/tools/setup_plan.py" --shell "${PLAN_ARGS[@]}" "$@"; }
PLAN_OUTPUT=$(plan) || exit 1    # a refusal: setup_plan.py said why, in one line
eval "$PLAN_OUTPUT"
if [ "$PLAN_APT_UPDATE_FIRST" = 1 ]; then
  # apt has no package lists yet, so whether it offers ROS 1 is not known: read them, ask again.
  say "reading apt's package lists (apt-get update)"
  apt_run update -qq
  APT_UPDATED=1
  PLAN_OUTPUT=$(plan --ros1-apt "$(has_candidate python3-rospy && echo yes || echo no)") \
    || exit 1
  eval "$PLAN_OUTPUT"
fi
say "platform: $PLAN_PLATFORM"
if [ -n "$PLAN_NOTES" ]; then
  while IFS= read -r note; do say "note: $note"; done <<<"$PLAN_NOTES"
fi
if [ -n "$PLAN_ROS_SETUP" ]; then
  # Before any check: Noetic's rospy is only on PYTHONPATH once this is sourced.
  set +eu
  # shellcheck disable=SC1090
  source "$PLAN_ROS_SETUP"
  set -eu
fi

# --- system packages -----------------------------------------------------------------------------

not_installed() {
  # The packages among "$@" that dpkg does not have installed.
  local installed
  installed=$(dpkg-query -W -f='${Package} ${Status}\n' "$@" 2>/dev/null \
                | awk '/ install ok installed$/ {print $1}' || true)
  local pkg
  for pkg in "$@"; do
    grep -qxF "$pkg" <<<"$installed" || printf '%s\n' "$pkg"
  done
}

without_unavailable_optional() {
  # "$@" less the optional packages that the apt sources do not offer (one line says so).
  local pkg skipped=()
  for pkg in "$@"; do
    if [[ " $PLAN_APT_OPTIONAL " == *" $pkg "* ]] && ! has_candidate "$pkg"; then
      skipped+=("$pkg")
    else
      printf '%s\n' "$pkg"
    fi
  done
  if [ ${#skipped[@]} -gt 0 ]; then
    say "not offered by this system's apt sources, skipped: ${skipped[*]}" >&2
  fi
}

install_system() {
  local missing=() wanted=()
  # shellcheck disable=SC2086  # PLAN_APT is a list of package names
  mapfile -t missing < <(not_installed $PLAN_APT)
  if [ ${#missing[@]} -gt 0 ]; then
    mapfile -t wanted < <(without_unavailable_optional "${missing[@]}" 2>/dev/null)
  fi
  if [ ${#wanted[@]} -eq 0 ]; then
    say "system packages: all present${missing[*]:+ (not offered here: ${missing[*]})}"
    return
  fi
  [ "$APT_UPDATED" = 1 ] || apt_run update -qq
  APT_UPDATED=1
  mapfile -t wanted < <(without_unavailable_optional "${missing[@]}")
  say "installing system packages: ${wanted[*]}"
  apt_run install -y -qq --no-install-recommends "${wanted[@]}"
}

# --- the Python venvs ----------------------------------------------------------------------------

venv_problem() {
  # venv_problem VENV STAMP CHECK: why VENV cannot be completed in place (nothing if it can,
  # or is absent).
  # A venv whose pyvenv.cfg is gone (an interrupted rm -rf) runs as the system Python, and pip
  # then refuses or writes outside it: such a venv is made anew, never patched.
  local venv=$1 prefix
  [ -e "$venv" ] || return 0
  if [ ! -f "$venv/pyvenv.cfg" ]; then
    echo "it has no pyvenv.cfg"
  elif [ ! -x "$venv/bin/python3" ]; then
    echo "it has no bin/python3"
  elif ! prefix=$("$venv/bin/python3" -c 'import sys; print(sys.prefix)' 2>/dev/null); then
    echo "its bin/python3 does not run"
  elif [ "$(cd "$venv" && pwd -P)" != "$(cd "$prefix" 2>/dev/null && pwd -P)" ]; then
    echo "its bin/python3 is not the venv's (its prefix is $prefix)"
  elif [ -f "$venv/$STAMP_NAME" ] && [ "$(cat "$venv/$STAMP_NAME")" = "$2" ] \
       && ! "$venv/bin/python3" -c "$3" >/dev/null 2>&1; then
    echo "it is stamped ready but cannot import its packages"
  fi
}

heal_venv() {
  # heal_venv VENV STAMP CHECK: a broken VENV is removed, with one line saying why.
  local problem
  problem=$(venv_problem "$1" "$2" "$3")
  if [ -n "$problem" ]; then
    say "python venv $1 is broken ($problem): making it anew"
    rm -rf "$1"
  fi
}

venv_ready() {
  # venv_ready VENV STAMP CHECK: stamped for this plan, and the import check passes.
  [ -f "$1/$STAMP_NAME" ] && [ "$(cat "$1/$STAMP_NAME")" = "$2" ] \
    && "$1/bin/python3" -c "$3" >/dev/null 2>&1
}

venv_base() {
  # venv_base VENV PYTHON [venv options]: a venv with a working pip, made anew only if needed.
  local venv=$1 python=$2
  shift 2
  if "$venv/bin/python3" -m pip --version >/dev/null 2>&1 \
     && [ "$("$venv/bin/python3" -c 'import sys; print(sys.version_info[:2])')" \
          = "$("$python" -c 'import sys; print(sys.version_info[:2])')" ]; then
    return
  fi
  mkdir -p "$(dirname "$venv")"
  "$python" -m venv --clear "$@" "$venv" || fail "$python -m venv $venv failed"
}

pip_install() {
  local venv=$1
  shift
  "$venv/bin/python3" -m pip install -q --disable-pip-version-check "$@" \
    || fail "pip install $* failed in $venv"
}

pybullet_wheel() {
  # Where there is no wheel on PyPI (Python 3.12+, ARM): build pybullet once, keep the wheel in
  # the user's cache, and print that folder for pip's --find-links. A second venv (make clean,
  # another clone) installs the kept wheel in seconds.
  local dir="${XDG_CACHE_HOME:-$HOME/.cache}/tutorial_turtlebot/wheels/$PLAN_WHEEL_CACHE"
  if compgen -G "$dir/pybullet-*.whl" >/dev/null; then
    say "pybullet: the wheel built before ($dir)" >&2
  else
    say "building pybullet from source once: about 5 minutes on 2 cores; kept in $dir" >&2
    local build log
    build=$(mktemp -d)
    log="$build/build.log"
    if ! CFLAGS="$PLAN_BUILD_CFLAGS ${CFLAGS:-}" "$VENV/bin/python3" -m pip wheel -q \
          --disable-pip-version-check --no-deps --no-build-isolation -w "$build" \
          "$(grep -oE 'pybullet==[^ ]+' <<<"$PLAN_PIP")" >"$log" 2>&1; then
      grep -E 'error|Error' "$log" | tail -n 5 >&2
      fail "building the pybullet wheel failed (whole log: $log)"
    fi
    mkdir -p "$dir"
    mv "$build"/pybullet-*.whl "$dir"/
    rm -rf "$build"
  fi
  printf '%s\n' "$dir"
}

patch_xacro() {
  # PyPI's xacro 1.13.3 (ROS 1's) writes attributes through minidom's private _write_data, which
  # Python 3.13 gave a third argument (attr). xacro's own later releases pass attr=True; the
  # same one-line change is made here where the Python needs it, and said once.
  "$1" - <<'PY' || fail "patching xacro for this Python failed"
import inspect, os, sys, xml.dom.minidom, xacro.xmlutils as m
if len(inspect.signature(xml.dom.minidom._write_data).parameters) >= 3:
    old = "xml.dom.minidom._write_data(writer, attrs[a_name].value)"
    path = m.__file__
    text = open(path).read()
    if old in text:
        open(path, "w").write(text.replace(old, old[:-1] + ", True)"))
        for cached in os.listdir(os.path.join(os.path.dirname(path), "__pycache__")):
            if cached.startswith("xmlutils."):
                os.remove(os.path.join(os.path.dirname(path), "__pycache__", cached))
        print("[setup] xacro 1.13.3 patched for Python %d.%d's minidom (attr=True, one line of %s)"
              % (sys.version_info[:2] + (path,)))
PY
}

MAIN_CHECK='import rospy, pybullet, numpy, trimesh, collada, xacro, gymnasium
assert pybullet.isNumpyEnabled(), "pybullet was built without numpy"'

install_python() {
  if venv_ready "$VENV" "$PLAN_STAMP" "$MAIN_CHECK"; then
    say "python venv: ready ($VENV)"
    return
  fi
  heal_venv "$VENV" "$PLAN_STAMP" "$MAIN_CHECK"
  # No stamp until the check below passes: a run that fails half-way leaves a venv that the
  # next run completes (or, if it broke, makes anew), never one it takes for ready.
  rm -f "$VENV/$STAMP_NAME"
  say "python venv $VENV: $PLAN_STAMP"
  venv_base "$VENV" "$SYS_PYTHON" --system-site-packages
  local first=() pkgs=() flags=()
  read -r -a first <<<"$PLAN_PIP_FIRST"
  read -r -a pkgs <<<"$PLAN_PIP"
  read -r -a flags <<<"$PLAN_PIP_FLAGS"
  [ ${#first[@]} -eq 0 ] || pip_install "$VENV" "${first[@]}"
  if [ "$PLAN_PYBULLET" = source ]; then
    local wheels
    wheels=$(pybullet_wheel) || exit 1
    flags+=(--find-links "$wheels")
  fi
  pip_install "$VENV" "${flags[@]}" "${pkgs[@]}"
  patch_xacro "$VENV/bin/python3"
  local error
  if ! error=$("$VENV/bin/python3" -c "$MAIN_CHECK" 2>&1); then
    fail "the venv cannot import rospy, pybullet, numpy, the mesh readers and gymnasium together: $(tail -n 1 <<<"$error")"
  fi
  printf '%s\n' "$PLAN_STAMP" >"$VENV/$STAMP_NAME"
}

PY38_CHECK='import rospy, genpy, pybullet, numpy, pytest, yaml, PIL, trimesh, collada, gymnasium
assert pybullet.isNumpyEnabled(), "pybullet was built without numpy"'

install_python38() {
  # make test also runs the unit tests under Python 3.8 (ROS Noetic's), where one exists.
  local out
  out=$("$SYS_PYTHON" "$ROOT/tools/setup_plan.py" --py38 --shell) || fail "setup_plan.py --py38 failed"
  eval "$out"
  if [ -z "$PY38_PYTHON" ]; then
    say "python 3.8 venv: skipped, $PY38_SKIP"
    printf '%s\n' "$PY38_SKIP" >"$WS/venv38.skipped"
    return
  fi
  rm -f "$WS/venv38.skipped"
  local stamp="python $PY38_PYTHON: pip install $PY38_PIP; .pth $PY38_PTH"
  if venv_ready "$VENV38" "$stamp" "$PY38_CHECK"; then
    say "python 3.8 venv: ready ($VENV38)"
    return
  fi
  heal_venv "$VENV38" "$stamp" "$PY38_CHECK"
  rm -f "$VENV38/$STAMP_NAME"
  say "python 3.8 venv $VENV38: $PY38_PYTHON, $PY38_PIP"
  venv_base "$VENV38" "$PY38_PYTHON"
  local pkgs=()
  read -r -a pkgs <<<"$PY38_PIP"
  # Wheels only: the compiled modules must be built for 3.8, not taken from the system.
  # pycollada for 3.8 (0.8) exists only as source: pure Python, built in a second.
  pip_install "$VENV38" --only-binary=:all: --no-binary=pycollada "${pkgs[@]}"
  local site
  site=$("$VENV38/bin/python3" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
  # Appended to sys.path (after the venv's own packages): the system's pure-Python ROS modules.
  printf '%s\n' "$PY38_PTH" >"$site/tutorial_turtlebot_system_ros.pth"
  local error
  if ! error=$("$VENV38/bin/python3" -c "$PY38_CHECK" 2>&1); then
    fail "the python 3.8 venv cannot import what the unit tests need: $(tail -n 1 <<<"$error")"
  fi
  printf '%s\n' "$stamp" >"$VENV38/$STAMP_NAME"
}

# --- the catkin workspace ------------------------------------------------------------------------

link_package() {
  # The workspace's copy of the package: a folder of links to the repository's entries, all
  # but catkin_ws itself (a link to the whole repository would let rosrun find every script
  # a second time inside catkin_ws and refuse to pick). catkin and rospack stop at its
  # package.xml, so msgs/gazebo_msgs inside it is not found a second time.
  local pkg="$WS/src/tutorial_turtlebot" entry
  [ -L "$pkg" ] && rm "$pkg"
  mkdir -p "$pkg"
  find "$pkg" -maxdepth 1 -type l ! -exec test -e {} \; -delete   # entries since removed
  for entry in "$ROOT"/* "$ROOT"/.ci; do
    if [ ! -e "$entry" ] || [ "$entry" = "$WS" ]; then continue; fi
    ln -sfn "$entry" "$pkg/$(basename "$entry")"
  done
}

link_stand_ins() {
  # Packages the repository carries for systems that lack them (Debian's and Ubuntu's ROS 1):
  # msgs/gazebo_msgs (the messages, built by catkin_make) and ros_shims/* (manifests for
  # Debian's manifest-less Python packages). Linked into the workspace's src/ there; on Noetic,
  # whose own packages are installed instead, links left from before are removed.
  local dir name link
  for dir in "$ROOT"/msgs/*/ "$ROOT"/ros_shims/*/; do
    [ -f "$dir/package.xml" ] || continue
    dir=${dir%/}
    name=$(basename "$dir")
    link="$WS/src/$name"
    if [ "$PLAN_GAZEBO_MSGS" = repo ]; then
      ln -sfn "$dir" "$link"
    elif [ -L "$link" ]; then
      rm "$link"
    fi
  done
  # links whose package was removed from the repository
  find "$WS/src" -maxdepth 1 -type l ! -name tutorial_turtlebot ! -exec test -e {} \; -delete
}

workspace_inputs() {
  # A digest of everything catkin_make reads: the build files and hooks of every package in
  # src/, the messages, the rostest files it globs, what is linked, and its own command line.
  # The Python code is not in it: the devel space points at src/, so an edit needs no build.
  # The CMakeLists.txt of the source folder is left out: catkin_make makes it, so a digest
  # taken before the first build would differ from the next one's and build once more.
  local args=$1
  {
    printf '%s\n' "$args"
    (cd "$WS/src" && find -L . -maxdepth 1 ! -name CMakeLists.txt | sort)
    (cd "$ROOT" && find CMakeLists.txt package.xml setup.py env-hooks msgs ros_shims \
        test/rostest -type f \( ! -path 'test/rostest/*' -o -name '*.test' \) -print0 \
        | sort -z | xargs -0 sha256sum)
  } | sha256sum | cut -d' ' -f1
}

build_workspace() {
  link_package
  link_stand_ins
  # The workspace sits inside the package's folder: catkin_lint (and catkin, from a workspace
  # above the clone) must not take its build and devel files for the package's own.
  [ -f "$WS/CATKIN_IGNORE" ] || printf 'the workspace of tools/setup.sh: no sources here\n' >"$WS/CATKIN_IGNORE"
  # PYTHON_EXECUTABLE for catkin's FindPythonInterp (Debian 12), Python_EXECUTABLE for its
  # FindPython (Debian 13): the relays of the scripts in devel/lib are written for that Python.
  local args=(-DPYTHON_EXECUTABLE="$VENV/bin/python3" -DPython_EXECUTABLE="$VENV/bin/python3"
              -DTUTORIAL_TURTLEBOT_VENV="$VENV" -DCATKIN_ENABLE_TESTING=ON)
  local stamp="$WS/build/$STAMP_NAME" inputs
  inputs=$(workspace_inputs "${args[*]}")
  if [ -f "$WS/devel/setup.bash" ] && [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$inputs" ]; then
    say "catkin workspace: built, nothing changed ($WS)"
    return
  fi
  say "building catkin workspace $WS"
  local log="$WS/build.log"
  rm -f "$stamp"
  if ! catkin_make -C "$WS" "${args[@]}" >"$log" 2>&1; then
    tail -n 30 "$log" >&2
    fail "catkin_make failed (whole log: $log)"
  fi
  printf '%s\n' "$inputs" >"$stamp"
}

compile_python() {
  # Byte-compile the package and the workspace's generated messages (gazebo_msgs ...) here,
  # at every set-up (what is up to date is only looked at): a Python that writes no bytecode
  # itself (PYTHONDONTWRITEBYTECODE, a read-only clone) would compile some 200 modules again
  # at every start of the sim, a quarter of a second of its start-up. Python checks each .pyc
  # against its source, so an edit made since is compiled afresh, as without this step.
  if ! "$VENV/bin/python3" -m compileall -q -j0 "$ROOT/src/tutorial_turtlebot" \
      "$WS/devel/lib/python3/dist-packages" >/dev/null; then
    say "could not byte-compile every module (Python compiles them at import instead)"
  fi
}

deps_only_hint() {
  # From your own ~/catkin_ws/src: the stand-ins (gazebo_msgs, ...) must sit beside the package
  # to be found; linked there when the clone is in a src/ folder, else the line says how.
  [ "$PLAN_GAZEBO_MSGS" = repo ] || return 0
  local src dir name
  src=$(dirname "$ROOT")
  for dir in "$ROOT"/msgs/*/ "$ROOT"/ros_shims/*/; do
    [ -f "$dir/package.xml" ] || continue
    dir=${dir%/}
    name=$(basename "$dir")
    if [ -e "$src/$name" ] || [ -L "$src/$name" ]; then
      continue
    elif [ "$(basename "$src")" = src ]; then
      ln -s "$(basename "$ROOT")/${dir#"$ROOT"/}" "$src/$name"
      say "linked $src/$name -> $(basename "$ROOT")/${dir#"$ROOT"/} (this system has no $name)"
    else
      say "this system has no $name: link it into your workspace's src/: ln -s $dir ~/catkin_ws/src/$name"
    fi
  done
}

case "$mode" in
  --deps-only) install_system; install_python; deps_only_hint
               say "done: packages and $VENV ready; build your workspace as the README says" ;;
  --test) install_system; install_python; install_python38; build_workspace; compile_python
          say "done: run 'source $WS/devel/setup.bash' for a shell with rosrun/roslaunch/rostest" ;;
  "") install_system; install_python; build_workspace; compile_python
      say "done: run 'source $WS/devel/setup.bash' for a shell with rosrun/roslaunch/rostest" ;;
esac
