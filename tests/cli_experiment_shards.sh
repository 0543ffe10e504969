#!/usr/bin/env bash
# dtlab experiment --shard K/N and merge: a study run as 3 shards at once (GNU parallel when
# installed, else background jobs) and merged has the unsharded run's plan keys and summary
# tables (their headers and rows' first columns; the figures are timings and differ); merge
# refuses a missing, doubled or foreign shard, a whole study and a shard with a run missing (exit 2,
# a message naming it), a shard from another commit, a run in the wrong shard and a merge into a
# shard's own folder; --resume runs only that shard's missing run, and the merge then succeeds;
# tools/cluster/experiment.sbatch's tasks (Slurm's variables set by hand) give shards that merge.
set -euo pipefail
dtlab="$1"
tools="$(cd "$(dirname "$0")/../tools" && pwd)"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
study=predicate-errors
args=(experiment "$study" --quick --inputs uniform,grid,sphere --sizes 150)
keys() { python3 -c 'import csv,sys; print("\n".join(sorted(r["run_key"] for r in csv.DictReader(open(sys.argv[1])))))' "$1"; }
# The tables' shape: each header line, and each row's first two cells.
shape() { grep '^| ' "$1" | sed -E 's/^(\|[^|]*\|[^|]*\|).*/\1/'; grep '^| input' "$1"; }

"$dtlab" "${args[@]}" --out "$dir/whole" >/dev/null 2>"$dir/whole.err" || fail "$(cat "$dir/whole.err")"
if command -v parallel >/dev/null; then
  parallel --halt now,fail=1 "$dtlab" "${args[@]}" --shard {}/3 --out "$dir/s{}" '>/dev/null' \
    '2>'"$dir/s{}.err" ::: 1 2 3 || fail "a shard failed: $(cat "$dir"/s*.err)"
  echo "3 shards run by GNU parallel"
else
  for k in 1 2 3; do
    "$dtlab" "${args[@]}" --shard "$k/3" --out "$dir/s$k" >/dev/null 2>"$dir/s$k.err" &
  done
  wait || fail "a shard failed"
  echo "3 shards run as background jobs (no GNU parallel)"
fi
for k in 1 2 3; do
  [ ! -e "$dir/s$k/$study.md" ] || fail "shard $k wrote a summary of its slice"
  [ -s "$dir/s$k/$study.csv" ] || fail "shard $k wrote no rows"
done
"$dtlab" experiment merge "$dir/merged" "$dir/s1" "$dir/s2" "$dir/s3" >"$dir/merged.out" \
  2>"$dir/merged.err" || fail "merge: $(cat "$dir/merged.err")"
"$tools/check_study_output.py" "$dir/merged" "$study"
diff <(keys "$dir/whole/$study.csv") <(keys "$dir/merged/$study.csv") || fail "the merged runs differ"
diff <(shape "$dir/whole/$study.md") <(shape "$dir/merged/$study.md") || fail "the merged tables differ"
cmp "$dir/merged.out" "$dir/merged/$study.md" || fail "merge printed another table than it wrote"
grep -q "as 3 shards merged by" "$dir/merged/$study.md" || fail "the summary does not say it is merged"
[ "$(python3 -c 'import json,sys; print(len(json.load(open(sys.argv[1]))))' "$dir/merged/machines.json")" = 3 ] ||
  fail "machines.json lacks a shard's machine"
echo "merged: $(keys "$dir/merged/$study.csv" | wc -l) runs, the same keys and tables as unsharded"

