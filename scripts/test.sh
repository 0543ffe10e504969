#!/usr/bin/env bash
# README command (b): set up, build and run the whole test suite (ctest), then print one plain
# summary line "N passed, N failed".
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
jobs="$(nproc)"
start=$(date +%s)
cmake --preset release -DDTLAB_BUILD_TESTS=ON -DDTLAB_BUILD_BENCH=ON >/dev/null
cmake --build --preset release -j"$jobs"
set +e
ctest --preset release -j"$jobs" 2>&1 | tee build/release/ctest.log
status=${PIPESTATUS[0]}
set -e
summary=$(grep -E "tests passed, [0-9]+ tests failed out of" build/release/ctest.log | tail -n1)
total=$(echo "$summary" | sed -E 's/.* out of ([0-9]+).*/\1/')
failed=$(echo "$summary" | sed -E 's/.*tests passed, ([0-9]+) tests failed.*/\1/')
passed=$((total - failed))
echo "test time: $(( $(date +%s) - start )) s on $jobs cores"
echo "$passed passed, $failed failed"
exit "$status"
