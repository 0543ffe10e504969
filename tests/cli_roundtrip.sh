#!/usr/bin/env bash
# triangulate -> .node/.ele and .vtu -> validate, and --stats - is pure JSON.
set -euo pipefail
dtlab="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$dtlab" triangulate grid:1000 -o "$dir/g.ele" --validate >/dev/null
"$dtlab" validate "$dir/g.node" "$dir/g.ele" >/dev/null
# --threads: the same report for 1 and 3 threads, on a mesh large enough to be split (some
# 33,000 tetrahedra; below 4,096 items a range runs on one thread); 0 is refused (exit 2).
"$dtlab" triangulate uniform:5000 -o "$dir/u.ele" >/dev/null
one=$("$dtlab" validate "$dir/u.node" "$dir/u.ele" --threads 1)
three=$("$dtlab" validate "$dir/u.node" "$dir/u.ele" --threads 3)
if [ "$one" != "$three" ]; then echo "validate --threads changed the report"; exit 1; fi
set +e
"$dtlab" validate "$dir/u.node" "$dir/u.ele" --threads 0 >/dev/null 2>&1
code=$?
set -e
if [ "$code" -ne 2 ]; then echo "validate --threads 0: exit $code, expected 2"; exit 1; fi
"$dtlab" triangulate sphere:2000 -o "$dir/s.vtu" --validate >/dev/null
grep -q 'Name="non_delaunay"' "$dir/s.vtu"
"$dtlab" triangulate uniform:2000 --stats - | python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["tetrahedra"] > 0 and d["inserted"] == 2000, d'
"$dtlab" triangulate duplicates:2000 --stats - --validate | python3 -c 'import json,sys; d=json.load(sys.stdin); assert d["duplicates"] == 1000 and d["validation"]["valid"], d'
# A mesh with one tetrahedron removed is reported invalid with exit code 1.
n=$(sed -n 2p "$dir/g.ele" | cut -d' ' -f1)
sed -i "3d; 2s/^$n /$((n - 1)) /" "$dir/g.ele"
set +e
"$dtlab" validate "$dir/g.node" "$dir/g.ele" >/dev/null 2>&1
code=$?
set -e
if [ "$code" -ne 1 ]; then echo "broken mesh: exit $code, expected 1"; exit 1; fi
echo "cli_roundtrip: ok"
