#!/usr/bin/env bash
# README command (a): set up, build Release, and run the main job on a generated default input:
# facts about the points, the mesh with three kernels, validated, in the CLI's default
# configuration (walk location, cavity insertion: the fastest exact one) and once in the paper's
# (--paper: DAG location, flips), and a comparison with CGAL (the compare study's own defaults:
# walk with flips and with cavities, and DAG, as its table says).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release -DDTLAB_BUILD_TESTS=OFF -DDTLAB_BUILD_BENCH=OFF >/dev/null
cmake --build --preset release -j"$(nproc)" --target dtlab
dtlab=build/release/cli/dtlab
input="${1:-uniform:100000}"
seed="${SEED:-1}"
echo "== dtlab info $input --seed $seed"
"$dtlab" info "$input" --seed "$seed"
echo
status=0
for kernel in fast adaptive filtered; do
  echo "== dtlab triangulate $input --seed $seed --predicates $kernel --validate"
  code=0
  "$dtlab" triangulate "$input" --seed "$seed" --predicates "$kernel" --validate || code=$?
  # An invalid mesh (exit 1) is a result for the fast kernel; for the exact ones it is a failure.
  if [ "$code" -ne 0 ] && { [ "$kernel" != fast ] || [ "$code" -ne 1 ]; }; then status=1; fi
  echo
done
echo "== dtlab triangulate $input --seed $seed --paper --validate   (the paper's DAG location and flips)"
"$dtlab" triangulate "$input" --seed "$seed" --paper --validate || status=1
echo
# The short comparison: dtlab (walk, DAG, optimistic-detect on 2 threads) against CGAL on the
# same points, 2 interleaved rounds (dtlab experiment compare --quick; the table also goes to
# build/main/compare.md, with the CSV, the plot and machine.json).
if [[ "$input" =~ ^([a-z-]+):([0-9]+)$ ]]; then
  compare_input=(--inputs "${BASH_REMATCH[1]}" --sizes "${BASH_REMATCH[2]}")
else
  compare_input=(--inputs "$(realpath "$input")")
fi
echo "== dtlab experiment compare --quick ${compare_input[*]} --out build/main"
mkdir -p build/main
# Progress goes to build/main/compare.log; on failure it is shown.
if ! "$dtlab" experiment compare --quick "${compare_input[@]}" --out build/main \
  2>build/main/compare.log; then
  cat build/main/compare.log
  status=1
fi
exit "$status"
