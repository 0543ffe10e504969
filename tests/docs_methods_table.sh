#!/usr/bin/env bash
# docs/design.md shows the method registry as `dtlab methods` prints it (between the markers
# "<!-- dtlab methods -->" and "<!-- end dtlab methods -->"): the docs read the registry.
# Usage: docs_methods_table.sh DTLAB DESIGN.md
set -euo pipefail
dtlab="$1" doc="$2"
expected=$("$dtlab" methods)
actual=$(sed -n '/^<!-- dtlab methods -->$/,/^<!-- end dtlab methods -->$/p' "$doc" | sed '1d;$d')
if [ "$expected" != "$actual" ]; then
  echo "docs/design.md's method table differs from \`dtlab methods\`:"
  diff <(echo "$expected") <(echo "$actual") || true
  exit 1
fi
echo "docs/design.md's method table is the registry's ($(echo "$expected" | wc -l) lines)"
