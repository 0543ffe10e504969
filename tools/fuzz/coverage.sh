#!/usr/bin/env bash
# Line coverage of dtlab's sources reached by replaying fuzz corpora (issue 38, part 0): builds the
# `coverage` preset (clang, -fprofile-instr-generate -fcoverage-mapping) replay_TARGET binaries,
# replays each corpus through its harness, and prints, per harness, the lines of engine/,
# predicates/ and io/ (sources and headers) that the replay executed, from llvm-cov's export.
# Usage: tools/fuzz/coverage.sh OUT TARGET=CORPUS-DIR [TARGET=CORPUS-DIR ...]
#   e.g. tools/fuzz/coverage.sh build/cov/after triangulate=fuzz/corpus/triangulate
# Writes OUT/TARGET.profdata, OUT/TARGET.json (llvm-cov export -summary-only) and OUT/summary.md.
set -euo pipefail
cd "$(dirname "$0")/../.."
[ $# -ge 2 ] || { echo "usage: $0 OUT TARGET=CORPUS-DIR ..." >&2; exit 2; }
out="$1"
shift
mkdir -p "$out"
targets=()
for spec in "$@"; do targets+=("replay_${spec%%=*}"); done
cmake --preset coverage >/dev/null
cmake --build --preset coverage -j"$(nproc)" --target "${targets[@]}" >/dev/null
profdata=$(command -v llvm-profdata-14 || command -v llvm-profdata)
cov=$(command -v llvm-cov-14 || command -v llvm-cov)
for spec in "$@"; do
  target="${spec%%=*}"
  corpus="${spec#*=}"
  raw="$out/$target.raw"
  rm -rf "$raw"
  mkdir -p "$raw"
  LLVM_PROFILE_FILE="$raw/%p.profraw" "build/coverage/fuzz/replay_$target" "$corpus" >"$out/$target.replay.log" 2>&1
  "$profdata" merge -sparse "$raw"/*.profraw -o "$out/$target.profdata"
  rm -rf "$raw"
  "$cov" export -summary-only "build/coverage/fuzz/replay_$target" \
    -instr-profile="$out/$target.profdata" \
    engine/src engine/include predicates/src predicates/include io/src io/include \
    >"$out/$target.json"
done
python3 tools/fuzz/coverage_summary.py "$out" "$@" | tee "$out/summary.md"
