#!/usr/bin/env bash
# README command (a): set up, build Release, and run the main job on a generated default input.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
cmake --preset release -DDTLAB_BUILD_TESTS=OFF -DDTLAB_BUILD_BENCH=OFF >/dev/null
cmake --build --preset release -j"$(nproc)" --target dtlab
dtlab=build/release/cli/dtlab
input="${1:-uniform:100000}"
seed="${SEED:-1}"
echo "== dtlab info $input --seed $seed"
"$dtlab" info "$input" --seed "$seed"
echo
for kernel in fast adaptive; do
  echo "== dtlab triangulate $input --seed $seed --predicates $kernel --validate"
  "$dtlab" triangulate "$input" --seed "$seed" --predicates "$kernel" --validate || true
  echo
done
echo "machine: $(nproc) cores, $(uname -m), $(lscpu 2>/dev/null | sed -n 's/^Model name: *//p' | head -n1)"
