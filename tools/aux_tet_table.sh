#!/usr/bin/env bash
# The paper's auxiliary tetrahedron vs the symbolic infinite vertex: hull tetrahedra lost.
# Usage: tools/aux_tet_table.sh [N] [SEEDS...]
set -euo pipefail
dtlab="${DTLAB:-build/release/cli/dtlab}"
n="${1:-20000}"
shift || true
seeds=("${@:-1 2 3}")
echo "| family | seed | tetrahedra (aux-tet) | hull tetrahedra lost |"
echo "|---|---:|---:|---:|"
for family in uniform normal cluster sphere grid; do
  for seed in ${seeds[@]}; do
    "$dtlab" triangulate "$family:$n" --seed "$seed" --bounding aux-tet --stats - 2>/dev/null |
      "$(dirname "$0")/stats_row.py" aux "$family" "$seed"
  done
done
