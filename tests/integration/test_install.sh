#!/usr/bin/env bash
# softtrace as a user gets it: `cmake --install` into an empty prefix, then the example consumer
# project (examples/consumer) configured with find_package(softtrace) against that prefix only,
# a fieldlib program compiled with pkg-config's flags, and, when the Python module was built,
# `import softtrace` and examples/python/example.py from the prefix. Every value printed must be
# the bits `softtrace eval` prints for the same field.
#   test_install.sh BUILD_DIR SOURCE_DIR WORK_DIR [PYTHON]
set -euo pipefail
build=$1 src=$2 work=$3 python=${4:-python3}
prefix=$work/prefix
scene=$src/examples/consumer/two_blobs.json

fail() {
  echo "test_install: FAILED: $*" >&2
  exit 1
}
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$prefix" >"$work/install.log"
for f in bin/softtrace bin/softtrace-core bin/softtrace-exr.so include/softtrace/eval/eval.h include/softtrace/loader/build.h \
  include/softtrace/scene/scene.h lib/cmake/softtrace/softtraceConfig.cmake \
  lib/cmake/softtrace/softtraceConfigVersion.cmake lib/pkgconfig/softtrace-fieldlib.pc \
  share/man/man1/softtrace.1 share/doc/softtrace/README.md; do
  [ -e "$prefix/$f" ] || fail "the install has no $f"
