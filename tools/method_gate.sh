#!/usr/bin/env bash
# Issue 3's correctness gate, as a sweep: every parallel method of the registry (`dtlab methods`)
# that runs the location and insertion asked, at 1, 2, 4 and 8 threads (oversubscribed on small
# machines, on purpose) on every generator family and on the real models, adaptive kernel,
# validated exactly. Every method without a post-check must be valid; one with it (burglary) must
# be mesh-consistent after the run and valid after --repair=rebuild (flips, then the reported
# rebuild where they got stuck; the stats say which). Prints one line per failure and a summary;
# exit 1 on any.
# Usage: tools/method_gate.sh [N-per-family (5000)] [MAX-MODEL-POINTS (45000)] [SEED (1)]
# DTLAB_LOCATION=walk runs the sweep in walk mode (default: dag); DTLAB_INSERTION=cavity, with it,
# inserts by Bowyer-Watson cavities instead of flips.
set -uo pipefail
dtlab="${DTLAB:-build/release/cli/dtlab}"
data="${DTLAB_DATA:-../shared/data}"
n="${1:-5000}"
max_model="${2:-45000}"  # 0: no real models
seed="${3:-1}"
location="${DTLAB_LOCATION:-dag}"
insertion="${DTLAB_INSERTION:-flips}"
# The partitioned method's parts (ignored by the others): small, so that these inputs are cut.
points_per_part="${DTLAB_POINTS_PER_PART:-64}"
families="${DTLAB_FAMILIES:-uniform normal cluster grid sphere planes cospherical duplicates near-duplicates lattice tiny huge}"
inputs=()
for f in $families; do inputs+=("$f:$n"); done
for f in "$data"/*.ply "$data"/*.xyz "$data"/*.off "$data"/*.xz; do
  [ -f "$f" ] || continue
  count=$("$dtlab" info "$f" | sed -nE 's/^points: *([0-9]+).*/\1/p')
  if [ -n "$count" ] && [ "$count" -le "$max_model" ]; then inputs+=("$f"); fi
done
# The parallel methods that run this location and insertion, from the registry (dtlab methods:
# name, what, threads, location, insertion, post-check); those with the post-check run it.
mapfile -t methods < <("$dtlab" methods | awk -F'|' -v loc="$location" -v ins="$insertion" \
  'NR > 2 && $4 !~ /^ *1 *$/ && index($5, loc) && index($6, ins) {
     gsub(/[` ]/, "", $2); gsub(/ /, "", $7); print $2 ":" $7 }')
err=$(mktemp)
trap 'rm -f "$err"' EXIT
runs=0
failures=0
for input in "${inputs[@]}"; do
  for entry in "${methods[@]}"; do
    method="${entry%%:*}"
    for threads in 1 2 4 8; do
      runs=$((runs + 1))
      if [ "${entry#*:}" = yes ]; then
        json=$("$dtlab" triangulate "$input" --seed "$seed" --method "$method" --threads "$threads" \
          --location "$location" --insertion "$insertion" --points-per-part "$points_per_part" --repair=rebuild --validate --stats - 2>"$err")
        ok=$(python3 -c 'import json,sys; d=json.load(sys.stdin); print(int(d["post_check"]["mesh_consistent"] and d["validation"]["valid"] and d["abandoned_insertions"]==0))' <<<"$json" 2>/dev/null)
      else
        json=$("$dtlab" triangulate "$input" --seed "$seed" --method "$method" --threads "$threads" \
          --location "$location" --insertion "$insertion" --points-per-part "$points_per_part" --validate --stats - 2>"$err")
        ok=$(python3 -c 'import json,sys; d=json.load(sys.stdin); print(int(d["validation"]["valid"] and d["abandoned_insertions"]==0))' <<<"$json" 2>/dev/null)
      fi
      if [ "$ok" != 1 ]; then
        failures=$((failures + 1))
        echo "FAIL $input $method $threads: $(head -c 300 "$err") $(head -c 300 <<<"$json")"
      fi
    done
  done
done
echo "method gate: $runs runs on ${#inputs[@]} inputs, $failures failed"
[ "$failures" -eq 0 ]
