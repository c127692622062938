#!/usr/bin/env bash
# The navigation extra (tools/install_extra.sh nav): gmapping, amcl, map_server, move_base and
# the planners, recoveries and costmap move_base loads, for the SLAM and Navigation chapters
# (doc/slam.md, doc/navigation.md).
#
# Debian (12, 13): none of these is packaged. They are built from source, each repository at the
# commit tools/nav_extra/pins names, with the patches in tools/nav_extra/patches/ (the smallest
# ports to Debian's Boost and pluginlib, one line each saying why), in a workspace of their own,
# catkin_ws/nav, overlaid on the package's catkin_ws/devel. Sources: $NAV_SRC/<repository>
# where NAV_SRC is set (a machine without GitHub, such as CI), else the pinned archives from
# codeload.github.com, kept in catkin_ws/nav/download. A second run, with nothing changed,
# builds nothing.
# Ubuntu with ROS Noetic: the distribution's packages (ros-noetic-*) are installed instead.
#
# Ends by printing the line that gives a shell where rosrun finds this package and the extra.
# NAV_JOBS: compile jobs (default: every core; make test builds with one beside the unit tests).
# Exit status: 0 built (or already built), 1 any failure, 3 the sources cannot be had.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
HERE="$ROOT/tools/nav_extra"
WS="${TUTORIAL_TURTLEBOT_WS:-$ROOT/catkin_ws}"
NAV_WS="$WS/nav"
STAMP_NAME=.tutorial_turtlebot-stamp

say() { printf '[nav] %s\n' "$*"; }
fail() { printf '[nav] ERROR: %s\n' "$1" >&2; exit "${2:-1}"; }

# The packages built, by repository (folders in its tree; . the tree itself).
declare -A PKGS=(
  [openslam_gmapping]="."
  [slam_gmapping]="gmapping"
  [navigation]="amcl map_server move_base costmap_2d nav_core navfn base_local_planner
                dwa_local_planner clear_costmap_recovery rotate_recovery voxel_grid"
)
# Debian's packages they build against.
DEBIAN_APT=(libmove-base-msgs-dev libangles-dev liblaser-geometry-dev libmap-msgs-dev
            libtf2-sensor-msgs-dev libvisualization-msgs-dev libdiagnostic-updater-dev
            libdynamic-reconfigure-config-init-mutex-dev libnodeletlib-dev librosbag-dev
            ros-cmake-modules libsdl1.2-dev libsdl-image1.2-dev libyaml-cpp-dev libbullet-dev
            libboost-program-options-dev g++ make cmake)
NOETIC_APT=(ros-noetic-gmapping ros-noetic-amcl ros-noetic-map-server ros-noetic-move-base
            ros-noetic-navfn ros-noetic-dwa-local-planner ros-noetic-clear-costmap-recovery
            ros-noetic-rotate-recovery)

if [ "$(id -u)" -eq 0 ]; then SUDO=(); elif command -v sudo >/dev/null; then SUDO=(sudo);
else SUDO=(false); fi

