#!/usr/bin/env bash
# Thread scaling on a lent many-core machine (issue 36; the `device` tool runs it there): builds the
# release CLI and bench/cgal_compare on every core, records the machine (lscpu, nproc, free,
# compiler) and runs cgal_compare on INPUT at each thread count with every parallel method of the
# registry that runs in walk mode beside CGAL's parallel mode (TBB), ROUNDS interleaved rounds,
# each engine in its own process. Everything lands in OUT (default $OUT/device_scaling where the
# device tool sets $OUT, else build/device_scaling): machine.txt, scaling.txt (cgal_compare's
# table), build.log.
# Usage: tools/device_scaling.sh [INPUT (uniform:1000000)] [THREADS (1,2,4,8,16)] [ROUNDS (3)]
#        [INSERTION (cavity | flips | both; default cavity)]
# DTLAB_DEVICE_BUILD=DIR reuses a release build with the bench (no build step), for a local try.
# At 16 cores the build takes about 2 minutes and 1M points by cavities about 4 more at 3 rounds
# (estimated from the 2-core VM's timings, not measured on a lent machine yet).
set -euo pipefail
cd "$(dirname "$0")/.."
input="${1:-uniform:1000000}"
threads="${2:-1,2,4,8,16}"
rounds="${3:-3}"
insertion="${4:-cavity}"
out="${OUT:+$OUT/device_scaling}"
out="${out:-build/device_scaling}"
mkdir -p "$out"
{
  date -u
  git rev-parse HEAD 2>/dev/null || echo "commit: unknown (no git)"
  nproc
  lscpu
  free -g
  c++ --version | head -n1
} >"$out/machine.txt" 2>&1
build="${DTLAB_DEVICE_BUILD:-build/device}"
if [ -z "${DTLAB_DEVICE_BUILD:-}" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DDTLAB_BUILD_TESTS=OFF \
    -DDTLAB_BUILD_BENCH=ON >"$out/build.log" 2>&1
  cmake --build "$build" -j"$(nproc)" --target dtlab cgal_compare >>"$out/build.log" 2>&1
fi
# The parallel methods that run in walk mode with this insertion, from the registry.
ins_column="$insertion"
[ "$insertion" = both ] && ins_column=cavity
methods=$("$build/cli/dtlab" methods | awk -F'|' -v ins="$ins_column" \
  'NR > 2 && $4 !~ /^ *1 *$/ && index($5, "walk") && index($6, ins) { gsub(/[` ]/, "", $2); print $2 }' |
  paste -sd, -)
echo "methods: $methods; threads: $threads; input: $input; rounds: $rounds" | tee -a "$out/machine.txt"
"$build/bench/cgal_compare" "$input" --repeat "$rounds" --threads "$threads" --methods "$methods" \
  --no-dag --insertion "$insertion" | tee "$out/scaling.txt"
