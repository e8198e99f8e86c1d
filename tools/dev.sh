#!/usr/bin/env bash
# softtrace's set-up on Debian 12, idempotent:
#   tools/dev.sh demo   install what is missing, build, render the default scene to out/
#   tools/dev.sh test   install what is missing, build, run the whole test suite (CTest)
#   tools/dev.sh build  install what is missing and build
set -euo pipefail
cd "$(dirname "$0")/.."

PACKAGES=(g++ cmake ninja-build pkg-config libembree-dev libopenimageio-dev libopenexr-dev
  libtbb-dev nlohmann-json3-dev libcli11-dev libgtest-dev libbenchmark-dev openimageio-tools)
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

build() {
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$BUILD_DIR" -j "$(nproc)"
}

case "${1:-}" in
  demo)
    install_missing
    build
    mkdir -p out
    "$BUILD_DIR/softtrace" render scenes/fig12b_soft_blend.json -o out/fig12b_soft_blend.exr \
      -o out/fig12b_soft_blend.png --aov depth,normal,steps
    ;;
  test)
    install_missing
    build
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
