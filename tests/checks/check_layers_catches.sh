#!/usr/bin/env bash
# The layering check must fail on deliberate back-up edges, each in a fresh copy of the sources,
# naming the file and line: a kernel that includes the loader, a tracer that includes the scene's
# loader, and the Python module including TBB.
set -euo pipefail
root=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# catches FILE INCLUDE EXPECTED: appends `#include INCLUDE` ("name" or <name>) to FILE in a copy;
# the check must fail with a line matching EXPECTED.
catches() {
  rm -rf "$tmp/fieldlib" "$tmp/renderer" "$tmp/python"
  cp -r "$root/fieldlib" "$root/renderer" "$root/python" "$tmp/"
  printf '#include %s\n' "$2" >>"$tmp/$1"
  if out=$(python3 "$root/tests/checks/check_layers.py" "$tmp" 2>&1); then
    echo "check_layers.py passed $1 including $2" >&2
    exit 1
  fi
  grep -q "$3" <<<"$out" || {
    echo "unexpected report: $out" >&2
    exit 1
  }
}

catches fieldlib/kernels/gauge.h '"loader/kinds.h"' \
  'fieldlib/kernels/gauge.h:[0-9]*: fieldlib/kernels may not include "loader/kinds.h"'
catches renderer/trace/tracer.h '"scene/scene.h"' \
  'renderer/trace/tracer.h:[0-9]*: renderer/trace may not include "scene/scene.h"'
catches renderer/trace/csg_trace.cpp '"scene/csg_load.h"' \
  'renderer/trace/csg_trace.cpp:[0-9]*: renderer/trace may not include "scene/csg_load.h"'
catches python/bind_field.cpp '<tbb/parallel_for.h>' \
  'python/bind_field.cpp:[0-9]*: <tbb/parallel_for.h> belongs in no library source'
echo "layers: injected back-up includes are reported"
