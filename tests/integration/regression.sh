#!/usr/bin/env bash
# Image regression of one scene: render it small, compare it with its reference by `softtrace diff`.
# Usage: regression.sh SOFTTRACE SCENE.json REFERENCE.exr WORK_DIR WIDTH HEIGHT
# Exit 0 when the render matches; otherwise 1 (2 when the scene does not render), and on a failed
# comparison WORK_DIR/<scene>.html shows reference | render | difference with the numbers.
# Thresholds: a pixel fails when a channel differs by more than 0.005 (ten times the references'
# half-float rounding; a 3 % change of a material colour or a 0.1 % zoom fails); the test fails
# when more than 0.5 % of pixels fail (room for silhouette pixels that flip with libm differences
# between CPUs). Pixels over 0.001 make `diff` say WARNING (exit 1): a near miss in the log, not a
# failure. The render is flattened over the background and only R,G,B are compared: the
# references hold colour over the background and A = coverage, a flattened render A = 1.
# The render options must stay those of tools/bless.sh, which makes the references.
set -euo pipefail
[ $# -eq 6 ] || { echo "usage: regression.sh SOFTTRACE SCENE.json REFERENCE.exr WORK_DIR WIDTH HEIGHT" >&2; exit 2; }
softtrace=$1 scene=$2 ref=$3 work=$4 width=$5 height=$6
name=$(basename "$scene" .json)
mkdir -p "$work"
out="$work/$name.exr"
diffimg="$work/$name.diff.exr"
html="$work/$name.html"
rm -f "$out" "$diffimg" "$html" "$work/$name".{ref,render,diff}.png "$work/$name.diff.txt"

"$softtrace" render "$scene" -o "$out" --width "$width" --height "$height" --spp 1 --flatten --quiet
if [ ! -f "$ref" ]; then
  echo "regression $name: no reference image $ref; make one with: tools/bless.sh $name" >&2
  exit 1
fi
status=0
"$softtrace" diff "$ref" "$out" --channels R,G,B --fail 0.005 --failpercent 0.5 --warn 0.001 \
  --abs --out "$diffimg" >"$work/$name.diff.txt" 2>&1 || status=$?
cat "$work/$name.diff.txt"
if [ $status -le 1 ]; then  # 0 pass, 1 warning
  rm -f "$work/$name.diff.txt"
  exit 0
fi

# The page: PNGs for a browser (sRGB for the images, the difference linear and 10x brighter).
png() { oiiotool "$1" --ch R,G,B "${@:3}" -d uint8 -o "$2"; }
if ! { png "$ref" "$work/$name.ref.png" --colorconvert linear sRGB &&
  png "$out" "$work/$name.render.png" --colorconvert linear sRGB &&
  { [ ! -f "$diffimg" ] || png "$diffimg" "$work/$name.diff.png" --mulc 10; }; }; then
  echo "regression $name: oiiotool could not make the page's PNGs" >&2
fi
escape() { sed -e 's/&/\&amp;/g' -e 's/</\&lt;/g' -e 's/>/\&gt;/g'; }
cell() { echo "<td><img src=\"$1\" width=\"$((2 * width))\" alt=\"$2\"></td>"; }
{
  echo "<!doctype html>"
  echo "<html><head><meta charset=\"utf-8\"><title>regression $name failed</title>"
  echo "<style>body{font-family:sans-serif}img{image-rendering:pixelated}</style></head><body>"
  echo "<h1>regression $name failed</h1>"
  echo "<table><tr><th>reference</th><th>render</th><th>difference &times;10</th></tr><tr>"
  cell "$name.ref.png" reference
  cell "$name.render.png" render
  cell "$name.diff.png" difference
  echo "</tr></table>"
  echo "<pre>"
  escape <"$work/$name.diff.txt"
  echo "</pre>"
  echo "<p>reference: $(escape <<<"$ref")<br>render: $(escape <<<"$out")<br>"
  echo "difference: $(escape <<<"$diffimg")</p>"
  echo "<p>If the change is intended, re-bless: <code>tools/bless.sh $name</code></p>"
  echo "</body></html>"
} >"$html"
rm -f "$work/$name.diff.txt"
echo "regression $name FAILED: see $html (reference $ref, render $out, difference $diffimg)" >&2
exit 1
