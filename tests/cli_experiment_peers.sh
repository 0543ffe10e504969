#!/usr/bin/env bash
# dtlab experiment peers: every outcome is classified as what it is.
# 1. Stand-in TetGen programs (--tetgen), one per outcome, whatever the installed tools do: one
#    that kills itself (crashed, with the signal), one that writes a one-tetrahedron mesh
#    (invalid: missing points), one that writes ids out of range (invalid: bad output), one that
#    says why and exits 3 (refused, with its message), one that sleeps past --timeout (hung, its
#    process and scratch folder gone afterwards), and the real program through a wrapper (valid),
#    also on duplicates (whose output nodes TetGen numbers afresh).
# 2. The installed tools on inputs where Debian 12's versions fail (tools/versions in
#    docs/experiments.md): Qhull Qt returns an invalid mesh of a 7x7x7 grid and crashes on points
#    scaled by 1e150, where CGAL on plain doubles loops (hung at --timeout 3).
#    --resume keeps those rows (they are results) instead of running them again.
# 3. Bad options: an unknown tool, a missing TetGen, --tools for another study: exit 2 and a message.
set -euo pipefail
dtlab="$1"
dir=$(mktemp -d)
export TMPDIR="$dir/tmp"
mkdir -p "$TMPDIR" "$dir/bin"
trap 'rm -rf "$dir"' EXIT
fail() { echo "FAIL: $*"; exit 1; }

stand_in() {  # NAME BODY: a TetGen stand-in called as `NAME -Q FILE.node`
  printf '#!/bin/sh\nnode="$2"\nele="${node%%.node}.1.ele"\n%s\n' "$2" >"$dir/bin/$1"
  chmod +x "$dir/bin/$1"
}
stand_in crash 'kill -SEGV $$'
stand_in one_tet 'printf "1 4 0\n0 0 1 2 3\n" >"$ele"'
stand_in bad_ids 'printf "1 4 0\n0 0 1 2 999999\n" >"$ele"'
stand_in refuse 'echo "Error: the stand-in refuses these points" >&2; exit 3'
stand_in sleeper 'exec sleep 31.25'
stand_in honest "exec tetgen \"\$@\""

# outcome CSV INPUT TOOL: the outcome column of that run; error likewise.
cell() {
  python3 - "$1" "$2" "$3" "$4" <<'PY'
import csv, sys
path, input_name, tool, column = sys.argv[1:]
rows = [r for r in csv.DictReader(open(path, newline=""))
        if r["input"] == input_name and r["variant"] == tool]
assert len(rows) == 1, "%d rows of %s %s" % (len(rows), input_name, tool)
print(rows[0][column])
PY
}

run_stand_in() {  # NAME EXPECTED [extra options]
  local name="$1" expected="$2"
  shift 2
  "$dtlab" experiment peers --tools tetgen --tetgen "$dir/bin/$name" --inputs uniform \
    --sizes 300 --seeds 1 --no-plot --out "$dir/$name" "$@" >/dev/null 2>"$dir/$name.err" ||
    fail "$name: $(cat "$dir/$name.err")"
  local got
  got=$(cell "$dir/$name/peers.csv" uniform tetgen outcome)
  [ "$got" = "$expected" ] || fail "$name: outcome $got, expected $expected"
  echo "stand-in $name: $got ($(cell "$dir/$name/peers.csv" uniform tetgen error))"
}

run_stand_in crash crashed
cell "$dir/crash/peers.csv" uniform tetgen error | grep -q "signal 11 (SEGV)" || fail "crash: no signal"
run_stand_in one_tet invalid
[ "$(cell "$dir/one_tet/peers.csv" uniform tetgen validation.missing_points)" -gt 0 ] ||
  fail "one_tet: no missing points counted"
run_stand_in bad_ids invalid
cell "$dir/bad_ids/peers.csv" uniform tetgen error | grep -q "unreadable mesh" || fail "bad_ids: no reason"
run_stand_in refuse refused
cell "$dir/refuse/peers.csv" uniform tetgen error | grep -q "exit code 3: Error: the stand-in refuses" ||
  fail "refuse: the message is not in the row"
