#!/usr/bin/env bash
# The larger real models at 8 threads (oversubscribed on 2 cores): every method validated; burglary with --repair.
set -uo pipefail
cd "$(dirname "$0")/.."
for f in ../shared/data/happy_buddha_scan78k.xyz ../shared/data/dragon_vrip_res2.ply.xz; do
  for m in pessimistic optimistic-detect optimistic-prevent batch; do
    build/release/cli/dtlab triangulate $f --method $m --threads 8 --validate | tail -1 | sed "s|^|$(basename $f) $m 8: |"
  done
  build/release/cli/dtlab triangulate $f --method burglary --threads 8 --repair=rebuild --validate | tail -2 | tr '\n' ' ' | sed "s|^|$(basename $f) burglary 8: |"; echo
done
for m in optimistic-detect burglary; do
  extra=""; [ $m = burglary ] && extra="--repair=rebuild"
  build/release/cli/dtlab triangulate ../shared/data/dragon_vrip.ply.xz --method $m --threads 8 $extra --validate | tail -2 | tr '\n' ' ' | sed "s|^|dragon_vrip $m 8: |"; echo
done
