#!/usr/bin/env bash
# README command (b): set up, build and run the test suite with ctest: the release build, an
# AddressSanitizer + UndefinedBehaviorSanitizer build of everything (skip: DTLAB_SKIP_ASAN=1), and a
# ThreadSanitizer build of the parallel tests (skip: DTLAB_SKIP_TSAN=1).
# Ends with one plain summary line "N passed, N failed".
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
jobs="$(nproc)"
start=$(date +%s)
total_passed=0
total_failed=0
status=0

run_suite() {  # run_suite PRESET BUILD-TARGETS CTEST-REGEX [cmake args...]
  local preset="$1" targets="$2" regex="$3"
  shift 3
  local t0
  t0=$(date +%s)
  cmake --preset "$preset" -DDTLAB_BUILD_TESTS=ON "$@" >/dev/null
  if [ -n "$targets" ]; then
    # shellcheck disable=SC2086
    cmake --build --preset "$preset" -j"$jobs" --target $targets
  else
    cmake --build --preset "$preset" -j"$jobs"
  fi
  local log="build/$preset/ctest.log"
  set +e
  ctest --preset "$preset" -j"$jobs" --timeout 1200 ${regex:+-R "$regex"} 2>&1 | tee "$log"
  local code=${PIPESTATUS[0]}
  set -e
  local summary total failed
  summary=$(grep -E "tests passed, [0-9]+ tests failed out of" "$log" | tail -n1)
  total=$(echo "$summary" | sed -E 's/.* out of ([0-9]+).*/\1/')
  failed=$(echo "$summary" | sed -E 's/.*tests passed, ([0-9]+) tests failed.*/\1/')
  if [ -z "$total" ]; then total=0; failed=1; fi
  total_passed=$((total_passed + total - failed))
  total_failed=$((total_failed + failed))
  [ "$code" -eq 0 ] || status=1
  echo "suite $preset: $((total - failed)) passed, $failed failed in $(( $(date +%s) - t0 )) s"
}

run_suite release "" "" -DDTLAB_BUILD_BENCH=ON
if [ "${DTLAB_SKIP_ASAN:-0}" != "1" ]; then
  run_suite asan "" ""
fi
if [ "${DTLAB_SKIP_TSAN:-0}" != "1" ]; then
  run_suite tsan "parallel_test" "^ParallelMethods\\."
fi
echo "test time: $(( $(date +%s) - start )) s on $jobs cores"
echo "$total_passed passed, $total_failed failed"
exit "$status"