done
# What --help points to: every page of docs/ and every scene of scenes/, under share/.
for f in "$src"/docs/*.md; do
  [ -e "$prefix/share/doc/softtrace/$(basename "$f")" ] || fail "the install has no docs/$(basename "$f")"
done
for f in "$src"/scenes/*.json; do
  [ -e "$prefix/share/softtrace/scenes/$(basename "$f")" ] ||
    fail "the install has no share/softtrace/scenes/$(basename "$f")"
done
"$prefix/bin/softtrace" --help | grep -q 'share/doc/softtrace/' || fail "--help does not point to the installed docs"
MANPATH=$prefix/share/man man -w softtrace | grep -qx "$prefix/share/man/man1/softtrace.1" ||
  fail "man does not find softtrace.1 under the prefix"
"$prefix/bin/softtrace" render "$prefix/share/softtrace/scenes/fig000_12b_soft_blend.json" --scale 0.1 -q \
  -o "$work/installed_scene.png" || fail "the installed binary cannot render an installed scene"
# A scene of several objects: softtrace-core opens Embree then (cli/embree_on_demand.cpp).
"$prefix/bin/softtrace" render "$prefix/share/softtrace/scenes/fig000_1b_superquadrics.json" --scale 0.1 -q \
  -o "$work/installed_objects.png" || fail "the installed binary cannot render a scene of several objects"
# EXR goes through bin/softtrace-exr.so, which softtrace-core opens beside itself.
"$prefix/bin/softtrace" render "$prefix/share/softtrace/scenes/fig000_12b_soft_blend.json" --scale 0.1 -q \
  -o "$work/installed_scene.exr" || fail "the installed binary cannot write an EXR"
"$prefix/bin/softtrace" diff "$work/installed_scene.exr" "$work/installed_scene.exr" >/dev/null ||
  fail "the installed binary cannot read its EXR back"
# Without the module, a render with an EXR output fails before its frame (no progress bar, no
# image written, not even the PNG beside it), in the one line its write would have given.
mkdir "$work/no_exr"
cp "$prefix/bin/softtrace" "$prefix/bin/softtrace-core" "$work/no_exr/"
status=0
"$work/no_exr/softtrace" render "$prefix/share/softtrace/scenes/fig000_12b_soft_blend.json" --scale 0.1 \
  --progress -o "$work/no_exr/scene.png" -o "$work/no_exr/scene.exr" 2>"$work/no_exr/stderr" || status=$?
[ "$status" = 2 ] || fail "a render to EXR without softtrace-exr.so exited with $status, not 2"
expected="softtrace: $work/no_exr/scene.exr: cannot load the EXR module: $work/no_exr/softtrace-exr.so:"
[ "$(wc -l <"$work/no_exr/stderr")" = 1 ] && [[ "$(cat "$work/no_exr/stderr")" == "$expected"* ]] ||
  fail "a render to EXR without softtrace-exr.so printed: $(head -c 400 "$work/no_exr/stderr")"
[ ! -e "$work/no_exr/scene.png" ] || fail "a render to EXR without softtrace-exr.so wrote its PNG"
# Every fieldlib header is installed, and every installed header compiles on its own (an
# installed header that includes one left out would not).
# Headers sit in their layer folders and include each other rooted there ("eval/eval.h").
for h in "$src"/fieldlib/*/*.h; do
  rel=${h#"$src"/fieldlib/}
  [ -e "$prefix/include/softtrace/$rel" ] || fail "the install has no include/softtrace/$rel"
done
# One compiler per header, as many at once as there are CPUs: one after the other, they were most
# of this test's time and left the other CPUs to CTest's other tests or to nothing.
mkdir "$work/headers"
# shellcheck disable=SC2016  # expanded by the shell that xargs starts
(cd "$prefix/include/softtrace" && printf '%s\0' */*.h) |
  xargs -0 -n 1 -P "$(nproc)" sh -c '
    logs=$1 include=$2 rel=$3
    log=$logs/$(echo "$rel" | tr / _).log
    echo "#include \"$rel\"" | c++ -std=c++17 -fsyntax-only -I"$include" -x c++ - 2>"$log" ||
      { echo "test_install: FAILED: $rel does not compile alone: $(head -n 3 "$log")" >&2; exit 1; }' \
    sh "$work/headers" "$prefix/include/softtrace" ||
  fail "the headers above do not compile alone"
"$prefix/bin/softtrace" --version | grep -q '^softtrace [0-9.]* (commit ' ||
  fail "softtrace --version: '$("$prefix/bin/softtrace" --version)'"

# The value of softtrace eval (the first column) at the test point.
point="20 1 2"
expected=$(echo "$point" | "$prefix/bin/softtrace" eval "$scene" | cut -d' ' -f1)

# Only the prefix: no build tree, no package registry.
cmake -S "$src/examples/consumer" -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF >"$work/consumer.log"
grep -q "softtrace_DIR:PATH=$prefix/" "$work/consumer/CMakeCache.txt" ||
  fail "the consumer found softtrace outside the prefix: $(grep softtrace_DIR "$work/consumer/CMakeCache.txt")"
cmake --build "$work/consumer" >>"$work/consumer.log"
got=$("$work/consumer/field_value" $point)
[ "$got" = "$expected" ] || fail "field_value printed $got, softtrace eval $expected"
got=$("$work/consumer/scene_value" "$scene" $point)
[ "$got" = "$expected" ] || fail "scene_value printed $got, softtrace eval $expected"

# pkg-config: fieldlib alone, no CMake.
export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
flags=$(pkg-config --cflags --libs softtrace-fieldlib) || fail "pkg-config softtrace-fieldlib"
# shellcheck disable=SC2086
c++ -std=c++17 -O1 "$src/examples/consumer/field_value.cpp" -o "$work/field_value_pc" $flags
got=$("$work/field_value_pc" $point)
[ "$got" = "$expected" ] || fail "field_value (pkg-config) printed $got, softtrace eval $expected"

python_dir=$(find "$prefix" -path '*/softtrace/__init__.py' -printf '%h/..\n' | head -n1)
if [ -n "$python_dir" ]; then
  got=$(PYTHONPATH=$python_dir "$python" "$src/examples/python/example.py" "$scene" $point)
  [ "$got" = "$expected" ] || fail "example.py printed $got, softtrace eval $expected"
fi
echo "test_install: ok ($expected at ($point); python: ${python_dir:-not built})"
