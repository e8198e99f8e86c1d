#!/usr/bin/python3
"""Writes a POV-Ray 3.7 blob of N mixed components, written out literally as a generator would.

The real-world-like cloud for tools/pov_compare.py's `cloudN` cases: spheres (60%) and cylinder
components (40%) in a cube of side 20, strengths from 0.6 to 2 with one component in eight
negative (dents and holes), and one in five scaled along its own axes or sheared (a `scale` after
a `rotate`). The radii shrink as N^(-1/3) so that every N covers about the same part of the
screen. Fixed seed: the same N gives the same file.

usage: tools/pov_cloud.py N [--seed S] [-o cloud.pov]
"""
import argparse
import random

import pov_scene


def scene(n, seed=1):
    rng = random.Random(seed)
    size = 2.2 * (1000.0 / n) ** (1.0 / 3.0)
    out = ["// %d mixed blob components (tools/pov_cloud.py, seed %d)" % (n, seed),
           "#version 3.7;", "global_settings { assumed_gamma 1.0 }",
           "camera { location <34, 38, -54> look_at <0, 0, 0> right x*4/3 angle 34 }",
           "light_source { <-30, 60, -40> color rgb 1 }",
           "light_source { <40, 20, -30> color rgb 0.35 shadowless }",
           "background { color rgb <0.4, 0.5, 0.65> }", "blob {", "  threshold 0.6"]
    for _ in range(n):
        c = [rng.uniform(-10, 10) for _ in range(3)]
        strength = rng.uniform(0.6, 2.0) * (-1 if rng.random() < 0.125 else 1)
        r = size * rng.uniform(0.7, 1.3)
        mods = ""
        if rng.random() < 0.2:
            mods = " rotate <%.1f, %.1f, %.1f> scale <%.3f, %.3f, %.3f>" % (
                tuple(rng.uniform(0, 90) for _ in range(3)) +
                tuple(rng.uniform(0.5, 1.6) for _ in range(3)))
        if rng.random() < 0.6:
            out.append("  sphere { 0, %.4f, %.4f%s translate <%.4f, %.4f, %.4f> }" % (
                r, strength, mods, *c))
        else:
            half = [rng.uniform(-1, 1) * size for _ in range(3)]
            out.append("  cylinder { <%.4f, %.4f, %.4f>, <%.4f, %.4f, %.4f>, %.4f, %.4f%s "
                       "translate <%.4f, %.4f, %.4f> }" % (
                           *[-h for h in half], *half, r * 0.7, strength, mods, *c))
    out += ["  pigment { color rgb <0.8, 0.7, 0.55> }",
            "  finish { ambient 0.1 diffuse 0.7 phong 0.4 }", "}"]
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("n", type=int, help="number of components (1 to 10000)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("-o", "--output", help="the .pov file (default: standard output)")
    a = ap.parse_args()
    if not 1 <= a.n <= 10000:
        ap.error("N must be in [1, 10000] (a soft_blend takes at most 10,000 children)")
    pov_scene.write_text(scene(a.n, a.seed), a.output)


if __name__ == "__main__":
    main()
