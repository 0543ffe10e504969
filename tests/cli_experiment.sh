#!/usr/bin/env bash
# dtlab experiment NAME --quick: every run finishes, and the CSV (its columns), the summary table,
# the plot and the machine record are written (tools/check_study_output.py); the table printed on
# stdout is the one written to NAME.md.
set -euo pipefail
dtlab="$1"
name="$2"
tools="$(cd "$(dirname "$0")/../tools" && pwd)"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$dtlab" experiment "$name" --quick --out "$dir/out" >"$dir/stdout" 2>"$dir/stderr" || {
  cat "$dir/stderr"; exit 1; }
"$tools/check_study_output.py" "$dir/out" "$name"
cmp "$dir/stdout" "$dir/out/$name.md"
