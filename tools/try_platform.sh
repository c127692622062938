#!/usr/bin/env bash
# Try the project on another Debian release for real: a root made with debootstrap from the
# Debian registry this machine's apt uses, a fresh clone of this repository's HEAD inside it,
# and `make test` (or the make targets given) run there as a new user would.
#   tools/try_platform.sh debian13              make test in a Debian 13 (trixie) root
#   tools/try_platform.sh debian13 unit         only the unit tests (make unit)
#   tools/try_platform.sh debian13 --root-only  build (or check) the root, run nothing
#   TRY_PLATFORM_NAV_SRC=DIR tools/try_platform.sh debian13 nav-extra rostest
#       the navigation extra built there from DIR (its NAV_SRC, mounted read-only as /nav_src),
#       then every rostest: the SLAM and navigation ones run. Without it no NAV_SRC goes in.
# Needs root (debootstrap, chroot and mounts) and the Debian registry; nothing else.
# The root is kept between runs in $TRY_PLATFORM_CACHE (default /var/cache/tutorial_turtlebot),
# and with it apt's packages and the pybullet wheel that the set-up builds, so a second run
# spends its time on the tests. Mounts are undone and processes left in the root are stopped on
# exit, Ctrl-C included. Ends with the inner run's last line and how long each part took.
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
CACHE=${TRY_PLATFORM_CACHE:-/var/cache/tutorial_turtlebot}

say() { printf '[try_platform] %s\n' "$*"; }
fail() { printf '[try_platform] ERROR: %s\n' "$*" >&2; exit 1; }

usage="usage: tools/try_platform.sh debian13 [--root-only | MAKE_TARGET...] (default target: test)"
[ $# -ge 1 ] || fail "$usage"
case "$1" in
  debian13) SUITE=trixie ;;
  -h|--help) sed -n '2,15p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) fail "unknown platform '$1': this script knows debian13. $usage" ;;
esac
PLATFORM=$1
shift
ROOT_ONLY=0
TARGETS=()
for arg in "$@"; do
  case "$arg" in
    --root-only) ROOT_ONLY=1 ;;
    -*) fail "unknown option '$arg'. $usage" ;;
    *) TARGETS+=("$arg") ;;
  esac
done
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(test)
[ "$(id -u)" -eq 0 ] || fail "run as root: debootstrap, chroot and mount need it"

FS="$CACHE/$PLATFORM"
DONE_STAMP="$FS/.tutorial_turtlebot-root-complete"
CLONE=/root/tutorial_turtlebot            # inside the root
START=$(date +%s)
elapsed() { echo $(( $(date +%s) - $1 )); }

