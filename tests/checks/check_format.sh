#!/usr/bin/env bash
# Fails when a tracked C++ file differs from what clang-format-14 makes of it (the root
# .clang-format); prints each place. Fix with: clang-format-14 -i FILE.
set -euo pipefail
cd "$1"
command -v clang-format-14 >/dev/null || { echo "clang-format-14 is missing (tools/dev.sh installs it)" >&2; exit 1; }
files=$(git ls-files '*.h' '*.cpp' 2>/dev/null || find fieldlib renderer tests python examples -name '*.h' -o -name '*.cpp')
clang-format-14 --dry-run --Werror $files
echo "format: $(echo "$files" | wc -w) files as .clang-format says"
