"""POV-Ray's `sky_sphere` as softtrace's gradient background (docs/scene-format.md, "background").

softtrace's sky is bottom (1 - t) + top t with t = (1 + d.up) / 2, linear in the height d.up of
the unit direction d. A sky_sphere's pigment is evaluated at d; `gradient y` takes the pattern
point's y, and the pattern's scale and translate along y make that an affine a d.y + b. With a
two-entry color_map [v0 c0] [v1 c1] the colour is linear in d.y as long as a d.y + b stays inside
[v0, v1] over the sky (no clamping) and inside [0, 1] (POV-Ray's gradient wraps at whole
numbers): `gradient y color_map { [0 bottom] [1 top] } scale 2 translate -y` is the exact case.
Anything else is refused with its line and column.
"""
from .values import parse_color

TRANSFORM_HINT = "(a vertical gradient is carried: scale and translate along y)"


def sky_sphere(s, ex, at):
    """The block after `sky_sphere` as a softtrace background {"gradient": [bottom, top]}."""
    s.expect("{")
    sky = None
    while not s.closes("sky_sphere"):
        tok = s.next()
        if tok.text != "pigment" or sky is not None:
            raise s.error(tok, "sky_sphere { %s } is not supported (one pigment { gradient y "
                          "color_map { two entries } } is)" % tok.text)
        sky = _gradient_pigment(s, ex, tok)
    if sky is None:
        raise s.error(at, "sky_sphere has no pigment")
    return sky


def _gradient_pigment(s, ex, at):
    s.expect("{")
    vertical = False
    entries = None
    scale, shift = 1.0, 0.0  # the pattern's value is scale * d.y + shift
    while not s.closes("pigment"):
        tok = s.next()
        word = tok.text
        if word == "gradient":
            g = ex.vector("gradient")
            if tuple(g) != (0.0, 1.0, 0.0):
                raise s.error(tok, "sky_sphere: only gradient y (a vertical sky) is supported")
            vertical = True
        elif word in ("color_map", "colour_map"):
            entries = _color_map(s, ex, tok)
        elif word == "scale":
            v = ex.expr()
            k = v[1] if isinstance(v, tuple) else v
            if k == 0:
                raise s.error(tok, "sky_sphere: scale by zero")
            scale /= k
        elif word == "translate":
            v = ex.vector("translate")
            shift -= scale * v[1]
        else:
            raise s.error(tok, "sky_sphere: pigment { %s } is not supported %s" % (
                word, TRANSFORM_HINT))
    if not vertical or entries is None:
        raise s.error(at, "sky_sphere: only pigment { gradient y color_map { ... } } is supported")
    (v0, c0), (v1, c1) = entries
    lo, hi = shift - abs(scale), shift + abs(scale)
    if lo < 0 or hi > 1:
        raise s.error(at, "sky_sphere: the gradient's value runs over [%g, %g] across the sky and "
                      "POV-Ray wraps it at whole numbers; softtrace's gradient sky is `gradient y "
                      "... scale 2 translate -y` (values 0 to 1 from straight down to straight up)"
                      % (lo, hi))
    if lo < v0 or hi > v1:
        raise s.error(at, "sky_sphere: the gradient's value runs over [%g, %g] across the sky, "
                      "beyond the color_map's [%g, %g]: the clamped colours are not a linear "
                      "gradient" % (lo, hi, v0, v1))

    def colour(dy):
        u = (scale * dy + shift - v0) / (v1 - v0)
        return [c0[k] + (c1[k] - c0[k]) * u for k in range(3)]

    return {"gradient": [colour(-1.0), colour(1.0)]}


def _color_map(s, ex, at):
    """Exactly two entries `[v colour]`, v0 < v1, opaque."""
    s.expect("{")
    entries = []
    while not s.closes("color_map"):
        s.expect("[", "(a color_map entry)")
        v = ex.number("a color_map value")
        s.accept(",")
        tok = s.peek()
        c = parse_color(ex, "a color_map colour")
        if c[3] or c[4]:
            raise s.error(tok, "sky_sphere: filter and transmit in a color_map are not supported")
        s.expect("]")
        entries.append((v, c[:3]))
    if len(entries) != 2:
        raise s.error(at, "sky_sphere: the color_map has %d entries; only two (a two-colour "
                      "gradient) are supported" % len(entries))
    if not entries[0][0] < entries[1][0]:
        raise s.error(at, "sky_sphere: the color_map's two values must increase")
    return entries
