"""POV-Ray's transformations as 4x4 affine matrices, and POV-Ray's frame as softtrace's.

Matrices act on column vectors, world = M local. POV-Ray applies transformations in the order
written, so each new one multiplies from the left. `rotate <a, b, c>` turns about x by a, then y
by b, then z by c, in degrees, with the usual rotation matrices: POV-Ray's left-handedness only
changes which way a positive angle looks on screen, not the numbers. `matrix <m00, ..., m32>` is
POV-Ray's row-vector form: p'_j = sum_i p_i m_ij + m_3j.

POV-Ray is left-handed with y up, softtrace right-handed with z up. Swapping y and z maps one to
the other (a swap of two axes flips the handedness), so POV-Ray's point (x, y, z) is softtrace's
(x, z, y) and the picture is the same, not mirrored; a matrix M becomes S M S, S the swap.
"""
import math

IDENTITY = ((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0))


def mul(a, b):
    return tuple(tuple(sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4))
                 for i in range(4))


def translate(v):
    return ((1.0, 0.0, 0.0, v[0]), (0.0, 1.0, 0.0, v[1]), (0.0, 0.0, 1.0, v[2]),
            (0.0, 0.0, 0.0, 1.0))


def scale(v):
    return ((v[0], 0.0, 0.0, 0.0), (0.0, v[1], 0.0, 0.0), (0.0, 0.0, v[2], 0.0),
            (0.0, 0.0, 0.0, 1.0))


def _about(axis, deg):
    c, s = math.cos(math.radians(deg)), math.sin(math.radians(deg))
    i, j = [(1, 2), (2, 0), (0, 1)][axis]
    m = [list(r) for r in IDENTITY]
    m[i][i], m[i][j], m[j][i], m[j][j] = c, -s, s, c
    return tuple(tuple(r) for r in m)


def rotate(v):
    return mul(_about(2, v[2]), mul(_about(1, v[1]), _about(0, v[0])))


def pov_matrix(m):
    """POV-Ray's 12 numbers (rows of the row-vector form) as a column-vector matrix."""
    return ((m[0], m[3], m[6], m[9]), (m[1], m[4], m[7], m[10]), (m[2], m[5], m[8], m[11]),
            (0.0, 0.0, 0.0, 1.0))


def apply(m, p):
    return tuple(m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2] + m[i][3] for i in range(3))


def linear(m):
    return tuple(tuple(m[i][j] for j in range(3)) for i in range(3))


def det3(a):
    return (a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
            a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
            a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]))


SWAP = ((1.0, 0.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))


def to_softtrace_point(p):
    return (p[0], p[2], p[1])


def to_softtrace(m):
    return mul(SWAP, mul(m, SWAP))


def _columns(a):
    return [tuple(a[i][j] for i in range(3)) for j in range(3)]


def _dot(p, q):
    return sum(x * y for x, y in zip(p, q))


def column_scales(a, tol=1e-12):
    """(k0, k1, k2) if a = R diag(k) with R a rotation and k > 0 (orthogonal columns, no
    mirror), else None."""
    cols = _columns(a)
    k = [math.sqrt(_dot(c, c)) for c in cols]
    if min(k) == 0 or det3(a) <= 0:
        return None
    for i in range(3):
        for j in range(i + 1, 3):
            if abs(_dot(cols[i], cols[j])) > tol * k[i] * k[j]:
                return None
    return tuple(k)


def axis_angle(r):
    """A rotation matrix as (unit axis, degrees); (None, 0) for the identity."""
    trace = r[0][0] + r[1][1] + r[2][2]
    angle = math.acos(max(-1.0, min(1.0, (trace - 1) / 2)))
    if angle < 1e-12:
        return None, 0.0
    if math.pi - angle < 1e-6:
        # Near a half turn the antisymmetric part vanishes: the axis is the dominant column of
        # (R + I) / 2 = a a^T.
        i = max(range(3), key=lambda k: r[k][k])
        col = [(r[k][i] + (1.0 if k == i else 0.0)) / 2 for k in range(3)]
        n = math.sqrt(_dot(col, col))
        return tuple(c / n for c in col), math.degrees(angle)
    axis = (r[2][1] - r[1][2], r[0][2] - r[2][0], r[1][0] - r[0][1])
    n = math.sqrt(_dot(axis, axis))
    return tuple(c / n for c in axis), math.degrees(angle)
