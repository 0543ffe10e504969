#!/usr/bin/env bash
# dtlab repair: the fast kernel's mesh of a sphere (consistent but not Delaunay: repaired locally,
# from its non-Delaunay faces), the same mesh with a tetrahedron listed twice (not a
# tetrahedralization: every vertex splayed) and a Delaunay mesh with one tetrahedron dropped (a
# hole) become the Delaunay mesh, equal to the exact triangulation, the same on 1 and on 3
# threads; burglary's --repair=flips-splay gives the exact mesh; a mesh that names a vertex the
# points do not have, or an unreadable file, is an error (exit 2).
set -euo pipefail
dtlab="$1"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
# The tetrahedra of an .ele as sorted vertex sets, one per line, sorted.
sorted() {
  python3 -c 'import sys
rows = [l.split() for l in open(sys.argv[1]) if l.strip() and not l.startswith("#")][1:]
print("\n".join(sorted(" ".join(sorted(r[1:5], key=int)) for r in rows)))' "$1"
}
"$dtlab" triangulate sphere:3000 -o "$dir/exact.ele" >/dev/null
"$dtlab" triangulate sphere:3000 --predicates fast -o "$dir/fast.ele" >/dev/null
if "$dtlab" validate "$dir/fast.node" "$dir/fast.ele" >/dev/null 2>&1; then
  echo "the fast kernel's sphere mesh was valid: the test repairs nothing"; exit 1
fi
"$dtlab" repair "$dir/fast.node" "$dir/fast.ele" -o "$dir/repaired.ele" --validate \
  --stats "$dir/stats.json" >/dev/null
# Locally exactly where the validator calls the input a consistent tetrahedralization (it did here,
# with GCC 12 on x86-64: the fast kernel's rounding decides it), with stars only around its faces.
"$dtlab" validate "$dir/fast.node" "$dir/fast.ele" >"$dir/fast_report.json" || true
python3 -c 'import json,sys
d = json.load(open(sys.argv[1]))
consistent = json.load(open(sys.argv[2]))["consistent"]
assert d["validation_valid"] and d["local"] == consistent, (d, consistent)
assert not consistent or (0 < d["stars"] < 3000 and d["non_delaunay_faces"] > 0), d' \
  "$dir/stats.json" "$dir/fast_report.json"
diff <(sorted "$dir/exact.ele") <(sorted "$dir/repaired.ele") >/dev/null
# The first tetrahedron twice: its faces in three tetrahedra or twice on one side, no
# tetrahedralization, so every vertex gets a star.
python3 -c 'import sys
lines = [l for l in open(sys.argv[1]) if not l.startswith("#")]
n = int(lines[0].split()[0])
first = lines[1].split()
open(sys.argv[2], "w").write("%d 4 0\n" % (n + 1) + "".join(lines[1:n + 1]) +
                             "%d %s\n" % (n + int(first[0]), " ".join(first[1:5])))' \
  "$dir/fast.ele" "$dir/doubled.ele"
"$dtlab" repair "$dir/fast.node" "$dir/doubled.ele" -o "$dir/undoubled.ele" --validate \
  --stats "$dir/doubled.json" >/dev/null
python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); assert d["validation_valid"] and not d["local"] and d["stars"] == 3000, d' "$dir/doubled.json"
diff <(sorted "$dir/exact.ele") <(sorted "$dir/undoubled.ele") >/dev/null
# The stars built on 1 and on 3 threads, locally and everywhere: the same mesh, line for line, and
# the same counts.
for input in fast doubled; do
  for t in 1 3; do
    "$dtlab" repair "$dir/fast.node" "$dir/$input.ele" --threads "$t" -o "$dir/t$t.ele" \
      --stats "$dir/t$t.json" >/dev/null
  done
  cmp "$dir/t1.ele" "$dir/t3.ele"
  python3 -c 'import json,sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
assert all(a[k] == b[k] for k in ("local", "stars", "offers", "changes", "bridges")), (a, b)' \
    "$dir/t1.json" "$dir/t3.json"
done
# Burglary's repair with exact flips first: the exact mesh, the flips' line printed, the counts in
# the stats (oversubscribed threads with delays: burglary's damage is likely, not certain).
"$dtlab" triangulate sphere:3000 --method burglary --threads 4 --stress --repair=flips-splay \
  -o "$dir/hybrid.ele" --stats "$dir/hybrid.json" >"$dir/hybrid.txt"
diff <(sorted "$dir/exact.ele") <(sorted "$dir/hybrid.ele") >/dev/null
python3 -c 'import json,sys
d = json.load(open(sys.argv[1]))
s = d["splay"]
assert d["repair"] == "flips-splay", d["repair"]
# The flips ran wherever the post-check found damage; stars only from the faces they left.
assert s["proven_by_post_check"] or s["flipped"], s
assert (s["stars"] > 0) == (s["faces_left"] > 0), s' "$dir/hybrid.json"
if python3 -c 'import json,sys; sys.exit(0 if json.load(open(sys.argv[1]))["splay"]["flipped"] else 1)' \
  "$dir/hybrid.json"; then
  grep -q "repair (flips before the stars):" "$dir/hybrid.txt"
fi
# A hole: the first tetrahedron dropped.
python3 -c 'import sys
lines = [l for l in open(sys.argv[1]) if not l.startswith("#")]
n = int(lines[0].split()[0])
open(sys.argv[2], "w").write("%d 4 0\n" % (n - 1) + "".join(lines[2:]))' "$dir/exact.ele" "$dir/hole.ele"
"$dtlab" repair "$dir/exact.node" "$dir/hole.ele" -o "$dir/filled.ele" >/dev/null
diff <(sorted "$dir/exact.ele") <(sorted "$dir/filled.ele") >/dev/null
# Errors: a vertex id beyond the points, a missing file.
printf '1 4 0\n0 0 1 2 99999\n' >"$dir/bad.ele"
set +e
"$dtlab" repair "$dir/exact.node" "$dir/bad.ele" >/dev/null 2>"$dir/err"
code=$?
"$dtlab" repair "$dir/exact.node" "$dir/missing.ele" >/dev/null 2>&1
code2=$?
set -e
if [ "$code" -ne 2 ] || [ "$code2" -ne 2 ]; then
  echo "bad mesh: exit $code and $code2, expected 2: $(cat "$dir/err")"; exit 1
fi
echo "cli_repair: ok"
