#!/usr/bin/env bash
# What plain floating point does per family: for each generator family, triangulate with the fast,
# the adaptive and the filtered kernel and validate exactly. Prints a Markdown table, one row per
# family and kernel. KERNELS="fast adaptive" restricts the kernels.
# Usage: tools/robustness_table.sh [N] [SEED]
set -euo pipefail
dtlab="${DTLAB:-build/release/cli/dtlab}"
n="${1:-20000}"
seed="${2:-1}"
kernels="${KERNELS:-fast adaptive filtered}"
echo "| family | kernel | abandoned | non-Delaunay faces | consistent | valid | seconds |"
echo "|---|---|---:|---:|---|---|---:|"
for family in uniform normal cluster grid sphere planes cospherical duplicates near-duplicates lattice tiny huge; do
  for kernel in $kernels; do
    # Exit code 1 means "invalid", which is a result here, not a failure of the script.
    json=$("$dtlab" triangulate "$family:$n" --seed "$seed" --predicates "$kernel" --validate --stats - 2>/dev/null) || true
    if [ -n "$json" ]; then
      "$(dirname "$0")/stats_row.py" robustness "$family" "$kernel" <<<"$json"
    else
      echo "| $family | $kernel | error | | | | |"
    fi
  done
done
