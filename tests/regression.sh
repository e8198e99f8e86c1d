#!/usr/bin/env bash
# Image regression of one scene: render it small, compare with reference_images/<name>.exr.
# Usage: regression.sh SOFTTRACE SOURCE_DIR WORK_DIR NAME WIDTH HEIGHT
# Thresholds: a pixel fails when a channel differs by more than 0.02; the test fails when more
# than 0.5 % of pixels fail (room for libm differences between CPUs, not for a changed picture).
set -euo pipefail
softtrace=$1 src=$2 work=$3 name=$4 width=$5 height=$6
mkdir -p "$work"
ref="$src/reference_images/$name.exr"
out="$work/$name.exr"
diffimg="$work/$name.diff.exr"
rm -f "$out" "$diffimg"
"$softtrace" render "$src/scenes/$name.json" -o "$out" --width "$width" --height "$height" --spp 1 --quiet
if [ ! -f "$ref" ]; then
  echo "no reference image $ref; bless one with: tools/bless.sh $name" >&2
  exit 1
fi
if "$softtrace" diff "$ref" "$out" --fail 0.02 --failpercent 0.5 --out "$diffimg"; then
  exit 0
fi
echo "regression $name FAILED: reference $ref, render $out, difference $diffimg" >&2
exit 1
