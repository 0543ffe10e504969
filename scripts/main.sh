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
status=0
for kernel in fast adaptive filtered; do
  echo "== dtlab triangulate $input --seed $seed --predicates $kernel --validate"
  code=0
  "$dtlab" triangulate "$input" --seed "$seed" --predicates "$kernel" --validate || code=$?
  # An invalid mesh (exit 1) is a result for the fast kernel; for the exact ones it is a failure.
  if [ "$code" -ne 0 ] && { [ "$kernel" != fast ] || [ "$code" -ne 1 ]; }; then status=1; fi
  echo
done
echo "machine: $(nproc) cores, $(uname -m), $(lscpu 2>/dev/null | sed -n 's/^Model name: *//p' | head -n1)"
exit "$status"
