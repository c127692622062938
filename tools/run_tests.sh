#!/usr/bin/env bash
# Run the test suites in a shell where `source .catkin_ws/devel/setup.bash` was done.
#   tools/run_tests.sh [unit|rostest|all]   (default all)
# Ends with one summary line "tests: N passed, N failed" and exits non-zero if any failed.
set -uo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$ROOT"
what=${1:-all}
passed=0
failed=0
results="$ROOT/.catkin_ws/test_results"
mkdir -p "$results"

run_unit() {
  echo "=== unit tests (pytest, no ROS master)"
  local out="$results/pytest.txt"
  python3 -m pytest -q -p no:cacheprovider test/unit --junitxml="$results/pytest-unit.xml" \
    2>&1 | tee "$out"
  local line
  line=$(grep -E '^[=]* ?[0-9]+ (passed|failed)' "$out" | tail -n 1)
  local p f e
  p=$(grep -oE '[0-9]+ passed' <<<"$line" | grep -oE '[0-9]+' || echo 0)
  f=$(grep -oE '[0-9]+ failed' <<<"$line" | grep -oE '[0-9]+' || echo 0)
  e=$(grep -oE '[0-9]+ error' <<<"$line" | grep -oE '[0-9]+' || echo 0)
  [ -n "$line" ] || f=1   # pytest did not even report: count it as a failure
  passed=$((passed + p)); failed=$((failed + f + e))
}

run_rostests() {
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
  done
}

case "$what" in
  unit) run_unit ;;
  rostest) run_rostests ;;
  all) run_unit; run_rostests ;;
  *) echo "usage: tools/run_tests.sh [unit|rostest|all]" >&2; exit 2 ;;
esac
echo "tests: $passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -gt 0 ]
