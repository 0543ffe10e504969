#!/usr/bin/env bash
# README command (b): set up, build and run the test suite with ctest: the release build, an
# AddressSanitizer + UndefinedBehaviorSanitizer build of everything with clang (skip:
# DTLAB_SKIP_ASAN=1), and a ThreadSanitizer build of the parallel tests, of the validator and of
# star splaying on several threads (skip: DTLAB_SKIP_TSAN=1), and each libFuzzer harness for a
# bounded time (scripts/fuzz.sh; skip: DTLAB_SKIP_FUZZ=1), taken from the ASan build, which builds
# them beside the tests (one instrumented build of the libraries instead of two).
# Ends with one plain summary line "N passed, N failed". Exits non-zero when any suite fails to
# configure or build, reports a failed test, runs no test, or prints no summary line.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
jobs="$(nproc)"
start=$(date +%s)
total_passed=0
total_failed=0
status=0

# suite_result NAME PASSED FAILED EXIT-CODE T0: adds a suite to the totals. A suite that failed,
# ran nothing or exited non-zero counts at least one failure and makes the script fail.
suite_result() {
  local name="$1" passed="$2" failed="$3" code="$4" t0="$5" note=""
  if [ "$code" -ne 0 ] && [ "$failed" -eq 0 ]; then
    failed=1
    note=" (exit status $code)"
  fi
  if [ $((passed + failed)) -eq 0 ]; then
    failed=1
    note=" (no test ran)"
  fi
  [ "$failed" -eq 0 ] || status=1
  total_passed=$((total_passed + passed))
  total_failed=$((total_failed + failed))
  echo "suite $name: $passed passed, $failed failed in $(($(date +%s) - t0)) s$note"
}

run_suite() { # run_suite PRESET BUILD-TARGETS CTEST-REGEX [cmake args...]
  local preset="$1" targets="$2" regex="$3"
  shift 3
  local t0
  t0=$(date +%s)
  local built=0
  if cmake --preset "$preset" -DDTLAB_BUILD_TESTS=ON "$@" >/dev/null; then
    if [ -n "$targets" ]; then
      # shellcheck disable=SC2086
      cmake --build --preset "$preset" -j"$jobs" --target $targets && built=1
    else
      cmake --build --preset "$preset" -j"$jobs" && built=1
    fi
  fi
  if [ "$built" -ne 1 ]; then
    echo "suite $preset: configure or build FAILED"
    suite_result "$preset" 0 1 1 "$t0"
    return 0
  fi
  local log="build/$preset/ctest.log"
  mkdir -p "build/$preset"
  set +e
  # The test presets set noTestsAction=error: ctest exits non-zero when it finds no test.
  ctest --preset "$preset" -j"$jobs" --timeout 1200 ${regex:+-R "$regex"} \
    ${ctest_exclude:+-E "$ctest_exclude"} 2>&1 | tee "$log"
  local code=${PIPESTATUS[0]}
  set -e
  local summary total=0 failed=0
  summary=$(grep -E "tests passed, [0-9]+ tests failed out of [0-9]+" "$log" | tail -n1 || true)
  if [ -n "$summary" ]; then
    total=$(echo "$summary" | sed -E 's/.* out of ([0-9]+).*/\1/')
    failed=$(echo "$summary" | sed -E 's/.*tests passed, ([0-9]+) tests failed.*/\1/')
  else
    echo "suite $preset: no ctest summary line"
    failed=1
  fi
  suite_result "$preset" $((total - failed > 0 ? total - failed : 0)) "$failed" "$code" "$t0"
}

# The predicates' stress test on 3 * 10^6 inputs each instead of 10^7 (176 s of one core on the
# 2-core CI machine; a plain ctest keeps 10^7).
run_suite release "" "" -DDTLAB_BUILD_BENCH=ON -DDTLAB_STRESS_CALLS=3000000
# The RapidCheck properties again with a fresh seed, printed (the suite above always checks the
# same cases): DTLAB_RC_FRESH_SEED picks it, DTLAB_SKIP_FRESH_SEED=1 skips the run. Each binary
# counts as one test.
if [ "${DTLAB_SKIP_FRESH_SEED:-0}" != "1" ]; then
  t0=$(date +%s)
  fresh_seed="${DTLAB_RC_FRESH_SEED:-$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')}"
  fresh_params="seed=$fresh_seed max_success=60"
  fresh_passed=0
  fresh_failed=0
  for binary in property_tests/engine_properties property_tests/repair_properties \
    tests/predicates_test tests/double_word_test tests/cgal_sign_test; do
    echo "RapidCheck fresh seed $fresh_seed: $binary (reproduce: RC_PARAMS='$fresh_params' build/release/$binary)"
    if RC_PARAMS="$fresh_params" "build/release/$binary" --gtest_brief=1; then
      fresh_passed=$((fresh_passed + 1))
    else
      fresh_failed=$((fresh_failed + 1))
    fi
  done
  suite_result fresh-seed "$fresh_passed" "$fresh_failed" 0 "$t0"
