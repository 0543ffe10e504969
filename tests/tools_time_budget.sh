#!/usr/bin/env bash
# tools/time_budget.py reads the steps of a partitioned run from its --stats (the passes, their
# setups, the ordering and output): on 30,000 points at 2 threads it finds the passes of several
# parts, their setups and the passes after the rounds, and the steps it lists leave at most a
# quarter of the run's total unaccounted (a loose bound: the rest is about 2 %, and a busy machine
# must not fail the test).
set -euo pipefail
dtlab="$1"
tool="$2"
out=$(python3 "$tool" "$dtlab" --input uniform:30000 --threads 2 --rounds 1)
echo "$out"
python3 - "$out" <<'PY'
import re, sys
rows = {}
for line in sys.argv[1].splitlines():
    cells = [c.strip().strip("*") for c in line.strip().strip("|").split("|")]
    if len(cells) == 4 and cells[1] and re.fullmatch(r"-?[0-9.]+", cells[1]):
        rows[cells[0]] = float(cells[1])
assert rows["insertions in the rounds' passes of several parts"] > 0, "no pass of several parts"
assert rows["setups of the passes of several parts"] > 0, "no setup found"
assert rows["passes after the rounds"] > 0, "no pass after the rounds"
assert 0 <= rows["rest"] < 0.25 * rows["total"], rows
assert re.search(r"speedup [0-9.]+x", sys.argv[1])
print("ok")
PY
