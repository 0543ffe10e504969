#!/usr/bin/env bash
# Coordinate magnitudes that span a wide range are no reason to refuse: adaptive, filtered and exact
# decide every finite double exactly (adaptive and filtered hand what their expansion arithmetic
# cannot take to GMP). Each input must triangulate VALID with each of them.
set -u
dtlab="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
# An 8^3 grid on [0,1]^3 whose first point has x = 4.94e-324, the smallest subnormal.
awk 'BEGIN { for (i = 0; i < 8; ++i) for (j = 0; j < 8; ++j) for (k = 0; k < 8; ++k) {
  if (i + j + k == 0) printf "4.94e-324 0 0\n"; else printf "%.17g %.17g %.17g\n", i / 7, j / 7, k / 7 } }' \
  >"$dir/grid_subnormal.xyz"
# 1e-300 next to 1 (scaled losslessly), and 1e300 next to subnormals (no lossless scaling).
printf '0 0 0\n1 0 0\n0 1 0\n0 0 1\n1e-300 0.5 0.5\n' >"$dir/wide.xyz"
printf '0 0 0\n1e300 0 0\n0 1e300 0\n0 0 1e300\n4.94e-324 3e299 3e299\n1e300 1e300 1e300\n1e-310 1e300 2e299\n' \
  >"$dir/huge_and_subnormal.xyz"
[ "$(wc -l <"$dir/grid_subnormal.xyz")" -eq 512 ] || fail "grid_subnormal.xyz has not 512 lines"

for input in grid_subnormal wide huge_and_subnormal; do
  info=$(timeout 60 "$dtlab" info "$dir/$input.xyz" 2>&1) || fail "info $input: exit $?"
  grep -q "^expansion range: *no" <<<"$info" || fail "info $input does not report 'expansion range: no': $info"
  for kernel in adaptive filtered exact; do
    out=$(timeout 120 "$dtlab" triangulate "$dir/$input.xyz" --predicates "$kernel" --validate 2>&1)
    code=$?
    if [ "$code" -ne 0 ] || ! grep -q ": VALID;" <<<"$out"; then
      fail "triangulate $input --predicates $kernel -> exit $code: $out"
    fi
  done
done

# The same through a lock method, the .ele round trip, and the stats.
for kernel in adaptive filtered; do
  timeout 120 "$dtlab" triangulate "$dir/grid_subnormal.xyz" --predicates "$kernel" \
    --method optimistic-detect --threads 2 --validate >/dev/null 2>&1 ||
    fail "optimistic-detect, $kernel on grid_subnormal"
  timeout 120 "$dtlab" triangulate "$dir/grid_subnormal.xyz" --predicates "$kernel" \
    -o "$dir/g_$kernel.ele" >/dev/null 2>&1 || fail "triangulate -o, $kernel"
  timeout 120 "$dtlab" validate "$dir/g_$kernel.node" "$dir/g_$kernel.ele" >/dev/null 2>&1 ||
    fail "validate of the $kernel mesh"
  json=$(timeout 120 "$dtlab" triangulate "$dir/grid_subnormal.xyz" --predicates "$kernel" --validate --stats - 2>/dev/null)
  python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["scale_exponent"] == 99 and d["validation"]["valid"] and d["inserted"] == 512, d' <<<"$json" ||
    fail "stats of $kernel on grid_subnormal"
done

# The audit of the filtered kernel has the stage columns, gmp included.
audit=$(timeout 120 "$dtlab" predicates-audit "$dir/grid_subnormal.xyz" --predicates filtered 2>&1) ||
  fail "predicates-audit --predicates filtered: exit $?"
grep -q "stage gmp" <<<"$audit" || fail "audit table without a gmp column: $audit"

echo "cli_wide_magnitudes: $failures failures"
[ "$failures" -eq 0 ]
