#!/usr/bin/env bash
# Thread scaling on a machine with enough cores (the lent 16-core machine; docs/performance-log.md):
#  1. bench/cgal_compare over the thread counts: the sequential walk, every lock method in walk mode
#     and CGAL (sequential and parallel at the same thread count), interleaved, medians of 3;
#  2. burglary, then star splaying (--repair), per insertion, thread count and seed: the run's
#     seconds, the repair's seconds and what was found (by the post-check or the repair's scan).
# Usage: tools/scaling_runs.sh OUTDIR [INPUT] [THREADS] [INSERTION] [PARTS]
#   INPUT     generator spec or point file (default uniform:1000000)
#   THREADS   comma-separated thread counts (default 2,4,8,16)
#   INSERTION what cgal_compare and the repair runs use: cavity, flips or both (default cavity)
#   PARTS     compare, repair or both (default both). Each repair run also runs the post-check's
#             exact validation twice (not timed in the run; about 20 s each at 1M points here).
# DTLAB_BIN names the build directory (default build/release); DTLAB_METHODS the lock methods
# (default all five; burglary's runs include its post-check, untimed but long at 1M points);
# DTLAB_REPAIR_SEEDS the repair runs' seeds (default "1 2 3"); DTLAB_REPAIR_MODES their --repair
# modes (default "splay"; "splay flips-splay" runs both, alternating per seed).
set -euo pipefail
out=${1:?usage: tools/scaling_runs.sh OUTDIR [INPUT] [THREADS] [INSERTION] [PARTS]}
input=${2:-uniform:1000000}
IFS=, read -r -a thread_counts <<<"${3:-2,4,8,16}"
insertion=${4:-cavity}
parts=${5:-both}
bin=${DTLAB_BIN:-build/release}
mkdir -p "$out"
tag=$(echo "$input" | tr ':/' '__')

{
  echo "date: $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "tree's commit: $(git rev-parse --short HEAD 2>/dev/null || echo unknown) (the binaries' own: DTLAB_BUILT_AT=${DTLAB_BUILT_AT:-not given})"
  echo "cpus available: $(nproc)"
  grep -m1 'model name' /proc/cpuinfo || true
  grep MemTotal /proc/meminfo || true
} | tee "$out/machine_$tag.txt"

methods=pessimistic,optimistic-detect,optimistic-prevent,burglary,batch
methods=${DTLAB_METHODS:-$methods}
if [[ $parts != repair ]]; then
  echo "== cgal_compare $input --threads ${3:-2,4,8,16} --methods $methods --insertion $insertion"
  "$bin/bench/cgal_compare" "$input" --repeat 3 --threads "${3:-2,4,8,16}" --methods "$methods" \
    --no-dag --insertion "$insertion" 2>&1 | tee "$out/compare_$tag.txt"
fi
[[ $parts == compare ]] && exit 0

# One JSON line per run: what the repair cost against the run it repaired.
repairs="$out/repair_$tag.jsonl"
: >"$repairs"
repair_insertions=$insertion
[[ $insertion == both ]] && repair_insertions="flips cavity"
for ins in $repair_insertions; do
for t in "${thread_counts[@]}"; do
  for seed in ${DTLAB_REPAIR_SEEDS:-1 2 3}; do
  for mode in ${DTLAB_REPAIR_MODES:-splay}; do
    stats=$(mktemp)
    "$bin/cli/dtlab" triangulate "$input" --location walk --insertion "$ins" --method burglary \
      --threads "$t" --repair="$mode" --seed "$seed" --stats "$stats" >/dev/null
    python3 - "$stats" "$t" "$seed" "$ins" >>"$repairs" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
splay = s.get("splay", {})
check = s.get("post_check", {})
print(json.dumps({
    "insertion": sys.argv[4], "threads": int(sys.argv[2]), "seed": int(sys.argv[3]),
    "repair": s.get("repair"),
    "seconds_total": s["seconds"]["total"],
    "seconds_repair": check.get("seconds_repair"),
    "seconds_scan": splay.get("seconds_scan"),
    "non_delaunay_faces_found": splay.get("non_delaunay_faces"),
    # True where those faces are the post-check's (no scan of the repair's own).
    "found_by_post_check": splay.get("found_by_post_check"),
    "stars": splay.get("stars"),
    # --repair=flips-splay: the exact flips first, and the faces they left to the stars.
    "flips": splay.get("flips"),
    "faces_left": splay.get("faces_left"),
    "seconds_flipping": splay.get("seconds_flipping"),
    # True where the post-check's validation already proved the mesh the unique one: no scan.
    "proven_by_post_check": splay.get("proven_by_post_check"),
    "seconds_check": check.get("seconds_check"),
    "non_delaunay_faces_after": check.get("non_delaunay_faces_after"),
    "reflex_boundary_edges_after": check.get("reflex_boundary_edges_after"),
    "mesh_consistent_after": check.get("mesh_consistent_after"),
}))
EOF
    rm -f "$stats"
  done
  done
done
done
cat "$repairs"