refuse() {  # MESSAGE DIR...: merge exits 2 with MESSAGE
  local message="$1"
  shift
  set +e
  "$dtlab" experiment merge "$dir/refused" "$@" >/dev/null 2>"$dir/refuse.err"
  local code=$?
  set -e
  [ "$code" -eq 2 ] || fail "merge $*: exit $code, expected 2"
  grep -q -- "$message" "$dir/refuse.err" || fail "merge $*: $(cat "$dir/refuse.err")"
  echo "refused: $(cat "$dir/refuse.err")"
}
refuse "shards missing: 3 of 3" "$dir/s1" "$dir/s2"
refuse "shard 2/3 given twice" "$dir/s1" "$dir/s2" "$dir/s2" "$dir/s3"
refuse "is a whole study, not a shard" "$dir/s1" "$dir/s2" "$dir/whole"
"$dtlab" "${args[@]/sphere/normal}" --shard 3/3 --out "$dir/foreign" >/dev/null 2>&1
refuse 'is foreign: field "parameters" of its plan.json differs' "$dir/s1" "$dir/s2" "$dir/foreign"
"$dtlab" experiment hull-loss --quick --shard 3/3 --out "$dir/other" --no-plot >/dev/null 2>&1
refuse 'is foreign: field "study" of its plan.json differs' "$dir/s1" "$dir/s2" "$dir/other"

# A shard from another commit (its plan.json says so), and a run in the wrong shard's CSV.
cp -r "$dir/s3" "$dir/s3commit"
python3 - "$dir/s3commit/plan.json" <<'PY'
import json, sys
plan = json.load(open(sys.argv[1]))
plan["commit"] = "0" * 40
json.dump(plan, open(sys.argv[1], "w"))
PY
refuse 'is foreign: field "commit" of its plan.json differs' "$dir/s1" "$dir/s2" "$dir/s3commit"
cp -r "$dir/s3" "$dir/s3extra"
sed -n 2p "$dir/s1/$study.csv" >>"$dir/s3extra/$study.csv"
refuse "belongs to another shard" "$dir/s1" "$dir/s2" "$dir/s3extra"
set +e
"$dtlab" experiment merge "$dir/s1" "$dir/s1" "$dir/s2" "$dir/s3" >/dev/null 2>"$dir/refuse.err"
code=$?
set -e
[ "$code" -eq 2 ] && grep -q "is one of the shards' folders" "$dir/refuse.err" ||
  fail "merge into a shard's own folder: exit $code: $(cat "$dir/refuse.err")"

# A shard interrupted before its last run: the merge names the run, --resume runs only it.
head -n -1 "$dir/s2/$study.csv" >"$dir/cut.csv" && mv "$dir/cut.csv" "$dir/s2/$study.csv"
refuse "1 of the plan's .* runs are missing, e.g. .*(shard 2/3, $dir/s2): run that shard again with --resume" \
  "$dir/s1" "$dir/s2" "$dir/s3"
"$dtlab" "${args[@]}" --shard 2/3 --resume --out "$dir/s2" >/dev/null 2>"$dir/resume.err"
[ "$(grep -c '^\[' "$dir/resume.err")" -eq 1 ] || fail "--resume ran $(grep -c '^\[' "$dir/resume.err") runs, expected 1"
"$dtlab" experiment merge "$dir/merged2" "$dir/s3" "$dir/s1" "$dir/s2" >/dev/null 2>&1 ||
  fail "the merge after --resume failed"
diff <(keys "$dir/whole/$study.csv") <(keys "$dir/merged2/$study.csv") || fail "the resumed merge differs"
# The Slurm job array's script, its tasks run here one after the other as Slurm would set them.
for task in 0 1 2; do
  SLURM_ARRAY_TASK_ID=$task SLURM_ARRAY_TASK_COUNT=3 STUDY=hull-loss OUT="$dir/slurm" \
    DTLAB="$dtlab" "$tools/cluster/experiment.sbatch" --quick >/dev/null 2>&1 ||
    fail "experiment.sbatch task $task failed"
done
"$dtlab" experiment merge "$dir/slurm/merged" "$dir"/slurm/shard-* >/dev/null 2>&1 ||
  fail "the Slurm tasks' shards do not merge"
"$tools/check_study_output.py" "$dir/slurm/merged" hull-loss

set +e
"$dtlab" experiment "$study" --quick --shard 4/3 --out "$dir/bad" >/dev/null 2>"$dir/bad.err"
code=$?
set -e
[ "$code" -eq 2 ] && grep -q "K/N with 1 <= K <= N" "$dir/bad.err" || fail "--shard 4/3: exit $code"
echo "cli_experiment_shards: sharded, merged, refused and resumed as documented"
