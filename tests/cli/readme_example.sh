#!/usr/bin/env bash
# The README's C++ example must be the compiled one: the first ```cpp block
# after the "Use it from C++" heading is compared with examples/cpp/grains.cpp.
# Usage: readme_example.sh README.md grains.cpp
set -euo pipefail
readme=$1 source=$2
shown=$(awk '/^## Use it from C\+\+/ { section = 1 }
             section && /^```cpp$/ { inside = 1; next }
             inside && /^```$/ { exit }
             inside { print }' "$readme")
if [[ -z $shown ]]; then
  echo "$readme: no \`\`\`cpp block under '## Use it from C++'" >&2
  exit 1
fi
if ! diff <(printf '%s\n' "$shown") "$source"; then
  echo "$readme: the C++ example differs from $source (lines above: < README, > source); copy the source in" >&2
  exit 1
fi
echo "README example matches $source ($(wc -l < "$source") lines)"