start=$(date +%s)
run_stand_in sleeper hung --timeout 2
[ $(($(date +%s) - start)) -lt 20 ] || fail "sleeper: the timeout did not end the run"
sleep 0.5
! pgrep -f "sleep 31.25" >/dev/null || fail "sleeper: the tool's process outlived its run"
[ -z "$(ls "$TMPDIR" | grep dtlab-run- || true)" ] || fail "a run's scratch folder was left behind"
if command -v tetgen >/dev/null; then
  run_stand_in honest valid
  [ "$(cell "$dir/honest/peers.csv" uniform tetgen validation.valid)" = true ] || fail "honest: not valid"
  # TetGen drops duplicates and numbers its output nodes afresh: they are mapped back to input ids.
  "$dtlab" experiment peers --tools tetgen --inputs duplicates --sizes 300 --seeds 1 --no-plot \
    --out "$dir/dups" >/dev/null 2>&1 || fail "tetgen on duplicates"
  [ "$(cell "$dir/dups/peers.csv" duplicates tetgen outcome)" = valid ] ||
    fail "tetgen duplicates: $(cell "$dir/dups/peers.csv" duplicates tetgen outcome)"
fi

# The installed tools where they fail.
"$dtlab" experiment peers --tools qhull-Qt,cgal-doubles,cgal-epick --inputs grid,huge --sizes 300 \
  --seeds 1 --timeout 3 --no-plot --out "$dir/real" >/dev/null 2>"$dir/real.err" ||
  fail "real tools: $(cat "$dir/real.err")"
csv="$dir/real/peers.csv"
[ "$(cell "$csv" grid qhull-Qt outcome)" = invalid ] || fail "qhull-Qt grid: $(cell "$csv" grid qhull-Qt outcome)"
[ "$(cell "$csv" huge qhull-Qt outcome)" = crashed ] || fail "qhull-Qt huge: $(cell "$csv" huge qhull-Qt outcome)"
[ "$(cell "$csv" huge cgal-doubles outcome)" = hung ] || fail "cgal-doubles huge: $(cell "$csv" huge cgal-doubles outcome)"
[ "$(cell "$csv" huge cgal-epick outcome)" = valid ] || fail "cgal-epick huge: $(cell "$csv" huge cgal-epick outcome)"
grep -qE '^\| grid \| [0-9,]+ \| yes \|' "$dir/real/peers.md" || fail "no grid row in the summary"
echo "installed tools: qhull-Qt grid invalid, huge crashed; cgal-doubles huge hung; cgal-epick valid"
# A refused, crashed or hung peer is a result: --resume keeps it and runs nothing.
"$dtlab" experiment peers --tools qhull-Qt,cgal-doubles,cgal-epick --inputs grid,huge --sizes 300 \
  --seeds 1 --timeout 3 --no-plot --resume --out "$dir/real" >/dev/null 2>"$dir/resume.err"
[ "$(grep -c '^\[' "$dir/resume.err" || true)" -eq 0 ] || fail "--resume ran peers again: $(cat "$dir/resume.err")"

# Bad options.
expect_error() {  # MESSAGE ARGS...
  local message="$1"
  shift
  set +e
  "$dtlab" experiment "$@" --no-plot --out "$dir/bad" >/dev/null 2>"$dir/bad.err"
  local code=$?
  set -e
  [ "$code" -eq 2 ] || fail "$*: exit $code"
  grep -q "$message" "$dir/bad.err" || fail "$*: $(cat "$dir/bad.err")"
}
expect_error "unknown tool nosuch" peers --tools nosuch --quick
expect_error "no program $dir/bin/absent" peers --tools tetgen --tetgen "$dir/bin/absent" --quick
expect_error "takes neither" flips --tools tetgen --quick
expect_error "peers takes no --location" peers --location dag --quick
echo "cli_experiment_peers: all outcomes classified"
