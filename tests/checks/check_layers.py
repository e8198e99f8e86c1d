#!/usr/bin/env python3
"""Fails when a source file includes from a layer it may not (README.md "Layout").

Each library's folders are layers (with their subfolders: fieldlib/program/ops/ is part of
program); a file may include its own folder and the folders listed for it below, never one above it. Third-party headers are held to the one room that adapts each library, in the Python
module (python/, above every layer) too: it reaches the worker threads through render/threads.h.
Usage: check_layers.py [REPO_ROOT]   (exit 1 and one line per violation, file:line: ...)
"""
import os
import re
import sys

FIELDLIB = ["math", "kernels", "program", "eval", "describe", "model", "loader", "mesh"]
# What each layer may include besides itself (rooted includes: "math/vec.h"): whole layers, or
# single files of one ("scene/primitive.h") where a layer may see only those.
MAY_INCLUDE = {
    "fieldlib/math": [],
    "fieldlib/kernels": ["math"],
    "fieldlib/program": ["math", "kernels"],
    "fieldlib/eval": ["math", "kernels", "program"],
    "fieldlib/describe": ["math"],
    "fieldlib/model": ["math", "kernels", "program", "describe"],
    "fieldlib/loader": ["math", "kernels", "program", "eval", "describe", "model"],
    # The mesher meshes a compiled program with the evaluators; it never sees the model.
    "fieldlib/mesh": ["math", "kernels", "program", "eval"],
    "renderer/io": ["math", "mesh"],
    "renderer/film": ["math", "io"],
    "renderer/scene": FIELDLIB + ["io"],
    # The tracer takes what it traces (scene/trace_target.h: compiled programs, iso, inside sign,
    # bounds, plain primitives, triangle meshes, a placed CSG's affine map) and never sees the
    # scene's loader (scene.h and the *_load, placement, json_ and scene_keys files), the model or
    # the JSON behind them.
    "renderer/trace": ["math", "kernels", "program", "eval", "scene/trace_target.h",
                       "scene/primitive.h", "scene/triangle_mesh.h", "scene/affine.h",
                       "scene/ranges.h"],
    "renderer/render": FIELDLIB + ["io", "film", "scene", "trace"],
    "renderer/cli": FIELDLIB + ["io", "film", "scene", "trace", "render"],
}
# Third-party headers and the only places that may include them.
EXTERNAL = [
    # The adapter and the device that turns Embree's errors into ours; the command line's
    # forwarders that open Embree at its first call, and the static program's that hand over.
    (re.compile(r"^embree3/"), ["renderer/trace/embree_scene.cpp", "renderer/trace/embree_device.",
                                "renderer/cli/embree_on_demand.cpp", "renderer/cli/embree_in_core.cpp"]),
    # None: the frame's threads are the renderer's own (render/threads.h); only libembree3 uses
    # TBB, inside itself.
    (re.compile(r"^tbb/"), []),
    (re.compile(r"^(Imf|Iex|half\.h|OpenEXR/|Imath)"), ["renderer/io/exr_io.cpp"]),
    (re.compile(r"^png\.h$"), ["renderer/io/png_io.cpp"]),
    (re.compile(r"^OpenImageIO/"), []),
    (re.compile(r"^nlohmann/"), ["fieldlib/describe/", "fieldlib/model/", "fieldlib/loader/",
                                 "renderer/scene/", "renderer/cli/",
                                 "renderer/io/mesh_glb.cpp"]),  # glTF's JSON chunk
    (re.compile(r"^CLI/"), ["renderer/cli/"]),
]
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')


def sources(folder):
    """The C++ sources under folder, its subfolders' included, relative to it, sorted."""
    names = []
    for dirpath, dirnames, filenames in os.walk(folder):
        dirnames.sort()
        sub = os.path.relpath(dirpath, folder)
        names += [name if sub == "." else f"{sub}/{name}" for name in sorted(filenames)]
    return [name for name in names if name.endswith((".h", ".cpp"))]


def includes(path):
    """(line number, '<' or '"', target) for each #include of the file."""
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            m = INCLUDE.match(line)
            if m:
                yield number, m.group(1), m.group(2)


def external(rel, number, target):
    """The problem with file rel including third-party <target> at line number, if any."""
    for pattern, places in EXTERNAL:
        if pattern.search(target) and not any(rel.startswith(p) for p in places):
            return [f"{rel}:{number}: <{target}> belongs in "
                    f"{' or '.join(places) or 'no library source'}"]
    return []


def check(root):
    problems = []
    rooms = set(MAY_INCLUDE)
    for lib in ("fieldlib", "renderer"):
        for entry in sorted(os.listdir(os.path.join(root, lib))):
            path = os.path.join(root, lib, entry)
            if os.path.isfile(path) and entry.endswith((".h", ".cpp")):
                problems.append(f"{lib}/{entry}:1: a source file outside every layer folder")
            if os.path.isdir(path) and f"{lib}/{entry}" not in rooms:
                problems.append(f"{lib}/{entry}: a folder that is no layer (add it to check_layers.py"
                                " and the README's layout)")
    for room, allowed in MAY_INCLUDE.items():
        folder = os.path.join(root, room)
        if not os.path.isdir(folder):
            problems.append(f"{room}: the layer folder is missing")
            continue
        lib, layer = room.split("/")
        for name in sources(folder):
            rel = f"{room}/{name}"
            for number, kind, target in includes(os.path.join(folder, name)):
                if kind == '"':
                    if "/" not in target:
                        if target != "commit.h":  # generated by the build
                            problems.append(f"{rel}:{number}: \"{target}\" is not rooted "
                                            "(write \"<layer>/{target}\")")
                        continue
                    first = target.split("/")[0]
                    if first == layer or first in allowed or target in allowed:
                        continue
                    problems.append(f"{rel}:{number}: {room} may not include \"{target}\" "
                                    f"(it may include {', '.join(allowed) or 'nothing'})")
                else:
                    problems += external(rel, number, target)
    # The Python module may include every layer, but third-party headers only where they belong.
    folder = os.path.join(root, "python")
    if os.path.isdir(folder):
        for name in sources(folder):
            for number, kind, target in includes(os.path.join(folder, name)):
                if kind == "<":
                    problems += external(f"python/{name}", number, target)
    return problems


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
    problems = check(root)
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} include(s) against the layers", file=sys.stderr)
        return 1
    print("layers: every include runs down a layer")
    return 0


if __name__ == "__main__":
    sys.exit(main())
