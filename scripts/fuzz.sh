#!/usr/bin/env bash
# Builds the libFuzzer harnesses (cmake --preset fuzz: clang, ASan + UBSan; DTLAB_FUZZ_PRESET=asan
# takes them from the asan preset's build, which has them beside the tests) and runs each one for
# a bounded time, starting from its seed corpus, two at a time. New inputs go to a scratch copy of
# the corpus (build/PRESET/corpus/TARGET), crashes to build/PRESET/artifacts/TARGET/. The scratch
# corpus keeps what earlier runs found (a campaign goes on where the last one stopped), unless
# DTLAB_FUZZ_FRESH=1 (scripts/test.sh): then it starts again from the seed corpus, so that a
# bounded run's replay does not grow with every run (a scratch corpus kept over a day's runs held
# 1,252 inputs, and replaying them under ASan took the whole 60 s: no fuzzing).
# Usage: scripts/fuzz.sh [SECONDS-PER-FUZZER (default 60)] [TARGET...]
# Ends with "fuzz: N passed, N failed". A fuzzer passes when it finds nothing in its time and has
# fuzzed: at least DTLAB_FUZZ_MIN_EXECS (default 100) executions after replaying its corpus (a run
# that only replays its corpus and stops is not a fuzz run). Each line says how many coverage
# counters the harness loaded (its own and the libraries it tests: cmake/Fuzzing.cmake), the
# executions before and after the corpus replay, and the coverage reached.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
shift || true
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then targets=(triangulate parallel predicates parsers repair); fi

preset="${DTLAB_FUZZ_PRESET:-fuzz}"
cmake --preset "$preset" >/dev/null
cmake --build --preset "$preset" -j"$(nproc)" --target "${targets[@]/#/fuzz_}"
out="build/$preset"

run_one() {  # run_one TARGET: exit status of the fuzzer, log in build/PRESET/TARGET.log
  local t="$1"
  local corpus="$out/corpus/$t" artifacts="$out/artifacts/$t"
  if [ "${DTLAB_FUZZ_FRESH:-0}" = "1" ]; then rm -rf "$corpus"; fi
  mkdir -p "$corpus" "$artifacts"
  cp -n fuzz/corpus/"$t"/* "$corpus"/
  "$out/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=60 -rss_limit_mb=4096 \
    -dict="fuzz/$t.dict" -artifact_prefix="$artifacts/" -print_final_stats=1 \
    "$corpus" >"$out/$t.log" 2>&1
}

min_execs="${DTLAB_FUZZ_MIN_EXECS:-100}"
passed=0
failed=0
pids=()
names=()
report() {  # report INDEX
  local t="${names[$1]}" log="$out/${names[$1]}.log"
  local counters inited total fuzzed cov code=0
  wait "${pids[$1]}" || code=$?
  counters=$(grep -Eo 'Loaded [0-9]+ modules +\([0-9]+ inline 8-bit counters\)' "$log" |
    grep -Eo '\([0-9]+' | tr -d '(' | head -n1 || true)
  inited=$(grep -E '^#[0-9]+[[:space:]]+INITED' "$log" | grep -Eo '^#[0-9]+' | tr -d '#' | head -n1 || true)
  total=$(grep -Eo 'stat::number_of_executed_units: *[0-9]+' "$log" | grep -Eo '[0-9]+$' || true)
  cov=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -n1 | grep -Eo 'cov: [0-9]+ ft: [0-9]+' || true)
  fuzzed=$(( ${total:-0} - ${inited:-0} ))
  if [ "$code" -ne 0 ]; then
    failed=$((failed + 1))
    echo "fuzz_$t: FAILED; log $log, inputs in $out/artifacts/$t/"
    tail -n 30 "$log"
  elif [ -z "$total" ] || [ -z "$inited" ] || [ "$fuzzed" -lt "$min_execs" ]; then
    failed=$((failed + 1))
    echo "fuzz_$t: FAILED: ${fuzzed} executions after the corpus replay (${inited:-?} in it), fewer than ${min_execs}: give it more time (DTLAB_FUZZ_SECONDS)"
  else
    passed=$((passed + 1))
    echo "fuzz_$t: nothing found in ${seconds} s: ${counters:-?} counters, ${inited} executions replaying the corpus, ${fuzzed} after, ${cov:-cov: ?}"
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
