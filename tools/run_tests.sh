#!/usr/bin/env bash
# Run the test suites in a shell where `source catkin_ws/devel/setup.bash` was done.
#   tools/run_tests.sh [unit|rostest|learning|all]   (default all)
# unit: pytest under the venv's Python, again under Python 3.8 (catkin_ws/venv38, made by
# `tools/setup.sh --test` where a Python 3.8 exists; skipped with one line where not), and
# every shell script checked by shellcheck (one test). rostest: every test/rostest/*.test.
# learning: test/learning (pytest: the learning environments on a two-node Ray cluster; Ray is
# installed into the venv on first use, by tools/install_extra.sh ray).
# Where NAV_SRC names the navigation extra's sources (a machine without GitHub, such as CI) and
# the extra is not built yet, it is built (tools/install_extra.sh nav, one compile job, at nice
# 10) beside the unit tests, which use one core, and the rostests wait for it: slam.test and the
# navigation tests then run instead of being skipped. A failed build counts as one failure.
# Ends with one line "failed: NAME" for each test that failed (pytest's node id, or the rostest
# file and its test case), then one summary line "tests: N passed, N failed" (", N skipped" when
# some were), and exits non-zero if any failed.
set -uo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT" || exit 2
what=${1:-all}
passed=0
failed=0
skipped=0
failures=()
results="$ROOT/catkin_ws/test_results"
VENV38="$ROOT/catkin_ws/venv38"
mkdir -p "$results"

count() {
  # count WORD LINE: the number before WORD in pytest's summary line, or 0.
  local n
  n=$(grep -oE "[0-9]+ $1" <<<"$2" | grep -oE '^[0-9]+' | head -n 1)
  echo "${n:-0}"
}

run_pytest() {
  # run_pytest LABEL PYTHON JUNIT_NAME [FOLDER (default test/unit)]
  local label=$1 python=$2 junit=$3 folder=${4:-test/unit}
  echo "=== $folder, $label (pytest, no ROS master)"
  local out="$results/${junit%.xml}.txt"
  # A module that fails to import counts as one error; the other modules still run.
  "$python" -m pytest -q -p no:cacheprovider --continue-on-collection-errors "$folder" \
    --junitxml="$results/$junit" 2>&1 | tee "$out"
  local line
  line=$(grep -E '^[=]* ?[0-9]+ (passed|failed|skipped|errors?)\b' "$out" | tail -n 1)
  local p f e s
  p=$(count passed "$line"); f=$(count failed "$line"); e=$(count error "$line")
  s=$(count skipped "$line")
  if [ -z "$line" ] || [ $((p + f + e)) -eq 0 ]; then
    echo "pytest ($label) reported no result: counted as a failure"
    f=$((f + 1))
  fi
  passed=$((passed + p)); failed=$((failed + f + e)); skipped=$((skipped + s))
  local name
  while IFS= read -r name; do
    failures+=("$label: $name")
  done < <(grep -oE '^(FAILED|ERROR) [^ ]+' "$out" | cut -d' ' -f2)
  if [ $((f + e)) -gt 0 ] && ! grep -qE '^(FAILED|ERROR) ' "$out"; then
    failures+=("$label: see $out")
  fi
}

run_unit() {
  run_pytest "$(python3 -c 'import sys; print("Python %d.%d" % sys.version_info[:2])')" \
    python3 pytest-unit.xml
}

run_learning() {
  run_pytest "learning on Ray, $(python3 -c 'import sys; print("Python %d.%d" % sys.version_info[:2])')" \
    python3 pytest-learning.xml test/learning
}

run_unit38() {
  if [ -f "$VENV38/.tutorial_turtlebot-stamp" ]; then
    run_pytest "Python 3.8 ($VENV38)" "$VENV38/bin/python3" pytest-unit-py38.xml
  elif [ -f "$ROOT/catkin_ws/venv38.skipped" ]; then
    echo "=== unit tests, Python 3.8: skipped, $(cat "$ROOT/catkin_ws/venv38.skipped")"
  else
    echo "=== unit tests, Python 3.8: skipped, no $VENV38 (tools/setup.sh --test makes it; make test runs that)"
  fi
}

shell_scripts() {
  # Every shell script of the repository: by shebang, or by name (*.sh, *.sh.in).
  local f
  while IFS= read -r -d '' f; do
    if [[ "$f" == *.sh || "$f" == *.sh.in ]] \
       || head -n 1 "$f" 2>/dev/null | grep -qE '^#!.*\b(ba|da|k)?sh\b'; then
      printf '%s\n' "$f"
    fi
  done < <(find . \( -path ./catkin_ws -o -path ./.git \) -prune -o -type f -print0 | sort -z)
}

