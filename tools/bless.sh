#!/usr/bin/env bash
# Re-bless reference images after an intended change:
#   tools/bless.sh NAME [NAME...]    or    tools/bless.sh --all
# Builds softtrace (in BUILD_DIR, default build/), renders each scene at its size in the
# SOFTTRACE_REGRESSION_SCENES list (tests/CMakeLists.txt) with tests/integration/regression.sh's render
# options (--flatten), and stores it as a half-float, zip-compressed EXR in reference_images/.
# A reference whose R,G,B are unchanged is left alone, so blessing never makes a change git would
# show (the header's render time differs on every run).
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
list=$(sed -n '/^set(SOFTTRACE_REGRESSION_SCENES/,/^)/p' tests/CMakeLists.txt | grep '"' | tr -d '"')
names=("$@")
if [ "${1:-}" = "--all" ]; then mapfile -t names < <(echo "$list" | awk '{print $1}'); fi
[ ${#names[@]} -gt 0 ] || { echo "usage: tools/bless.sh NAME... | --all" >&2; exit 2; }
[ -f "$build/CMakeCache.txt" ] || { echo "bless: no build in $build; run tools/dev.sh build" >&2; exit 2; }
cmake --build "$build" --target softtrace >/dev/null
softtrace="$build/softtrace"

# Beside the references, so the final mv is a rename on the same file system.
tmp=$(mktemp -d reference_images/.bless.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
for name in "${names[@]}"; do
  size=$(echo "$list" | awk -v n="$name" '$1 == n {print $2, $3}')
  [ -n "$size" ] || { echo "bless: $name is not in SOFTTRACE_REGRESSION_SCENES (tests/CMakeLists.txt)" >&2; exit 2; }
  [ -f "scenes/$name.json" ] || { echo "bless: scenes/$name.json does not exist" >&2; exit 2; }
  read -r w h <<<"$size"
  ref="reference_images/$name.exr"
  "$softtrace" render "scenes/$name.json" -o "$tmp/$name.exr" --width "$w" --height "$h" --spp 1 \
    --flatten --half --quiet
  if [ -f "$ref" ] && "$softtrace" diff "$ref" "$tmp/$name.exr" --channels R,G,B --fail 0 --warn 0 >/dev/null 2>&1; then
    echo "unchanged $ref"
    continue
  fi
  if [ -f "$ref" ]; then
    "$softtrace" diff "$ref" "$tmp/$name.exr" --channels R,G,B --fail 0.005 2>&1 | grep -E "Max error|over 0.005" || true
  fi
  mv "$tmp/$name.exr" "$ref"
  echo "blessed $ref (${w}x${h}, $(stat -c %s "$ref") bytes)"
done
