#!/usr/bin/env bash
# Every bad input gets a clear message and exit code 2, never a crash (exit >= 128) or a hang.
set -u
dtlab="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0
expect() {  # expect CODE MESSAGE-FRAGMENT -- args...
  local code="$1" fragment="$2"
  shift 3
  if [ -z "$fragment" ]; then echo "FAIL: an empty fragment matches every message"; failures=$((failures + 1)); fi
  local out
  out=$(timeout 60 "$dtlab" "$@" 2>&1 >/dev/null)
  local got=$?
  if [ "$got" -ne "$code" ] || ! grep -qF -- "$fragment" <<<"$out"; then
    echo "FAIL: dtlab $* -> exit $got, stderr: $out (wanted $code and '$fragment')"
    failures=$((failures + 1))
  fi
}
printf '1 2 3\n4 nan 6\n' >"$dir/nan.xyz"
printf '0 0 0\n1 0 0\n0 1 0\n' >"$dir/three.xyz"
printf 'ply\nformat binary_little_endian 1.0\nelement vertex 5\nproperty double x\nproperty double y\nproperty double z\nend_header\nabc' >"$dir/trunc.ply"
expect 2 "cannot open" -- info "$dir/missing.xyz"
expect 2 "nan.xyz:2" -- info "$dir/nan.xyz"
expect 2 "truncated" -- triangulate "$dir/trunc.ply"
expect 2 "unknown generator" -- info "nosuch:100"
expect 2 "out of range" -- triangulate "uniform:0"
expect 2 "dimension" -- triangulate "$dir/three.xyz" -o "$dir/out.ele"
expect 2 "coplanar" -- triangulate "coplanar:1000" -o "$dir/out.ele"
expect 2 "collinear" -- triangulate "collinear:1000"
expect 2 "must end in" -- triangulate "uniform:100" -o "$dir/out.txt"
# An output path that is a folder with a file in it: the rename fails (it aborted until 2026-11-28).
mkdir -p "$dir/taken.ele" && touch "$dir/taken.ele/keep"
expect 2 "cannot rename the finished output into place" -- triangulate "uniform:100" -o "$dir/taken.ele"
expect 2 "needs --location walk" -- triangulate "uniform:100" --location dag --insertion cavity
expect 2 "--location excludes --paper" -- triangulate "uniform:100" --paper --location walk
expect 2 "--insertion excludes --paper" -- triangulate "uniform:100" --paper --insertion cavity
expect 2 "insertion" -- triangulate "uniform:100" --location walk --insertion bowyer
expect 2 "--predicates: Check nosuch value in {adaptive" -- triangulate "uniform:100" --predicates nosuch
expect 2 "--predicates: Check nosuch value in {adaptive" -- predicates-audit "uniform:100" --predicates nosuch
expect 2 "not in {splay,flips-splay,flips,rebuild}" -- triangulate "uniform:100" --method burglary --repair=bogus
expect 2 "post-check" -- triangulate "uniform:100" --repair=flips
expect 2 "--watchdog: Value -1 is not a finite number at least 0" -- triangulate "uniform:100" --watchdog -1
expect 2 "--watchdog: Value nan is not a finite number at least 0" -- triangulate "uniform:100" --watchdog nan
expect 2 "--timeout: Value nan is not a finite number at least 0" -- experiment speedup --quick --timeout nan --out "$dir/study"
# An unsigned option given a negative number: CLI11 read -1 as 2^64 - 1 and ran with it.
expect 2 "--seed: Value -1 is negative" -- triangulate "uniform:100" --seed -1
expect 2 "--seed: Value -1 is negative" -- generate uniform 10 --seed -1 -o "$dir/out.xyz"
expect 2 "--max-flips: Value -1 is negative" -- triangulate "uniform:100" --max-flips -1
expect 2 "--seed: Value 18446744073709551616 is above 2^64 - 1" -- triangulate "uniform:100" --seed 18446744073709551616
# Output that could not be written is an error, not stats silently lost (exit 0 until 2026-11-30).
if [ -w /dev/full ]; then
  expect 2 "/dev/full: writing failed" -- triangulate "uniform:100" --stats /dev/full
  out=$(timeout 60 "$dtlab" triangulate "uniform:100" --stats - 2>&1 >/dev/full)
  got=$?
  if [ "$got" -ne 2 ] || ! grep -qF "writing to standard output failed" <<<"$out"; then
    echo "FAIL: dtlab triangulate uniform:100 --stats - >/dev/full -> exit $got, stderr: $out"
    failures=$((failures + 1))
  fi
else
  echo "cli_bad_input: /dev/full is not writable here: the failed-write cases are skipped"
fi
mkdir -p "$dir/folder.xyz"
expect 2 "folder.xyz: is a directory" -- triangulate "$dir/folder.xyz"
expect 2 "--grid-cells: Value 0 not in range 1 to 256" -- triangulate "uniform:100" --method lock-grid --location walk --grid-cells 0
expect 2 "--method lock-grid needs --location walk: its undo log keeps no DAG children" -- triangulate "uniform:100" --method lock-grid --location dag
expect 2 "--method partitioned needs --location walk" -- triangulate "uniform:100" --method partitioned --threads 2 --paper
expect 2 "need -o FILE" -- triangulate "uniform:100" --neighbors
expect 2 "--vtu: Check" -- triangulate "uniform:100" -o "$dir/x.vtu" --vtu base32
# More threads than the CPUs available can serve, for a method whose waits spin (docs/design.md,
# "Threads a CPU"): refused before the run, which took minutes or stalled.
# The CPUs as the engine counts them (the affinity mask; nproc may also follow OMP_NUM_THREADS).
cpus=$(python3 -c "import os; print(len(os.sched_getaffinity(0)))")
if [ $((32 * cpus + 1)) -le 1024 ]; then
  expect 2 "at most $((32 * cpus)) here (32 a CPU, $cpus CPU" -- triangulate "uniform:100" --method optimistic-detect --threads $((32 * cpus + 1))
  expect 2 "--threads $((32 * cpus + 1)): at most $((32 * cpus)) here" -- experiment speedup --quick --threads $((32 * cpus + 1)) --out "$dir/study"
fi
# The CPUs are the affinity mask's: on one CPU, 33 threads are too many.
if command -v taskset >/dev/null && taskset -c 0 true 2>/dev/null; then
  out=$(timeout 60 taskset -c 0 "$dtlab" triangulate "uniform:100" --method lock-grid --threads 33 2>&1 >/dev/null)
  got=$?
  if [ "$got" -ne 2 ] || ! grep -qF "at most 32 here (32 a CPU, 1 CPU available)" <<<"$out"; then
    echo "FAIL: taskset -c 0 dtlab ... --method lock-grid --threads 33 -> exit $got, stderr: $out"
    failures=$((failures + 1))
  fi
fi
if ls "$dir"/out.* "$dir"/taken.ele.tmp-* >/dev/null 2>&1; then echo "FAIL: an output file was left behind"; failures=$((failures + 1)); fi
echo "cli_bad_input: $failures failures"
[ "$failures" -eq 0 ]
