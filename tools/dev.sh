#!/usr/bin/env bash
# softtrace's set-up on Debian 12, idempotent:
#   tools/dev.sh demo   install what is missing, build, render the default scene to out/
#   tools/dev.sh test   install what is missing, build, then the same tests and the fuzzers in one
#                       clang build with AddressSanitizer+UBSan (build-asan/): the fuzzers, the scene
#                       loader for FUZZ_SECONDS (default 60) and, beside it, merge's tile headers then
#                       diff's image readers for half of it each; the sanitized suite; the whole test
#                       suite (CTest) of the plain build last
#   tools/dev.sh build  install what is missing and build
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(g++ cmake ninja-build pkg-config libembree-dev libopenimageio-dev libopenexr-dev
  libpng-dev libtbb-dev nlohmann-json3-dev libcli11-dev libgtest-dev libbenchmark-dev openimageio-tools
  clang-14 clang-format-14 libclang-rt-14-dev munge slurmctld slurmd slurm-client
  pybind11-dev python3-pybind11 python3-numpy python3-pytest python3-mypy python3-venv python3-pip
  python3-setuptools python3-wheel libcgal-dev groff-base man-db
  povray python3-pil)
BUILD_DIR=${BUILD_DIR:-build}

install_missing() {
  local missing=()
  for p in "${PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "installing: ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# build [TARGET...]: everything, or only the named targets (the demo needs only `softtrace`).
build() {
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$BUILD_DIR" -j "$(nproc)" ${1:+--target "$@"}
}

# The unit and CLI tests again and the fuzzers, in one clang 14 build (build-asan/), so that the
# libraries compile once for both: -fsanitize=address,undefined (no recovery: a report fails its
# test), and libFuzzer's coverage on the libraries (not on the tests' own code:
# tests/CMakeLists.txt). Leak checking is off: the image and threading libraries keep singletons.
# -O1 -g1 rather than RelWithDebInfo's -O2 -g: the instrumented build is CI's longest step, and
# these flags halve its compile time while keeping line numbers in the reports;
# tests/CMakeLists.txt compiles the test sources themselves at -O0.
sanitized_build() {
  CXX=clang++-14 cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DSOFTTRACE_SANITIZE=ON \
    -DSOFTTRACE_FUZZ=ON >/dev/null
  cmake --build build-asan -j "$(nproc)"
}

sanitize() {
  ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan -j "$(nproc)" --output-on-failure
}

# libFuzzer, three targets: the scene loader and field evaluation (tests/fuzz/fuzz_scene.cpp) for
# FUZZ_SECONDS, seeded from scenes/ and tests/bad_scenes/, with a dictionary of every kind and
# parameter name (`softtrace nodes --dict`, from the one list of kinds) plus
# tests/fuzz/fuzz_scene.dict; beside it, merge's tile headers (tests/fuzz/fuzz_merge_tiles.cpp)
# then diff's image readers (tests/fuzz/fuzz_diff_images.cpp) for half of FUZZ_SECONDS each,
# seeded with small EXR tiles and PNGs the plain build renders (and reference_images/ for diff).
# A crash leaves its input in build-asan/fuzz/crash-*; make it a test (a tests/bad_scenes/ file, a
# tile or image case) or fix the reader before going on.
FUZZ_DIR=build-asan/fuzz
run_fuzzer() {  # NAME SECONDS MAX_LEN [libFuzzer options and corpus folders...]
  local name=$1 seconds=$2 max_len=$3
  shift 3
  if ! ASAN_OPTIONS=detect_leaks=0 "build-asan/tests/$name" -max_total_time="$seconds" \
    -max_len="$max_len" -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$FUZZ_DIR/" "$@" >"$FUZZ_DIR/$name.log" 2>&1; then
    tail -n 60 "$FUZZ_DIR/$name.log"
    echo "$name failed: the input is in $FUZZ_DIR/ (crash-*, timeout-*, oom-*)" >&2
    return 1
  fi
  grep -E '^(Done|stat::)' "$FUZZ_DIR/$name.log"
}

# Seeds for the tile and image fuzzers: tiles with and without AOVs, flattened and half, PNGs.
fuzz_seeds() {
  local seeds=$FUZZ_DIR/image-seeds scene=tests/scenes/turntable.json
  mkdir -p "$seeds"
  local core=("$BUILD_DIR/softtrace" render "$scene" --quiet --width 8 --height 6)
  "${core[@]}" --tile 0/2 -o "$seeds/t0.exr" -o "$seeds/rgb.png"
  "${core[@]}" --tile 1/2 --aov depth,normal,steps -o "$seeds/t1-aov.exr"
  "${core[@]}" --crop 0,0.5,0,1 --flatten --half -o "$seeds/half.exr"
  "${core[@]}" --png-alpha -o "$seeds/rgba.png"
}

fuzz() {
  mkdir -p "$FUZZ_DIR/corpus" "$FUZZ_DIR/corpus-merge" "$FUZZ_DIR/corpus-diff"
  "$BUILD_DIR/softtrace" nodes --dict >"$FUZZ_DIR/scene.dict"
  cat tests/fuzz/fuzz_scene.dict >>"$FUZZ_DIR/scene.dict"
  fuzz_seeds
  local seconds=${FUZZ_SECONDS:-60} failed=0 scene_fuzzer
  # A fuzzer is one process on one CPU: the scene loader's runs beside the other two, which run
  # one after the other, so that each has a CPU of its own for all its seconds.
  run_fuzzer fuzz_scene "$seconds" 16384 -dict="$FUZZ_DIR/scene.dict" \
    "$FUZZ_DIR/corpus" scenes tests/bad_scenes &
  scene_fuzzer=$!
  run_fuzzer fuzz_merge_tiles $((seconds / 2)) 65536 "$FUZZ_DIR/corpus-merge" \
    "$FUZZ_DIR/image-seeds" || failed=1
  run_fuzzer fuzz_diff_images $((seconds / 2)) 65536 "$FUZZ_DIR/corpus-diff" \
    "$FUZZ_DIR/image-seeds" reference_images || failed=1
  wait "$scene_fuzzer" || failed=1
  return "$failed"
}

case "${1:-}" in
  demo)
    install_missing
    build softtrace
    mkdir -p out
    "$BUILD_DIR/softtrace" render scenes/fig000_12b_soft_blend.json -o out/fig000_12b_soft_blend.exr \
      -o out/fig000_12b_soft_blend.png --aov depth,normal,steps
    ;;
  test)
    install_missing
    build
    sanitized_build
    fuzz
    sanitize
    # The plain build's suite last, so its summary closes the log.
    ctest --test-dir "$BUILD_DIR" -j "$(nproc)" --output-on-failure
    ;;
  build)
    install_missing
    build
    ;;
  *)
    echo "usage: tools/dev.sh demo|test|build" >&2
    exit 2
    ;;
esac
