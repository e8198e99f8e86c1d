#!/usr/bin/env bash
# Re-bless reference images after an intended change: tools/bless.sh NAME [NAME...] (or --all).
# Renders each scene at its regression size (tests/CMakeLists.txt) with the built softtrace and
# stores it as a compact half-float, zip-compressed EXR in reference_images/.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
list=$(sed -n '/^set(SOFTTRACE_REGRESSION_SCENES/,/^)/p' tests/CMakeLists.txt | grep '"' | tr -d '"')
names=("$@")
if [ "${1:-}" = "--all" ]; then mapfile -t names < <(echo "$list" | awk '{print $1}'); fi
[ ${#names[@]} -gt 0 ] || { echo "usage: tools/bless.sh NAME... | --all" >&2; exit 2; }
for name in "${names[@]}"; do
  size=$(echo "$list" | awk -v n="$name" '$1 == n {print $2, $3}')
  [ -n "$size" ] || { echo "bless: $name is not in SOFTTRACE_REGRESSION_SCENES" >&2; exit 2; }
  read -r w h <<<"$size"
  tmp=$(mktemp --suffix=.exr)
  "$build/softtrace" render "scenes/$name.json" -o "$tmp" --width "$w" --height "$h" --spp 1 --quiet
  oiiotool "$tmp" -d half --compression zip -o "reference_images/$name.exr"
  rm -f "$tmp"
  echo "blessed reference_images/$name.exr (${w}x${h})"
done
