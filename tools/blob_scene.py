#!/usr/bin/env python3
"""Writes a scene of N blobs: POV-Ray's `blob` as softtrace sees it.

POV-Ray's blob component of strength 1 and radius r has density (1 - (d/r)^2)^2 inside r, and
the surface is where the summed density reaches the threshold. That is exactly a `soft_blend` of
`murakami` soft objects over `lp_metric` distances d/r (n = 2) at iso = threshold, which is what
this writes. Centres are uniform in a cube of side 40 around the origin, from a fixed seed; the
radius shrinks as N^(-1/3) so that every N covers about the same part of the screen (the blobs'
total volume stays the same).

With --pov FILE it also writes the same picture as a POV-Ray scene (tools/pov_scene.py): the
blob of the same spheres, strength 1, threshold 0.5, with the same camera, lights and size.

With --meets K the radius is instead the one at which a ray crossing the cube passes through K
supports on average (meets_radius): a denser cloud at the same N.

usage: tools/blob_scene.py N [--meets K] [--seed S] [--width W] [--height H] [-o scene.json] [--pov scene.pov]
"""
import argparse
import math
import random

import pov_scene


def meets_radius(n, meets):
    """The radius at which a ray crossing the cube of side 40 passes, on average, through `meets`
    of n blobs' supports: n pi r^2 / 40^2 = meets (the blob1000 of the default radius, 6, is 71)."""
    return 40.0 * math.sqrt(meets / (n * math.pi))


def blobs(n, seed, radius=None):
    rng = random.Random(seed)
    if radius is None:
        radius = 12.0 * (1000.0 / n) ** (1.0 / 3.0) * 0.5
    out = []
    for _ in range(n):
        c = [round(rng.uniform(-20, 20), 6) for _ in range(3)]
        out.append((c, radius))
    return out


def scene(n, seed, width, height, radius=None):
    children = [{"type": "soft_object", "potential": {"type": "murakami"},
                 "distance": {"type": "lp_metric", "radii": [r, r, r], "n": 2},
                 "translate": c} for c, r in blobs(n, seed, radius)]
    return {
        "camera": {"eye": [70, -95, 60], "target": [0, 0, 0], "up": [0, 0, 1], "fov": 30},
        "image": {"width": width, "height": height, "spp": 1},
        "background": [0.45, 0.55, 0.75],
        "lights": [{"type": "directional", "direction": [1.0, 0.35, -1.0], "intensity": 0.85,
                    "shadows": True},
                   {"type": "ambient", "intensity": 0.18}],
        "objects": [{"name": f"blobs{n}", "material": {"color": [0.85, 0.8, 0.72]},
                     "convention": "soft", "iso": 0.5,
                     "field": {"type": "soft_blend", "children": children}}],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("n", type=int, help="number of blobs (2 to 10000)")
    ap.add_argument("--meets", type=float, help="blobs a ray through the cube passes through")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=480)
    ap.add_argument("-o", "--output", help="scene file (default: standard output)")
    ap.add_argument("--pov", help="also write the POV-Ray version of the scene here")
    a = ap.parse_args()
    if not 2 <= a.n <= 10000:
        ap.error("N must be in [2, 10000] (a soft_blend takes at most 10,000 children)")
    radius = meets_radius(a.n, a.meets) if a.meets else None
    sc = scene(a.n, a.seed, a.width, a.height, radius)
    pov_scene.write_scene(sc, a.output, a.pov, pov_scene.blob, a.width, a.height)


if __name__ == "__main__":
    main()
