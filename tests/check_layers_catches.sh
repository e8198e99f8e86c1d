#!/usr/bin/env bash
# The layering check must fail on a kernel that includes the loader (a deliberate back-up edge in
# a copy of the sources), naming the file and line.
set -euo pipefail
root=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp -r "$root/fieldlib" "$root/renderer" "$tmp/"
printf '#include "loader/kinds.h"\n' >>"$tmp/fieldlib/kernels/gauge.h"
if out=$(python3 "$root/tests/check_layers.py" "$tmp" 2>&1); then
  echo "check_layers.py passed a kernel that includes the loader" >&2
  exit 1
fi
grep -q 'fieldlib/kernels/gauge.h:[0-9]*: fieldlib/kernels may not include "loader/kinds.h"' <<<"$out" || {
  echo "unexpected report: $out" >&2
  exit 1
}
echo "layers: an injected back-up include is reported"