run_shellcheck() {
  echo "=== shellcheck (every shell script, one test)"
  if ! command -v shellcheck >/dev/null; then
    echo "shellcheck: skipped, not installed (tools/setup.sh installs it)"
    skipped=$((skipped + 1))
    return
  fi
  local f ok=1 n=0
  while IFS= read -r f; do
    n=$((n + 1))
    if head -n 1 "$f" | grep -q '^#!'; then
      shellcheck "$f" || ok=0
    else
      shellcheck --shell=sh "$f" || ok=0   # sourced fragments (catkin env hooks: SHELLS sh)
    fi
  done < <(shell_scripts)
  if [ "$ok" = 1 ] && [ "$n" -gt 0 ]; then
    echo "shellcheck: $n scripts clean"
    passed=$((passed + 1))
  else
    echo "shellcheck: findings above ($n scripts checked)"
    failed=$((failed + 1))
    failures+=("shellcheck")
  fi
}

NAV_LOG="$results/nav-extra.txt"
nav_pid=""

start_nav_extra() {
  # The navigation extra built in the background where NAV_SRC is set and it is not built.
  [ -n "${NAV_SRC:-}" ] || return 0
  echo "=== navigation extra from NAV_SRC=$NAV_SRC (beside the unit tests; log: $NAV_LOG)"
  NAV_JOBS=1 nice -n 10 bash tools/install_extra.sh nav >"$NAV_LOG" 2>&1 &
  nav_pid=$!
}

wait_nav_extra() {
  [ -n "$nav_pid" ] || return 0
  echo "=== waiting for the navigation extra's build"
  if wait "$nav_pid"; then
    grep -E '^\[nav\] (nav (is )?built|building)' "$NAV_LOG" || true
    passed=$((passed + 1))
  else
    tail -n 15 "$NAV_LOG"
    failed=$((failed + 1))
    failures+=("navigation extra build (see $NAV_LOG)")
  fi
  nav_pid=""
}

run_rostests() {
  wait_nav_extra
  local t name out
  for t in test/rostest/*.test; do
    [ -e "$t" ] || continue
    name=$(basename "$t")
    echo "=== rostest tutorial_turtlebot $name"
    out="$results/rostest-${name%.test}.txt"
    rostest --text tutorial_turtlebot "$name" 2>&1 | tee "$out"
    local status=${PIPESTATUS[0]}
    local n e f
    n=$(grep -oE '^ \* TESTS: [0-9]+' "$out" | grep -oE '[0-9]+' | tail -n 1)
    e=$(grep -oE '^ \* ERRORS: [0-9]+' "$out" | grep -oE '[0-9]+' | tail -n 1)
    f=$(grep -oE '^ \* FAILURES: [0-9]+' "$out" | grep -oE '[0-9]+' | tail -n 1)
    e=${e:-0}; f=${f:-0}
    if [ -z "$n" ]; then n=1; f=1; echo "rostest $name reported no result: counted as failed"
    elif [ "$status" -ne 0 ] && [ $((e + f)) -eq 0 ]; then f=1; fi  # died after reporting
    passed=$((passed + n - e - f)); failed=$((failed + e + f))
    if [ $((e + f)) -gt 0 ]; then
      # rostest's summary names them: " * FAILURES: 1 [test_x]", " * ERRORS: 0 []".
      local cases
      cases=$(grep -E '^ \* (FAILURES|ERRORS): [0-9]+ \[' "$out" | grep -oE '\[.*\]' | tr -d '[]' \
        | tr ',\n' '  ' | tr -s ' ')
      cases=${cases# }; cases=${cases% }
      failures+=("rostest $name${cases:+: $cases}")
    fi
  done
}

case "$what" in
  unit) run_unit; run_unit38; run_shellcheck ;;
  rostest) start_nav_extra; run_rostests ;;
  learning) run_learning ;;
  all) start_nav_extra; run_unit; run_unit38; run_shellcheck; run_rostests; run_learning ;;
  *) echo "usage: tools/run_tests.sh [unit|rostest|learning|all]" >&2; exit 2 ;;
esac
for name in "${failures[@]}"; do
  echo "failed: $name"
done
if [ "$skipped" -gt 0 ]; then
  echo "tests: $passed passed, $failed failed, $skipped skipped"
else
  echo "tests: $passed passed, $failed failed"
fi
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
