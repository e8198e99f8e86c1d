#!/usr/bin/env bash
# `pip install .` as docs/python.md gives it: a copy of the source tree's tracked files installed
# into a fresh venv (--system-site-packages for Debian's numpy; --no-build-isolation --no-index:
# Debian's setuptools and wheel, no network). The native module comes from this build
# (SOFTTRACE_CMAKE_BUILD, setup.py), so the test costs seconds, not a second build; what it checks
# is pip's side: the package, its metadata, its stubs and py.typed, importable from the venv
# alone and able to render.
# Usage: test_pip_install.sh BUILD_DIR SOURCE_DIR WORK_DIR PYTHON
set -euo pipefail
build=$1 src=$2 work=$3 python=$4

fail() {
  echo "test_pip_install: FAILED: $*" >&2
  exit 1
}

rm -rf "$work"
mkdir -p "$work/src"
# The tracked files only, as a fresh clone has them (outside git: all but the build folders).
if git -C "$src" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  git -C "$src" ls-files -z | tar -C "$src" --null -T - -cf - | tar -C "$work/src" -xf -
else
  tar -C "$src" --exclude='./build*' --exclude='./out' -cf - . | tar -C "$work/src" -xf -
fi
"$python" -m venv --system-site-packages "$work/venv"
SOFTTRACE_CMAKE_BUILD=$build "$work/venv/bin/python" -m pip install -q --no-build-isolation \
  --no-index "$work/src" >"$work/pip.log" 2>&1 || fail "pip install: $(tail -n 5 "$work/pip.log")"

version=$(sed -n 's/^project(softtrace VERSION \([0-9.]*\).*/\1/p' "$src/CMakeLists.txt")
cd "$work"  # not the source tree: the import must find the venv's package
"$work/venv/bin/python" - "$work/venv" "$version" "$src/scenes/fig000_12b_soft_blend.json" <<'PY' || fail "the installed package"
import importlib.metadata as metadata
import os
import sys

import softtrace

venv, version, scene = sys.argv[1:]
where = os.path.dirname(os.path.realpath(softtrace.__file__))
assert where.startswith(os.path.realpath(venv)), f"softtrace imported from {where}, not the venv"
assert metadata.version("softtrace") == version, metadata.version("softtrace")
assert "numpy" in " ".join(metadata.requires("softtrace") or []), metadata.requires("softtrace")
for name in ("py.typed", "__init__.pyi", "_native.pyi"):
    assert os.path.exists(os.path.join(where, name)), f"the installed package has no {name}"
image = softtrace.render(softtrace.load_scene(scene), width=16, height=12)["rgba"]
assert image.shape == (12, 16, 4), image.shape
assert image[..., 3].max() > 0, "the render shows nothing"
print("pip install: softtrace", version, "from", where)
PY
