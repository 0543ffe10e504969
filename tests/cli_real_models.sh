#!/usr/bin/env bash
# Every real model in shared/data loads; the small ones triangulate and validate.
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
