#!/usr/bin/env bash
# tools/time_budget.py reads the steps of a partitioned run from its --stats (the passes, their
# setups, the ordering and output): on 30,000 points at 2 threads it finds every step (the
# ordering, the rounds' passes of one part and of several, their setups, the passes after the
# rounds, the output), its "all insertions" row is the sum of the four insertion rows, the steps
# leave at most a quarter of the run's total unaccounted (a loose bound: the rest is about 2 %,
# and a busy machine must not fail the test), each "over" cell is the partitioned cell less the
# sequential one, a speedup is listed for each of the 3 rounds, and the sequential column is the sequential walk's own divided by the threads:
# runs of it beside take within a third of the threads times that column's total.
set -euo pipefail
dtlab="$1"
tool="$2"
out=$(python3 "$tool" "$dtlab" --input uniform:30000 --threads 2 --rounds 3)
echo "$out"
sequential_ideal=$(python3 - "$out" <<'PY'
import re, sys
rows, ideal, over = {}, {}, {}
for line in sys.argv[1].splitlines():
    cells = [c.strip().strip("*") for c in line.strip().strip("|").split("|")]
    if len(cells) != 4 or not re.fullmatch(r"-?[0-9.]+", cells[1]):
        continue
    rows[cells[0]] = float(cells[1])
    if cells[2]:
        ideal[cells[0]], over[cells[0]] = float(cells[2]), float(cells[3])
for step in ["ordering", "the rounds' passes of one part", "setups of the passes of several parts",
             "insertions in the rounds' passes of several parts", "passes after the rounds",
             "output"]:
    assert rows[step] > 0, f"no {step}: {rows}"
four = ["the rounds' passes of one part", "setups of the passes of several parts",
        "insertions in the rounds' passes of several parts", "passes after the rounds"]
assert abs(rows["all insertions (the four rows above)"] - sum(rows[k] for k in four)) < 0.0025, rows
assert 0 <= rows["rest"] < 0.25 * rows["total"], rows
assert set(ideal) == {"ordering", "all insertions (the four rows above)", "output", "total"}, ideal
for k in ideal:
    assert abs(1e3 * (rows[k] - ideal[k]) - over[k]) < 2, (k, rows[k], ideal[k], over[k])
assert re.search(r"speedup [0-9.]+x", sys.argv[1])
per_round = re.search(r"speedup per round: ([0-9., ]+); median ([0-9.]+)", sys.argv[1])
assert per_round and len(per_round.group(1).split(",")) == 3, "no speedup for each of the 3 rounds"
print(ideal["total"])
PY
)
# The sequential walk's own total (the median of 3 runs beside) against the column's total times
# the 2 threads: within a third either way (a column not divided by the threads is off by half).
totals=()
for _ in 1 2 3; do
  totals+=("$("$dtlab" triangulate uniform:30000 --location walk --insertion cavity \
    --method sequential --seed 1 --stats - |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["seconds"]["total"])')")
done
python3 -c "import statistics, sys
s = statistics.median(float(x) for x in sys.argv[2:])
i = 2 * float(sys.argv[1])
assert 0.67 * i <= s <= 1.5 * i, (s, i)" "$sequential_ideal" "${totals[@]}"
echo ok
