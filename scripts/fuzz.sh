#!/usr/bin/env bash
# Builds the libFuzzer harnesses (cmake --preset fuzz: clang, ASan + UBSan) and runs each one for a
# bounded time, starting from its seed corpus, two at a time. New inputs go to a scratch copy of
# the corpus (build/fuzz/corpus/TARGET), crashes to build/fuzz/artifacts/TARGET/.
# Usage: scripts/fuzz.sh [SECONDS-PER-FUZZER (default 60)] [TARGET...]
# Ends with "fuzz: N passed, N failed" (a fuzzer passes when it finds nothing in its time).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=(triangulate parallel predicates parsers repair); fi

cmake --preset fuzz >/dev/null
cmake --build --preset fuzz -j"$(nproc)" --target "${targets[@]/#/fuzz_}"

run_one() {  # run_one TARGET: exit status of the fuzzer, log in build/fuzz/TARGET.log
  local t="$1"
  local corpus="build/fuzz/corpus/$t" artifacts="build/fuzz/artifacts/$t"
  mkdir -p "$corpus" "$artifacts"
  cp -n fuzz/corpus/"$t"/* "$corpus"/
  "build/fuzz/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=60 -rss_limit_mb=4096 \
    -dict="fuzz/$t.dict" -artifact_prefix="$artifacts/" -print_final_stats=1 \
    "$corpus" >"build/fuzz/$t.log" 2>&1
}

passed=0
failed=0
pids=()
names=()
report() {  # report INDEX
  local t="${names[$1]}"
  if wait "${pids[$1]}"; then
    passed=$((passed + 1))
    echo "fuzz_$t: nothing found in ${seconds} s ($(grep -Eo 'stat::number_of_executed_units: *[0-9]+' "build/fuzz/$t.log" | grep -Eo '[0-9]+$' || echo '?') runs)"
  else
    failed=$((failed + 1))
    echo "fuzz_$t: FAILED; log build/fuzz/$t.log, inputs in build/fuzz/artifacts/$t/"
    tail -n 30 "build/fuzz/$t.log"
  fi
}
for t in "${targets[@]}"; do
  run_one "$t" &
  pids+=($!)
  names+=("$t")
  if [ ${#pids[@]} -eq 2 ]; then
    report 0
    report 1
    pids=()
    names=()
  fi
done
if [ ${#pids[@]} -eq 1 ]; then report 0; fi
echo "fuzz: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
