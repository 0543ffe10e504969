#!/usr/bin/env bash
# dtlab experiment: --resume keeps the finished rows of an interrupted study (a cut last line is
# dropped) and runs only the others; --list names every study; a bad study, input or directory
# is an error (exit 2) with a message.
set -euo pipefail
dtlab="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$dtlab" experiment flips --quick --out "$dir/full" >/dev/null 2>&1
total=$(($(wc -l <"$dir/full/flips.csv") - 1))
[ "$total" -ge 3 ] || { echo "flips --quick planned $total runs"; exit 1; }
# An interrupted run: the header, the first finished row and half of the second.
mkdir "$dir/cut"
head -n 2 "$dir/full/flips.csv" >"$dir/cut/flips.csv"
sed -n 3p "$dir/full/flips.csv" | head -c 40 >>"$dir/cut/flips.csv"
"$dtlab" experiment flips --quick --resume --out "$dir/cut" >/dev/null 2>"$dir/resume.err"
grep -q "1 finished rows kept, a cut last line dropped" "$dir/resume.err"
ran=$(grep -c '^\[' "$dir/resume.err")
[ "$ran" -eq $((total - 1)) ] || { echo "resume ran $ran runs, expected $((total - 1))"; exit 1; }
[ "$(sed -n 2p "$dir/cut/flips.csv")" = "$(sed -n 2p "$dir/full/flips.csv")" ]
keys() { cut -d, -f1 "$1" | sort; }
diff <(keys "$dir/full/flips.csv") <(keys "$dir/cut/flips.csv")
# Resuming a finished study runs nothing.
"$dtlab" experiment flips --quick --resume --out "$dir/cut" >/dev/null 2>"$dir/again.err"
! grep -q '^\[' "$dir/again.err"

listed=$("$dtlab" experiment --list | awk '{print $1}' | tr '\n' ' ')
[ "$listed" = "burglary-errors predicate-errors speedup breakdown flips deadlocks hull-loss compare " ] || {
  echo "--list: $listed"; exit 1; }
expect_error() {
  local pattern="$1"
  shift
  set +e
  "$dtlab" "$@" >/dev/null 2>"$dir/err"
  local code=$?
  set -e
  [ "$code" -eq 2 ] || { echo "$* exited $code"; exit 1; }
  grep -q "$pattern" "$dir/err" || { echo "$*: no '$pattern' in: $(cat "$dir/err")"; exit 1; }
}
expect_error "unknown study" experiment no-such-study --out "$dir/x"
expect_error "neither a generator family" experiment flips --quick --inputs no_such_model --out "$dir/x"
expect_error "out DIR is required" experiment flips --quick
expect_error "unknown location" experiment flips --quick --location sideways --out "$dir/x"
touch "$dir/file"
expect_error "error" experiment flips --quick --out "$dir/file/sub"
