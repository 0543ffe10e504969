#!/usr/bin/env bash
# A fuzz campaign with a record (issue 38, part 0): runs each harness of a libFuzzer build for
# SECONDS from a fresh copy of its seed corpus (fuzz/corpus/TARGET), one harness at a time, and
# writes per harness the log, the grown corpus, any crash, and (with SNAPSHOT=S) a copy of the
# corpus and the last coverage line S seconds in. Two campaigns started together (say an old and a
# new build) thus run the same harness side by side, one core each, under the same load.
# Usage: tools/fuzz/campaign.sh BUILD-DIR SECONDS OUT [TARGET...]   (BUILD-DIR: e.g. build/fuzz)
# Prints one line per harness: counters loaded, executions, final cov/ft, corpus size, crashes.
set -euo pipefail
cd "$(dirname "$0")/../.."
[ $# -ge 3 ] || { echo "usage: $0 BUILD-DIR SECONDS OUT [TARGET...]" >&2; exit 2; }
build="$1" seconds="$2" out="$3"
shift 3
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(triangulate parallel predicates parsers repair)
snapshot="${SNAPSHOT:-0}"
mkdir -p "$out"
status=0
for t in "${targets[@]}"; do
  corpus="$out/corpus/$t" artifacts="$out/artifacts/$t" log="$out/$t.log"
  rm -rf "$corpus" "$artifacts"
  mkdir -p "$corpus" "$artifacts"
  cp fuzz/corpus/"$t"/* "$corpus"/
  if [ "$snapshot" -gt 0 ]; then
    (
      sleep "$snapshot"
      mkdir -p "$out/corpus_at_${snapshot}s/$t"
      cp "$corpus"/* "$out/corpus_at_${snapshot}s/$t"/ 2>/dev/null || true
      grep -E '^#[0-9]+.*cov: ' "$log" | tail -n1 >"$out/$t.at_${snapshot}s" || true
    ) &
  fi
  set +e
  "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=60 -rss_limit_mb=4096 \
    -dict="fuzz/$t.dict" -artifact_prefix="$artifacts/" -print_final_stats=1 "$corpus" \
    >"$log" 2>&1
  code=$?
  set -e
  wait
  [ "$code" -eq 0 ] || status=1
  counters=$(grep -Eo 'Loaded [0-9]+ modules +\([0-9]+ inline 8-bit counters\)' "$log" | grep -Eo '\([0-9]+' | tr -d '(' | head -n1)
  execs=$(grep -Eo 'stat::number_of_executed_units: *[0-9]+' "$log" | grep -Eo '[0-9]+$' || echo '?')
  last=$(grep -E '^#[0-9]+.*cov: ' "$log" | tail -n1 | grep -Eo 'cov: [0-9]+ ft: [0-9]+' || echo 'cov: ? ft: ?')
  # crash-, leak-, timeout- and oom- inputs are failures; slow-unit- ones (over 10 s) are only told.
  failures=$(find "$artifacts" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  slow=$(find "$artifacts" -type f -name 'slow-unit-*' | wc -l)
  [ "$failures" -eq 0 ] || status=1
  echo "$t: exit $code, counters ${counters:-?}, $execs executions in $seconds s, $last, corpus $(find "$corpus" -type f | wc -l) files, failing inputs $failures, slow inputs $slow" | tee -a "$out/summary.txt"
done
exit "$status"
