#!/usr/bin/env python3
"""Prints the first object's field value of a scene at a point, as `softtrace eval` does.

usage: example.py SCENE X Y Z   (with the module on PYTHONPATH: PREFIX/lib/python3/dist-packages)
"""
import sys

import numpy as np

import softtrace


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__.strip())
    scene = softtrace.load_scene(sys.argv[1])
    field = softtrace.Field(scene)
    point = np.array([[float(v) for v in sys.argv[2:5]]])
    values, grads = field.gradient(point)
    print("%.17g" % values[0])


if __name__ == "__main__":
    main()
