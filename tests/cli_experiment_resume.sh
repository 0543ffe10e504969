#!/usr/bin/env bash
# dtlab experiment --resume: keeps the finished rows of an interrupted study (a cut last line is
# dropped), runs only the others, runs failed ones again, reads an older CSV whose columns are a
# subset of today's, moves rows of other parameters aside, and matches a parallel row written
# before the key named the distribution with the one it ran with. Also: --list names every study;
# a bad study, input, location, distribution, --threads for a sequential study or an unwritable directory is an
# error (exit 2) with a message.
set -euo pipefail
dtlab="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "$*"; exit 1; }
ran() { grep -c '^\[' "$1" || true; }
"$dtlab" experiment flips --quick --out "$dir/full" >/dev/null 2>&1
csv="$dir/full/flips.csv"
total=$(($(wc -l <"$csv") - 1))
[ "$total" -ge 3 ] || fail "flips --quick planned $total runs"
keys() { cut -d, -f1 "$1" | sort; }

# An interrupted run: the header, the first finished row and 40 bytes of the second.
mkdir "$dir/cut"
head -n 2 "$csv" >"$dir/cut/flips.csv"
sed -n 3p "$csv" | head -c 40 >>"$dir/cut/flips.csv"
"$dtlab" experiment flips --quick --resume --out "$dir/cut" >/dev/null 2>"$dir/resume.err"
grep -q "1 finished rows kept, 1 cut lines dropped" "$dir/resume.err" || fail "$(cat "$dir/resume.err")"
[ "$(ran "$dir/resume.err")" -eq $((total - 1)) ] || fail "resume ran $(ran "$dir/resume.err") runs"
[ "$(sed -n 2p "$dir/cut/flips.csv")" = "$(sed -n 2p "$csv")" ] || fail "the kept row changed"
diff <(keys "$csv") <(keys "$dir/cut/flips.csv") >/dev/null || fail "resume lost or added runs"

# A finished study: resuming runs nothing.
"$dtlab" experiment flips --quick --resume --out "$dir/cut" >/dev/null 2>"$dir/again.err"
[ "$(ran "$dir/again.err")" -eq 0 ] || fail "resuming a finished study ran $(ran "$dir/again.err") runs"

# A failed run is run again; an older CSV without a column is read (the cell stays empty); rows
# of other parameters (here: a size this plan does not have) are moved aside.
mkdir "$dir/old"
python3 - "$csv" "$dir/old/flips.csv" <<'PY'
import csv, sys
rows = list(csv.reader(open(sys.argv[1], newline="")))
header = rows[0]
drop = header.index("options.audit")
status = header.index("status")
rows[1][status] = "error"
other = list(rows[2])
other[0] = "other-" + other[0]
rows.append(other)
with open(sys.argv[2], "w", newline="") as f:
    w = csv.writer(f, lineterminator="\n")
    for r in rows:
        w.writerow(r[:drop] + r[drop + 1:])
PY
"$dtlab" experiment flips --quick --resume --out "$dir/old" >/dev/null 2>"$dir/old.err"
grep -q "1 failed runs to run again, 1 columns new in this version" "$dir/old.err" ||
  fail "$(cat "$dir/old.err")"
grep -q "1 rows of other parameters moved to" "$dir/old.err" || fail "$(cat "$dir/old.err")"
[ "$(ran "$dir/old.err")" -eq 1 ] || fail "the old CSV's resume ran $(ran "$dir/old.err") runs"
[ "$(($(wc -l <"$dir/old/flips.other-runs.csv") - 1))" -eq 1 ] || fail "no row moved aside"
diff <(keys "$csv") <(keys "$dir/old/flips.csv") >/dev/null || fail "old CSV: runs differ"

# Keys written before the distribution joined them: a parallel row is matched with the
# distribution it ran with. The walk mode's default was static then and is blocks now, so those
# rows are moved aside and run again; the DAG mode's (static then and now) are kept.
"$dtlab" experiment speedup --quick --out "$dir/dist" --no-plot >/dev/null 2>&1
mkdir "$dir/olddist"
moved=$(python3 - "$dir/dist/speedup.csv" "$dir/olddist/speedup.csv" <<'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1], newline="")))
moved = 0
for r in rows:
    if r["method"] != "sequential":
        assert r["run_key"].endswith("/" + r["distribution"]), r["run_key"]
        r["run_key"] = r["run_key"][: -len("/" + r["distribution"])]
        if r["location"] == "walk":
            assert r["distribution"] == "blocks", r["distribution"]
            r["distribution"] = "static"
            moved += 1
with open(sys.argv[2], "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()), lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
print(moved)
PY
)
[ "$moved" -ge 1 ] || fail "speedup --quick has no parallel walk-mode run"
"$dtlab" experiment speedup --quick --resume --out "$dir/olddist" --no-plot >/dev/null 2>"$dir/olddist.err"
grep -q "$moved rows of other parameters moved to" "$dir/olddist.err" || fail "$(cat "$dir/olddist.err")"
[ "$(ran "$dir/olddist.err")" -eq "$moved" ] ||
  fail "old keys: resume ran $(ran "$dir/olddist.err") runs, not $moved"
diff <(keys "$dir/dist/speedup.csv") <(keys "$dir/olddist/speedup.csv") >/dev/null ||
  fail "old keys: runs differ"

listed=$("$dtlab" experiment --list | awk '{print $1}' | tr '\n' ' ')
[ "$listed" = "burglary-errors predicate-errors speedup breakdown flips deadlocks hull-loss compare peers " ] ||
  fail "--list: $listed"
expect_error() {
  local pattern="$1"
  shift
  set +e
  "$dtlab" "$@" >/dev/null 2>"$dir/err"
  local code=$?
  set -e
  [ "$code" -eq 2 ] || fail "$* exited $code"
  grep -q "$pattern" "$dir/err" || fail "$*: no '$pattern' in: $(cat "$dir/err")"
}
expect_error "unknown study" experiment no-such-study --out "$dir/x"
expect_error "neither a generator family" experiment flips --quick --inputs no_such_model --out "$dir/x"
expect_error "out DIR is required" experiment flips --quick
expect_error "unknown location" experiment flips --quick --location sideways --out "$dir/x"
expect_error "unknown distribution" experiment speedup --quick --distribution diagonal --out "$dir/x"
expect_error "takes no --threads" experiment flips --quick --threads 2 --out "$dir/x"
touch "$dir/file"
expect_error "Not a directory" experiment flips --quick --out "$dir/file/sub"