apt_install() {
  # apt_install PKG...: those not installed yet, through sudo where needed.
  local missing=() pkg
  for pkg in "$@"; do
    dpkg-query -W -f='${Status}\n' "$pkg" 2>/dev/null | grep -q ' installed$' \
      || missing+=("$pkg")
  done
  [ ${#missing[@]} -gt 0 ] || return 0
  [ "${SUDO[0]:-}" != false ] || fail "not root and no sudo: install ${missing[*]} first"
  say "installing system packages: ${missing[*]}"
  local log="${TMPDIR:-/tmp}/tutorial_turtlebot-nav-apt.$$.log"
  if ! "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
        --no-install-recommends "${missing[@]}" >"$log" 2>&1; then
    "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq >/dev/null 2>&1 || true
    "${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
        --no-install-recommends "${missing[@]}" >"$log" 2>&1 \
      || { tail -n 5 "$log" >&2; fail "apt-get install ${missing[*]} failed"; }
  fi
  rm -f "$log"
}

[ -f "$WS/devel/setup.bash" ] || fail "no $WS/devel: run 'make setup' (tools/setup.sh) first"

if [ -f /opt/ros/noetic/setup.bash ]; then
  apt_install "${NOETIC_APT[@]}"
  say "nav: ROS Noetic's packages are installed"
  say "a shell with both: source $WS/devel/setup.bash"
  exit 0
fi

apt_install "${DEBIAN_APT[@]}"

# --- the sources -----------------------------------------------------------------------------

declare -A PIN OWNER
while read -r folder owner_repo commit _; do
  [[ -z "$folder" || "$folder" == \#* ]] && continue
  PIN[$folder]=$commit
  OWNER[$folder]=$owner_repo
done <"$HERE/pins"
REPOS=(openslam_gmapping slam_gmapping navigation)

source_tree() {
  # source_tree REPO: the folder holding REPO's tree at its pin.
  local repo=$1
  if [ -n "${NAV_SRC:-}" ]; then
    [ -d "$NAV_SRC/$repo" ] || fail "NAV_SRC=$NAV_SRC has no folder $repo" 3
    printf '%s\n' "$NAV_SRC/$repo"
    return
  fi
  local dir="$NAV_WS/download/$repo-${PIN[$repo]}"
  if [ ! -d "$dir" ]; then
    local url="https://codeload.github.com/${OWNER[$repo]}/tar.gz/${PIN[$repo]}"
    command -v curl >/dev/null || fail "no curl to download $url: install curl (or set NAV_SRC)"
    say "downloading $url" >&2
    mkdir -p "$dir.part"
    curl -fsSL "$url" | tar -xz -C "$dir.part" --strip-components=1 \
      || { rm -rf "$dir.part"; fail "cannot download $url (or set NAV_SRC)" 3; }
    mv "$dir.part" "$dir"
  fi
  printf '%s\n' "$dir"
}

# catkin_make's command line: the overlay's Python is the system's (ROS' C++ code generators run
# with it), and /usr/bin comes first on PATH so that no venv's python3 is taken.
# The package's workspace holds a manifest-only dynamic_reconfigure (ros_shims/): CMake is
# pointed at Debian's, which has the code generator.
DYNRECONF_DIR=$(dirname "$(dpkg -L libdynamic-reconfigure-config-init-mutex-dev 2>/dev/null \
                           | grep -m 1 '/dynamic_reconfigureConfig.cmake$' || echo /none/x)")
ARGS=(-DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython_EXECUTABLE=/usr/bin/python3
      -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=OFF
      -Ddynamic_reconfigure_DIR="$DYNRECONF_DIR")

inputs() {
  # A digest of what the build reads: the pins (the sources, wherever they lie), the patches,
  # the packages and the command line.
  {
    printf '%s\n' "${ARGS[*]}" "$WS" "${PKGS[*]}"
    cat "$HERE/pins" "$HERE"/patches/*.patch
  } | sha256sum | cut -d' ' -f1
}

STAMP="$NAV_WS/build/$STAMP_NAME"
DIGEST=$(inputs)
if [ -f "$NAV_WS/devel/setup.bash" ] && [ -f "$STAMP" ] && [ "$(cat "$STAMP")" = "$DIGEST" ]; then
  say "nav is built, nothing changed ($NAV_WS)"
  say "a shell with both: source $NAV_WS/devel/setup.bash"
  exit 0
fi

declare -A TREE
for repo in "${REPOS[@]}"; do TREE[$repo]=$(source_tree "$repo"); done

# The workspace's sources: a copy of the packages built (mtimes kept, so a rebuild after a new
# patch compiles only what changed), then the patches.
rm -rf "$NAV_WS/src"
mkdir -p "$NAV_WS/src"
for repo in "${REPOS[@]}"; do
  read -r -a pkgs <<<"$(tr '\n' ' ' <<<"${PKGS[$repo]}")"
  for pkg in "${pkgs[@]}"; do
    [ -f "${TREE[$repo]}/$pkg/package.xml" ] \
      || fail "${TREE[$repo]} has no $pkg/package.xml: not ${OWNER[$repo]} at ${PIN[$repo]}?"
    dest="$NAV_WS/src/$repo/$pkg"
    mkdir -p "$dest"
    cp -a "${TREE[$repo]}/$pkg/." "$dest/"
  done
  for patch in "$HERE/patches/$repo"-*.patch; do
    [ -e "$patch" ] || continue
    patch -s -p1 -d "$NAV_WS/src/$repo" <"$patch" \
      || fail "patch $(basename "$patch") does not apply to ${TREE[$repo]}"
  done
done

say "building the navigation extra in $NAV_WS (once: about 20 minutes on 2 cores)"
rm -f "$STAMP"
log="$NAV_WS/build.log"
started=$(date +%s)
if ! (
  set +eu
  # shellcheck disable=SC1091
  source "$WS/devel/setup.bash"
  export PATH="/usr/bin:$PATH"
  catkin_make -C "$NAV_WS" "${ARGS[@]}" -j"${NAV_JOBS:-$(nproc)}"
) >"$log" 2>&1; then
  grep -E 'error|Error' "$log" | tail -n 10 >&2
  fail "catkin_make failed (whole log: $log)"
fi
printf '%s\n' "$DIGEST" >"$STAMP"
say "nav built in $(( $(date +%s) - started )) s"
say "a shell with both: source $NAV_WS/devel/setup.bash"
