#!/usr/bin/env bash
# Installs the build tree into a temporary prefix and builds a consumer with find_package(dtlab).
set -euo pipefail
build="$1"
source="$2"
prefix=$(mktemp -d)
trap 'rm -rf "$prefix"' EXIT
cmake --install "$build" --prefix "$prefix/usr" >/dev/null
cmake -S "$source/tests/consumer" -B "$prefix/build" -DCMAKE_PREFIX_PATH="$prefix/usr" >/dev/null
cmake --build "$prefix/build" -j2 >/dev/null
"$prefix/build/consumer"
