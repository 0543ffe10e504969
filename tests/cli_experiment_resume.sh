#!/usr/bin/env bash
# dtlab experiment --resume: keeps the finished rows of an interrupted study (a cut last line is
# dropped), runs only the others, runs failed ones again, reads an older CSV whose columns are a
# subset of today's, and moves rows of other parameters aside. Also: --list names every study;
# a bad study, input, location, --threads for a sequential study or an unwritable directory is an
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

listed=$("$dtlab" experiment --list | awk '{print $1}' | tr '\n' ' ')
[ "$listed" = "burglary-errors predicate-errors speedup breakdown flips deadlocks hull-loss compare " ] ||
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
expect_error "takes no --threads" experiment flips --quick --threads 2 --out "$dir/x"
touch "$dir/file"
expect_error "Not a directory" experiment flips --quick --out "$dir/file/sub"
