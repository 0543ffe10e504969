#!/usr/bin/env bash
# The runs behind docs/experiments.md: every study of `dtlab experiment`, one after the other (never
# beside other work: the timings are the machine's), into OUT (default build/experiments), then
# tools/experiments_doc.py OUT rewrites docs/experiments.md from their tables.
# Usage: tools/run_experiments.sh [OUT] [STUDY ...]   (about 90 minutes on a 2-core machine; it resumes what an earlier run in OUT finished)
set -euo pipefail
cd "$(dirname "$0")/.."
dtlab=build/release/cli/dtlab
out="${1:-build/experiments}"
shift || true
declare -A args=(
  [burglary-errors]="--sizes 10000,50000"
  [burglary-errors-1m]="--inputs uniform --sizes 1000000 --threads 2 --location walk"
  [predicate-errors]=""
  [speedup]="--sizes 50000,200000 --seeds 3"
  [speedup-1m]="--sizes 1000000 --location walk --threads 1,2 --seeds 3 --inputs uniform"
  [breakdown]="--sizes 10000,20000,50000,100000,200000,500000,1000000"
  [flips]=""
  [deadlocks]=""
  [hull-loss]=""
  [compare]=""
  [peers]=""
)
order=(burglary-errors burglary-errors-1m predicate-errors speedup speedup-1m breakdown flips deadlocks hull-loss compare peers)
[ $# -gt 0 ] && order=("$@")
for run in "${order[@]}"; do
  study="${run%-1m}"
  dir="$out/$run"
  mkdir -p "$dir"
  echo "== dtlab experiment $study --out $dir ${args[$run]} ($(date -u +%H:%M:%S))"
  # shellcheck disable=SC2086
  "$dtlab" experiment "$study" --out "$dir" ${args[$run]} --resume >"$dir/$study.stdout" \
    2>"$dir/$study.log" || echo "   $run failed: see $dir/$study.log"
done
echo "== done ($(date -u +%H:%M:%S))"
