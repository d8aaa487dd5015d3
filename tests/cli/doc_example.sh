#!/usr/bin/env bash
# The C++ example of docs/api.md must be the compiled one: its first ```cpp block
# is compared with examples/cpp/grains.cpp.
# Usage: doc_example.sh docs/api.md grains.cpp
set -euo pipefail
doc=$1 source=$2
shown=$(awk '/^```cpp$/ { inside = 1; next }
             inside && /^```$/ { exit }
             inside { print }' "$doc")
if [[ -z $shown ]]; then
  echo "$doc: no \`\`\`cpp block" >&2
  exit 1
fi
if ! diff <(printf '%s\n' "$shown") "$source"; then
  echo "$doc: the C++ example differs from $source (lines above: < $doc, > source); copy the source in" >&2
  exit 1
fi
echo "$doc: the example matches $source ($(wc -l < "$source") lines)"
