#!/usr/bin/python3
"""Converts a POV-Ray 3.7 scene of blobs and plain shapes into a softtrace scene (JSON).

The scene must be written out literally: numbers, vectors and colours may be `#declare`d, but
loops, macros, conditionals and rand() are refused. Carried across: `camera` (location, look_at,
angle, direction, up, right, sky, orthographic, focal blur), `light_source` (point, `parallel`,
`spotlight`, `area_light`, fading, `shadowless`), `background`, `sky_sphere` (a vertical
two-colour gradient), `global_settings { ambient_light }`, `blob` objects (sphere
and cylinder components with their strengths, the threshold, translate/rotate/scale/matrix/
transform on components and on the blob, the blob's pigment and finish), transparency (a
pigment's filter and transmit, `reflection { [MIN,] MAX fresnel on }`, `conserve_energy`,
`interior { ior }`), plane, box, sphere, cylinder, cone and disc objects, and `mesh`/`mesh2`
objects, whose triangles go to OUTPUT-STEM_NAME.obj beside the output (so a scene with meshes
needs -o). POV-Ray's y-up left-handed frame becomes softtrace's z-up
right-handed one by swapping y and z, which keeps the picture unmirrored (tools/povsdl/affine.py).
POV-Ray's `angle` is horizontal, softtrace's `fov` vertical. docs/pov.md has the details.

Anything it cannot carry is refused with one line, `SCENE.pov:LINE:COL: what`, and exit status 2;
the output file is then left as it was.

usage: tools/pov2softtrace.py SCENE.pov [-o SCENE.json] [--width 320] [--height 240]
                              [--antialias T] [--antialias-depth R] [--antialias-gamma G]
POV-Ray's anti-aliasing is a command-line (or .ini) option, not scene syntax: give +A0.3 +R3 as
`--antialias 0.3 --antialias-depth 3`, and an .ini's Antialias_Gamma=G as `--antialias-gamma G`.
"""
import argparse
import json
import os
import re
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from povsdl.lexer import PovError  # noqa: E402
from povsdl.scene import convert, obj_text  # noqa: E402


def write_atomically(path, text):
    """The whole file or nothing: written beside the target, then renamed over it."""
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".pov2softtrace-", dir=folder)
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        os.replace(tmp, path)
    except BaseException:
        os.unlink(tmp)
        raise


def dumps(scene):
    """Indented JSON with each list of numbers on one line."""
    text = json.dumps(scene, indent=1)
    return re.sub(r"\[[^\[\]{}\"]*\]", lambda m: re.sub(r"\s+", " ", m.group(0))
                  .replace("[ ", "[").replace(" ]", "]"), text)


def mesh_objects(objects):
    """The mesh objects among `objects` and their CSGs' operands, depth first."""
    for obj in objects:
        if "mesh" in obj:
            yield obj
        yield from mesh_objects(obj.get("operands", []))


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="pov2softtrace.py", description=__doc__.split("\n\n")[0],
        epilog="Exit status: 0 converted, 2 refused (one located line on standard error).")
    ap.add_argument("scene", help="the POV-Ray scene (.pov)")
    ap.add_argument("-o", "--output", help="the softtrace scene to write (default: standard output)")
    ap.add_argument("--width", type=int, default=320,
                    help="image width: the scene's image size and POV-Ray's image_width (320)")
    ap.add_argument("--height", type=int, default=240,
                    help="image height, and POV-Ray's image_height (240)")
    ap.add_argument("--antialias", type=float, metavar="T",
                    help="POV-Ray's +AT (+A alone is +A0.3): adaptive anti-aliasing with that "
                    "threshold, the scene's image.antialias (default: off)")
    ap.add_argument("--antialias-depth", type=int, default=3, metavar="R",
                    help="POV-Ray's +R (3): a refined pixel takes R*R times the samples")
    ap.add_argument("--antialias-gamma", type=float, metavar="G",
                    help="POV-Ray's Antialias_Gamma (an .ini option; 2.5 when not given): the "
                    "colours are compared as c^(1/G), the scene's image.antialias.gamma")
    a = ap.parse_args(argv)
    if not (1 <= a.width <= 16384 and 1 <= a.height <= 16384):
        print("pov2softtrace.py: --width and --height must be 1 to 16384", file=sys.stderr)
        return 2
    if a.antialias is not None and not 0 <= a.antialias <= 1e6:
        print("pov2softtrace.py: --antialias must be 0 to 1e6", file=sys.stderr)
        return 2
    if not 1 <= a.antialias_depth <= 9:
        print("pov2softtrace.py: --antialias-depth must be 1 to 9", file=sys.stderr)
        return 2
    if a.antialias_gamma is not None and not 0.01 <= a.antialias_gamma <= 100:
        print("pov2softtrace.py: --antialias-gamma must be 0.01 to 100", file=sys.stderr)
        return 2
    if a.antialias_gamma is not None and a.antialias is None:
        print("pov2softtrace.py: --antialias-gamma needs --antialias (POV-Ray's +A)",
              file=sys.stderr)
        return 2
    try:
        with open(a.scene, encoding="utf-8", errors="replace") as f:
            text = f.read()
    except OSError as e:
        print("%s: cannot read: %s" % (a.scene, e.strerror), file=sys.stderr)
        return 2
    meshes = []
    try:
        scene = convert(a.scene, text, a.width, a.height, meshes)
    except PovError as e:
        print("%s:%d:%d: %s" % (a.scene, e.line, e.col, e.message), file=sys.stderr)
        return 2
    if meshes and not a.output:
        print("%s: the scene has %d mesh object(s), whose triangles go to OBJ files beside the "
              "output: give -o" % (a.scene, len(meshes)), file=sys.stderr)
        return 2
    if a.antialias is not None:
        scene["image"]["antialias"] = {"threshold": a.antialias, "depth": a.antialias_depth}
        if a.antialias_gamma is not None:
            scene["image"]["antialias"]["gamma"] = a.antialias_gamma
    out = "// Converted from %s by tools/pov2softtrace.py\n%s\n" % (
        os.path.basename(a.scene), dumps(scene))
    if a.output:
        # Each mesh's triangles beside the scene, OUTPUT-STEM_NAME.obj, named by a path relative
        # to it (docs/scene-format.md "Triangle meshes"), written before the scene.
        stem = os.path.splitext(os.path.abspath(a.output))[0]
        for obj in mesh_objects(scene["objects"]):
            path = "%s_%s.obj" % (stem, obj["name"])
            write_atomically(path, obj_text(meshes[obj["mesh"]]))
            obj["mesh"] = os.path.basename(path)
        out = "// Converted from %s by tools/pov2softtrace.py\n%s\n" % (
            os.path.basename(a.scene), dumps(scene))
        write_atomically(a.output, out)
    else:
        sys.stdout.write(out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
