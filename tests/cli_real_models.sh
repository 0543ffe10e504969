#!/usr/bin/env bash
# Every real model in shared/data loads; the small ones triangulate and validate, in DAG and walk
# mode; the full dragon (2,100 duplicates) validates in walk mode, sequential and optimistic-detect.
set -euo pipefail
dtlab="$1"
data="$2"
if [ ! -d "$data" ]; then echo "no shared data at $data"; exit 1; fi
for f in "$data"/*.ply "$data"/*.xyz "$data"/*.off "$data"/*.xz; do
  "$dtlab" info "$f" | sed -n '2,4p' | tr '\n' ' '
  echo " <- $(basename "$f")"
done
for f in dragon_vrip_res4.ply armadillo_cgal26k.off dragon_vrip_res3.xyz; do
  "$dtlab" triangulate "$data/$f" --validate | tail -n1
  "$dtlab" triangulate "$data/$f" --validate | grep -q ': VALID;'
done
for f in dragon_vrip_res4.ply armadillo_cgal26k.off dragon_vrip_res3.xyz; do
  "$dtlab" triangulate "$data/$f" --location walk --validate | grep -q ': VALID;'
done
dragon=$("$dtlab" triangulate "$data/dragon_vrip.ply.xz" --location walk --validate)
echo "$dragon" | tail -n1
echo "$dragon" | grep -q ': VALID;'
echo "$dragon" | grep -q '435545 inserted, 2100 duplicates'
"$dtlab" triangulate "$data/dragon_vrip_res3.xyz" --location walk --method optimistic-detect \
  --threads 2 --validate | grep -q ': VALID;'