debian_mirror() {
  # The first Debian archive this machine's apt reads (deb822 .sources or a sources.list line).
  local uri
  uri=$(grep -hE '^URIs:' /etc/apt/sources.list.d/*.sources 2>/dev/null \
          | awk '{print $2}' | grep -v -- '-security' | head -n 1 || true)
  if [ -z "$uri" ]; then
    uri=$(grep -hE '^deb ' /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null \
            | awk '{print $2}' | grep -v -- '-security' | head -n 1 || true)
  fi
  echo "${uri:-http://deb.debian.org/debian}"
}

# --- mounts, and their undoing -----------------------------------------------------------------

MOUNTED=()
# shellcheck disable=SC2317  # called from the EXIT trap
stop_root_processes() {
  # Every process whose root directory is the platform's root: a test left running, a roscore.
  local pid root signal
  for signal in TERM KILL; do
    for pid in /proc/[0-9]*; do
      root=$(readlink "$pid/root" 2>/dev/null || true)
      if [ "$root" = "$FS" ]; then kill "-$signal" "${pid#/proc/}" 2>/dev/null || true; fi
    done
    if [ "$signal" = TERM ]; then sleep 2; fi
  done
}
# shellcheck disable=SC2317  # the EXIT trap
cleanup() {
  local status=$?
  trap - EXIT INT TERM
  set +e
  if [ ${#MOUNTED[@]} -gt 0 ]; then
    stop_root_processes
    local i
    for (( i=${#MOUNTED[@]}-1; i>=0; i-- )); do
      umount -R "${MOUNTED[$i]}" 2>/dev/null || umount -R -l "${MOUNTED[$i]}" 2>/dev/null || true
    done
  fi
  exit "$status"
}
trap cleanup EXIT
trap 'say "interrupted"; exit 130' INT TERM

mount_into_root() {
  # mount_into_root TARGET ARGS...: mount, and remember it for cleanup.
  local target="$FS$1"
  shift
  mkdir -p "$target"
  mount "$@" "$target"
  MOUNTED+=("$target")
}

# --- the root ------------------------------------------------------------------------------------

make_root() {
  command -v debootstrap >/dev/null || {
    say "installing debootstrap"
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap >/dev/null 2>&1 \
      || { apt-get update -qq >/dev/null 2>&1 \
           && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap >/dev/null; } \
      || fail "apt-get install debootstrap failed"
  }
  local mirror t0 log
  mirror=$(debian_mirror)
  t0=$(date +%s)
  say "making a Debian $SUITE root in $FS from $mirror (a few minutes, once)"
  rm -rf "$FS"
  mkdir -p "$CACHE"
  log="$CACHE/$PLATFORM.debootstrap.log"
  if ! debootstrap --include=make,git,ca-certificates "$SUITE" "$FS" "$mirror" >"$log" 2>&1; then
    tail -n 15 "$log" >&2
    fail "debootstrap failed (whole log: $log)"
  fi
  cat >"$FS/etc/apt/sources.list" <<EOF
deb $mirror $SUITE main
deb $mirror $SUITE-updates main
EOF
  touch "$DONE_STAMP"
  say "root ready in $(elapsed "$t0") s"
}

if [ -f "$DONE_STAMP" ]; then
  say "reusing the Debian $SUITE root in $FS ($(du -sh "$FS" 2>/dev/null | cut -f1))"
else
  make_root
fi
[ "$ROOT_ONLY" = 0 ] || { say "root only: done"; exit 0; }

# What the root needs from this machine: name resolution, and the CA bundle for pip (a proxy's
# certificate may be in it); pip's index settings, so pip inside asks what pip outside asks.
cp -L /etc/resolv.conf "$FS/etc/resolv.conf" 2>/dev/null || true
cp -L /etc/hosts "$FS/etc/hosts"
cp -L /etc/ssl/certs/ca-certificates.crt "$FS/etc/ssl/certs/host-ca-bundle.crt"

mount_into_root /proc -t proc proc
mount_into_root /sys -t sysfs sysfs
mount_into_root /dev --rbind /dev
mount --make-rslave "$FS/dev"
mount_into_root /tmp -t tmpfs tmpfs
nav_env=()
if [ -n "${TRY_PLATFORM_NAV_SRC:-}" ]; then
  [ -d "$TRY_PLATFORM_NAV_SRC" ] || fail "TRY_PLATFORM_NAV_SRC=$TRY_PLATFORM_NAV_SRC is no folder"
  mount_into_root /nav_src --bind "$TRY_PLATFORM_NAV_SRC"
  mount -o remount,bind,ro "$FS/nav_src"
  nav_env=(NAV_SRC=/nav_src)
fi

# --- the clone and the run -----------------------------------------------------------------------

rm -rf "${FS:?}$CLONE"
git clone -q --no-hardlinks "$ROOT" "$FS$CLONE"
say "cloned $(git -C "$ROOT" rev-parse --short HEAD) (HEAD; uncommitted changes are not in it) into $CLONE"
say "running: make ${TARGETS[*]} in Debian $SUITE"
t_run=$(date +%s)
log="$CACHE/$PLATFORM.run.log"
set +e
chroot "$FS" /usr/bin/env -i HOME=/root LANG=C.UTF-8 TERM=dumb CI="${CI:-}" \
  PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
  PIP_CERT=/etc/ssl/certs/host-ca-bundle.crt PIP_DISABLE_PIP_VERSION_CHECK=1 \
  PIP_DEFAULT_TIMEOUT=180 "${nav_env[@]}" \
  bash -c "cd $CLONE && make ${TARGETS[*]}" </dev/null 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
set -e
say "Debian $SUITE: make ${TARGETS[*]} exited $status after $(elapsed "$t_run") s" \
    "($(elapsed "$START") s in all; log: $log)"
exit "$status"
