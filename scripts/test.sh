#!/usr/bin/env bash
# README command (b): set up, build and run the test suite with ctest: the release build, an
# AddressSanitizer + UndefinedBehaviorSanitizer build of everything (skip: DTLAB_SKIP_ASAN=1), and a
# ThreadSanitizer build of the parallel tests (skip: DTLAB_SKIP_TSAN=1), and each libFuzzer
# harness for a bounded time (scripts/fuzz.sh; skip: DTLAB_SKIP_FUZZ=1).
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
  # Memory errors, not coverage, are this suite's job: fewer RapidCheck cases.
  run_suite asan "" "" "-DDTLAB_RC_PARAMS=seed=20261121 max_success=100"
fi
if [ "${DTLAB_SKIP_TSAN:-0}" != "1" ]; then
  run_suite tsan "parallel_test replay_parallel" "^ParallelMethods\\.|^fuzz\\.replay_parallel$"
fi
if [ "${DTLAB_SKIP_FUZZ:-0}" != "1" ]; then
  # Each libFuzzer harness for a bounded time from its corpus (DTLAB_FUZZ_SECONDS, default 45).
  t0=$(date +%s)
  set +e
  scripts/fuzz.sh "${DTLAB_FUZZ_SECONDS:-45}" | tee build/fuzz.log
  code=${PIPESTATUS[0]}
  set -e
  summary=$(grep -E "^fuzz: [0-9]+ passed, [0-9]+ failed" build/fuzz.log | tail -n1 || true)
  fuzz_passed=$(echo "$summary" | sed -E 's/^fuzz: ([0-9]+) passed.*/\1/')
  fuzz_failed=$(echo "$summary" | sed -E 's/.* ([0-9]+) failed/\1/')
  if [ -z "$summary" ]; then fuzz_passed=0; fuzz_failed=1; fi
  total_passed=$((total_passed + fuzz_passed))
  total_failed=$((total_failed + fuzz_failed))
  [ "$code" -eq 0 ] || status=1
  echo "suite fuzz: $fuzz_passed passed, $fuzz_failed failed in $(( $(date +%s) - t0 )) s"
fi
echo "test time: $(( $(date +%s) - start )) s on $jobs cores"
echo "$total_passed passed, $total_failed failed"
exit "$status"