fi
if [ "${DTLAB_SKIP_ASAN:-0}" != "1" ]; then
  # Memory errors, not coverage, are this suite's job: fewer RapidCheck cases.
  # The real models (the full dragon among them) and the studies' --quick runs drive the same
  # engine through the CLI on bigger inputs: the release suite runs them; here they took 285 s of
  # the suite's 1,289 s of tests (docs/testing.md).
  # BurglaryStaysConsistentAndRepairs (183 s of this suite's ctest on 2026-11-28, its exact GMP
  # recounts the most of it): burglary's post-check and repairs stay under ASan in the parallel
  # fuzz corpus replay and the fuzz run, and the test itself runs in the release suite.
  ctest_exclude='^(cli\.real_models|experiment\.quick\..*|ParallelMethods\.BurglaryStaysConsistentAndRepairs)$' \
    run_suite asan "" "" "-DDTLAB_RC_PARAMS=seed=20261121 max_success=40"
fi
if [ "${DTLAB_SKIP_TSAN:-0}" != "1" ]; then
  # BurglaryStaysConsistentAndRepairs is about the sequential post-check and repairs after
  # burglary (its threads are under TSan in four other tests and the parallel fuzz replay), and
  # took 202 s of the TSan suite's 395 s of tests on 2026-11-28.
  ctest_exclude='^ParallelMethods\.BurglaryStaysConsistentAndRepairs$' \
    run_suite tsan "parallel_test lock_grid_test replay_parallel validator_threads_test parallel_ranges_test star_splaying_test run_monitor_test progress_counters_test populate_pages_test radix_sort_test worker_pool_test" \
    "^ParallelMethods\\.|^fuzz\\.replay_parallel$|^ValidatorThreads\\.|^InParallel|^SplayTetrahedra\\.EveryThreadCount|^SplaySharedMesh\\.ParallelScan|^RunMonitor\\.|^ProgressCounters\\.|^Watchdog\\.|^PopulatePages\\.|^StableSortByKey\\.|^WorkerPool\\."
fi
if [ "${DTLAB_SKIP_FUZZ:-0}" != "1" ]; then
  # Each libFuzzer harness for a bounded time from its corpus (DTLAB_FUZZ_SECONDS, default 60: the
  # corpus replay, then at least DTLAB_FUZZ_MIN_EXECS executions of fuzzing).
  t0=$(date +%s)
  mkdir -p build
  set +e
  fuzz_preset=fuzz
  [ "${DTLAB_SKIP_ASAN:-0}" = "1" ] || fuzz_preset=asan
  # From the seed corpus every time (DTLAB_FUZZ_FRESH): a scratch corpus grown by earlier runs
  # takes longer to replay each time, until no time is left to fuzz.
  DTLAB_FUZZ_FRESH=1 DTLAB_FUZZ_PRESET="$fuzz_preset" scripts/fuzz.sh "${DTLAB_FUZZ_SECONDS:-60}" 2>&1 | tee build/fuzz.log
  code=${PIPESTATUS[0]}
  set -e
  summary=$(grep -E "^fuzz: [0-9]+ passed, [0-9]+ failed" build/fuzz.log | tail -n1 || true)
  fuzz_passed=0
  fuzz_failed=0
  if [ -n "$summary" ]; then
    fuzz_passed=$(echo "$summary" | sed -E 's/^fuzz: ([0-9]+) passed.*/\1/')
    fuzz_failed=$(echo "$summary" | sed -E 's/.* ([0-9]+) failed.*/\1/')
  else
    echo "suite fuzz: no summary line"
    fuzz_failed=1
  fi
  suite_result fuzz "$fuzz_passed" "$fuzz_failed" "$code" "$t0"
fi
echo "test time: $(($(date +%s) - start)) s on $jobs cores"
[ "$total_failed" -eq 0 ] || status=1
echo "$total_passed passed, $total_failed failed"
exit "$status"
