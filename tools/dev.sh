#!/usr/bin/env bash
# softtrace's set-up on Debian 12, idempotent:
#   tools/dev.sh demo   install what is missing, build, render the default scene to out/
#   tools/dev.sh test   install what is missing, build, run the whole test suite (CTest), then
#                       the same tests built with AddressSanitizer+UBSan (build-asan/) and the
#                       scene-loader fuzzer for FUZZ_SECONDS (default 60; build-fuzz/)
#   tools/dev.sh build  install what is missing and build
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(g++ cmake ninja-build pkg-config libembree-dev libopenimageio-dev libopenexr-dev
  libpng-dev libtbb-dev nlohmann-json3-dev libcli11-dev libgtest-dev libbenchmark-dev openimageio-tools
  clang-14 libclang-rt-14-dev munge slurmctld slurmd slurm-client
  pybind11-dev python3-pybind11 python3-numpy python3-pytest groff-base man-db)
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

# The unit and CLI tests again, built with -fsanitize=address,undefined (no recovery: a report
# fails its test). Leak checking is off: the image and threading libraries keep singletons.
sanitize() {
  cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSOFTTRACE_SANITIZE=ON >/dev/null
  cmake --build build-asan -j "$(nproc)"
  ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --test-dir build-asan -j "$(nproc)" --output-on-failure
}

# libFuzzer on the scene loader and field evaluation (tests/fuzz_scene.cpp), seeded from scenes/
# and tests/bad_scenes/, with a dictionary of every kind and parameter name (`softtrace nodes
# --dict`, from the one list of kinds) plus tests/fuzz_scene.dict. A crash leaves its input in
# build-fuzz/crash-*; make it a tests/bad_scenes/ file (or fix the loader) before going on.
fuzz() {
  CXX=clang++-14 cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DSOFTTRACE_SANITIZE=ON -DSOFTTRACE_FUZZ=ON >/dev/null
  cmake --build build-fuzz -j "$(nproc)" --target fuzz_scene
  mkdir -p build-fuzz/corpus
  "$BUILD_DIR/softtrace" nodes --dict >build-fuzz/scene.dict
  cat tests/fuzz_scene.dict >>build-fuzz/scene.dict
  if ! ASAN_OPTIONS=detect_leaks=0 build-fuzz/tests/fuzz_scene -max_total_time="${FUZZ_SECONDS:-60}" \
    -max_len=16384 -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 -dict=build-fuzz/scene.dict \
    -artifact_prefix=build-fuzz/ build-fuzz/corpus scenes tests/bad_scenes >build-fuzz/fuzz.log 2>&1; then
    tail -n 60 build-fuzz/fuzz.log
    echo "fuzz_scene failed: the input is in build-fuzz/ (crash-*, timeout-*, oom-*)" >&2
    return 1
  fi
  grep -E '^(Done|stat::)' build-fuzz/fuzz.log
}

case "${1:-}" in
  demo)
    install_missing
    build softtrace
    mkdir -p out
    "$BUILD_DIR/softtrace" render scenes/fig12b_soft_blend.json -o out/fig12b_soft_blend.exr \
      -o out/fig12b_soft_blend.png --aov depth,normal,steps
    ;;
  test)
    install_missing
    build
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
