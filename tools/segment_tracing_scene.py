#!/usr/bin/python3
"""Writes a reconstruction of the Segment Tracing paper's blob scene, and its POV-Ray fit.

Galin, Guérin, Paris and Peytavie, "Segment Tracing Using Local Lipschitz Bounds" (Computer
Graphics Forum 39(2), 2020), render a scene of 1001 point blobs with the kernel (1 - d²/R²)³,
summed and cut at 0.5. This is a reconstruction of that scene's character, not their data: 1001
centres grown as a branching random walk from the origin (each new centre one step of about 2
units from an earlier one, leaning away from the origin, so the blobs form a coral of arms about
25 units long that overlap along their length), every radius R = 2.25 and strength 1, iso 0.5, all from a fixed
seed. In softtrace it is exact: a `soft_blend` of `cubic` soft objects over spheres of radius R.

POV-Ray's blob has no such kernel; its component is s(1 - d²/r²)², our `murakami`. With --pov
this also writes the closest such blob (`fit()`): one strength c and one radius r = sqrt(k) R for
every component, (c, k) minimising the squared difference of the two field profiles,
the integral over d from 0 to max(R, r) of ((1 - d²/R²)³ - c(1 - d²/(kR²))²)² (each term 0
outside its support). The fit is not the same surface: a single blob's 0.5 level and the way
neighbours' fields add both move a little (tools/pov_compare.py's `segtrace` case reports the
silhouettes' IoU).

usage: tools/segment_tracing_scene.py [--seed S] [--width W] [--height H] [-o scene.json]
           [--pov scene.pov]
"""
import argparse
import math
import random

import pov_scene

COUNT = 1001
RADIUS = 2.25
ISO = 0.5
STEP = 2.0


def centres(seed, n=COUNT):
    """n centres of a branching walk from the origin: each grows from the farther from the origin
    of two earlier centres picked at random (so tips grow more than the middle fills), one step of
    STEP times [0.8, 1.2] along a random direction leaning outward."""
    rng = random.Random(seed)
    out = [(0.0, 0.0, 0.0)]
    while len(out) < n:
        p = max(out[rng.randrange(len(out))], out[rng.randrange(len(out))],
                key=lambda q: q[0] * q[0] + q[1] * q[1] + q[2] * q[2])
        g = [rng.gauss(0, 1) for _ in range(3)]
        norm_p = math.sqrt(sum(c * c for c in p)) or 1.0
        d = [g[i] + 1.2 * p[i] / norm_p for i in range(3)]
        norm_d = math.sqrt(sum(c * c for c in d))
        step = STEP * rng.uniform(0.8, 1.2)
        out.append(tuple(round(p[i] + step * d[i] / norm_d, 6) for i in range(3)))
    return out


def _profile_error(c, k, samples=4000):
    """The integral over s = d/R in [0, max(1, sqrt k)] of ((1-s²)³ - c(1-s²/k)²)², midpoints."""
    top = max(1.0, math.sqrt(k))
    h = top / samples
    total = 0.0
    for i in range(samples):
        s2 = ((i + 0.5) * h) ** 2
        f = (1 - s2) ** 3 if s2 < 1 else 0.0
        g = c * (1 - s2 / k) ** 2 if s2 < k else 0.0
        total += (f - g) ** 2
    return total * h


def _best_strength(k, samples=4000):
    """The c minimising the profile error for this k (linear least squares): <f, h> / <h, h>."""
    top = max(1.0, math.sqrt(k))
    h = top / samples
    fh = hh = 0.0
    for i in range(samples):
        s2 = ((i + 0.5) * h) ** 2
        f = (1 - s2) ** 3 if s2 < 1 else 0.0
        g = (1 - s2 / k) ** 2 if s2 < k else 0.0
        fh += f * g
        hh += g * g
    return fh / hh


def fit():
    """(c, k): the murakami term c(1 - d²/(kR²))² closest to (1 - d²/R²)³ in the profile's least
    squares; c in closed form for each k, k by golden-section search over [0.2, 2]."""
    lo, hi = 0.2, 2.0
    phi = (math.sqrt(5) - 1) / 2
    err = lambda k: _profile_error(_best_strength(k), k)  # noqa: E731
    a, b = hi - phi * (hi - lo), lo + phi * (hi - lo)
    ea, eb = err(a), err(b)
    while hi - lo > 1e-7:
        if ea < eb:
            hi, b, eb = b, a, ea
            a = hi - phi * (hi - lo)
            ea = err(a)
        else:
            lo, a, ea = a, b, eb
            b = lo + phi * (hi - lo)
            eb = err(b)
    k = 0.5 * (lo + hi)
    return _best_strength(k), k


def scene(seed=1, width=640, height=480):
    pts = centres(seed)
    children = [{"type": "soft_object", "potential": {"type": "cubic"},
                 "distance": {"type": "lp_metric", "radii": [RADIUS] * 3, "n": 2},
                 "translate": list(p)} for p in pts]
    lo = [min(p[i] for p in pts) - RADIUS for i in range(3)]
    hi = [max(p[i] for p in pts) + RADIUS for i in range(3)]
    centre = [0.5 * (lo[i] + hi[i]) for i in range(3)]
    size = max(hi[i] - lo[i] for i in range(3))
    # Seen from the front and a little above, far enough that the whole coral fits a 34 degree
    # vertical field of view.
    dist = 0.5 * size / math.tan(math.radians(17))
    eye = [centre[0] + 0.35 * dist, centre[1] - 0.9 * dist, centre[2] + 0.3 * dist]
    return {
        "camera": {"eye": [round(c, 4) for c in eye], "target": [round(c, 4) for c in centre],
                   "up": [0, 0, 1], "fov": 34},
        "image": {"width": width, "height": height, "spp": 1},
        "background": [0.45, 0.55, 0.75],
        "lights": [{"type": "directional", "direction": [1.0, 0.35, -1.0], "intensity": 0.85,
                    "shadows": True},
                   {"type": "ambient", "intensity": 0.18}],
        "objects": [{"name": "segment_tracing_blobs", "material": {"color": [0.85, 0.45, 0.4]},
                     "convention": "soft", "iso": ISO,
                     "field": {"type": "soft_blend", "children": children}}],
    }


def pov_blob(sc):
    """The scene's blob as POV-Ray's closest murakami fit: strength c and radius sqrt(k) R."""
    c, k = fit()
    obj = sc["objects"][0]
    lines = ["// the murakami fit of (1 - d^2/R^2)^3: strength %.6f, radius %.6f R (k = %.6f)"
             % (c, math.sqrt(k), k), "blob { threshold %.9g" % obj["iso"]]
    for child in obj["field"]["children"]:
        r = child["distance"]["radii"][0] * math.sqrt(k)
        lines.append("  sphere { %s, %.9g, %.9g }" % (pov_scene.pov_vec(child["translate"]), r, c))
    lines.append(pov_scene.material(obj))
    lines.append("}")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=480)
    ap.add_argument("-o", "--output", help="scene file (default: standard output)")
    ap.add_argument("--pov", help="also write POV-Ray's murakami fit of the scene here")
    a = ap.parse_args()
    if a.width < 1 or a.height < 1:
        ap.error("--width and --height must be positive")
    sc = scene(a.seed, a.width, a.height)
    pov_scene.write_scene(sc, a.output, a.pov, pov_blob, a.width, a.height)


if __name__ == "__main__":
    main()
