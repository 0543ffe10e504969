#!/usr/bin/env bash
# ns per predicate call of every kernel, with the adaptive kernel of an earlier commit beside the
# current one, measured in one run: both bench/predicates_bench binaries alternate for ROUNDS
# rounds (default 5) and the table gives the median per row.
#   tools/predicates_ns_table.sh [BASE_COMMIT] [ROUNDS]
# BASE_COMMIT (default af8950d, the last commit before the predicates rewrite) is built in a
# temporary git worktree with the release preset's flags; the current tree must be built already
# (cmake --preset release -DDTLAB_BUILD_BENCH=ON && cmake --build --preset release).
set -euo pipefail
cd "$(dirname "$0")/.."
base="${1:-af8950d}"
rounds="${2:-5}"
current=build/release/bench/predicates_bench
[ -x "$current" ] || { echo "build the release preset with DTLAB_BUILD_BENCH=ON first" >&2; exit 2; }
work="$(mktemp -d)"
trap 'git worktree remove --force "$work/src" >/dev/null 2>&1 || true; rm -rf "$work"' EXIT
git worktree add --detach "$work/src" "$base" >/dev/null 2>&1
(cd "$work/src" && cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DDTLAB_BUILD_BENCH=ON \
  -DDTLAB_BUILD_TESTS=OFF >/dev/null && cmake --build build -j"$(nproc)" --target predicates_bench >/dev/null)
previous="$work/src/build/bench/predicates_bench"
for r in $(seq 1 "$rounds"); do
  "$previous" --benchmark_format=csv 2>/dev/null | sed "s/^/previous,$r,/" >>"$work/runs.csv"
  "$current" --benchmark_format=csv 2>/dev/null | sed "s/^/current,$r,/" >>"$work/runs.csv"
done
python3 - "$work/runs.csv" "$base" "$rounds" <<'PY'
import csv, statistics, sys, subprocess
rows = {}
for line in open(sys.argv[1]):
    parts = next(csv.reader([line]))
    if len(parts) < 6 or parts[2] == "name": continue
    build, name, ns = parts[0], parts[2], float(parts[5])
    rows.setdefault((build, name), []).append(ns)
head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "?")
print(f"ns per call, median of {sys.argv[3]} alternating rounds; {cpu}, {subprocess.run(['nproc'], capture_output=True, text=True).stdout.strip()} cores;")
print(f"previous = {sys.argv[2]}, current = {head} (+ working tree). Arg 0: random points in the unit cube; arg 1: rounded points on a sphere.\n")
print("| predicate | input | fast | adaptive (previous) | adaptive | filtered | exact |")
print("|---|---|---|---|---|---|---|")
def med(build, name):
    v = rows.get((build, name))
    return f"{statistics.median(v):.1f}" if v else "-"
for pred in ("orient3d", "insphere"):
    for arg, label in (("0", "random"), ("1", "near-sphere")):
        print(f"| {pred} | {label} | {med('current', f'{pred}<FastKernel>/{arg}')} | "
              f"{med('previous', f'{pred}<AdaptiveKernel>/{arg}')} | {med('current', f'{pred}<AdaptiveKernel>/{arg}')} | "
              f"{med('current', f'{pred}<FilteredKernel>/{arg}')} | {med('current', f'{pred}<ExactKernel>/{arg}')} |")
PY
