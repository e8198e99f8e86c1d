"""Numbers, vectors and colours of POV-Ray's expression language.

A value is a float or a tuple of floats (a vector; colours are 5-tuples r, g, b, filter,
transmit). Operators work as in POV-Ray: a float meets a vector by promotion to every component,
vectors combine component by component. Names resolve in `Symbols`: the scene's `#declare`s, then
the built-ins (x, y, z, pi, image_width, ...).
"""
import math

from .lexer import describe


class Symbols:
    """`#declare`d and `#local` names (one scope: the converter takes no macros) and built-ins."""

    def __init__(self, width, height):
        self.declared = {}
        self.builtin = {
            "x": (1.0, 0.0, 0.0), "y": (0.0, 1.0, 0.0), "z": (0.0, 0.0, 1.0),
            "u": (1.0, 0.0), "v": (0.0, 1.0), "t": (0.0, 0.0, 0.0, 1.0),
            "pi": math.pi, "tau": 2 * math.pi, "clock": 0.0, "version": 3.7,
            "image_width": float(width), "image_height": float(height),
            "true": 1.0, "yes": 1.0, "on": 1.0, "false": 0.0, "no": 0.0, "off": 0.0,
        }

    def get(self, name):
        if name in self.declared:
            return self.declared[name]
        return self.builtin.get(name)


def _unary(f):
    return lambda args: f(_float(args[0]))


def _float(v):
    if isinstance(v, tuple):
        raise TypeError("a vector where a number is needed")
    return v


def _vec3(v):
    if not isinstance(v, tuple):
        return (v, v, v)
    return (tuple(v) + (0.0, 0.0, 0.0))[:3]


FUNCTIONS = {
    "sqrt": (1, _unary(math.sqrt)), "abs": (1, _unary(abs)), "sin": (1, _unary(math.sin)),
    "cos": (1, _unary(math.cos)), "tan": (1, _unary(math.tan)), "asin": (1, _unary(math.asin)),
    "acos": (1, _unary(math.acos)), "atan": (1, _unary(math.atan)), "exp": (1, _unary(math.exp)),
    "log": (1, _unary(math.log10)), "ln": (1, _unary(math.log)),
    "radians": (1, _unary(math.radians)), "degrees": (1, _unary(math.degrees)),
    "floor": (1, _unary(math.floor)), "ceil": (1, _unary(math.ceil)),
    "int": (1, _unary(lambda a: float(int(a)))),
    "atan2": (2, lambda a: math.atan2(_float(a[0]), _float(a[1]))),
    "pow": (2, lambda a: math.pow(_float(a[0]), _float(a[1]))),
    "mod": (2, lambda a: math.fmod(_float(a[0]), _float(a[1]))),
    "min": (None, lambda a: min(_float(v) for v in a)),
    "max": (None, lambda a: max(_float(v) for v in a)),
    "vlength": (1, lambda a: math.sqrt(sum(c * c for c in _vec3(a[0])))),
    "vdot": (2, lambda a: sum(p * q for p, q in zip(_vec3(a[0]), _vec3(a[1])))),
    "vcross": (2, lambda a: _cross(_vec3(a[0]), _vec3(a[1]))),
    "vnormalize": (1, lambda a: _normalize(_vec3(a[0]))),
}

MEMBERS = {"x": 0, "u": 0, "red": 0, "y": 1, "v": 1, "green": 1, "z": 2, "blue": 2,
           "filter": 3, "t": 3, "transmit": 4}


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _normalize(a):
    n = math.sqrt(sum(c * c for c in a))
    if n == 0:
        raise ValueError("vnormalize of a zero vector")
    return tuple(c / n for c in a)


def combine(a, b, op):
    if isinstance(a, tuple) or isinstance(b, tuple):
        size = max(len(a) if isinstance(a, tuple) else 0, len(b) if isinstance(b, tuple) else 0)
        aa = a + (0.0,) * (size - len(a)) if isinstance(a, tuple) else (a,) * size
        bb = b + (0.0,) * (size - len(b)) if isinstance(b, tuple) else (b,) * size
        return tuple(op(p, q) for p, q in zip(aa, bb))
    return op(a, b)


def _div(p, q):
    if q == 0:
        raise ZeroDivisionError("division by zero")
    return p / q


class Expressions:
    """Recursive descent over POV-Ray's arithmetic: + - * /, unary signs, parentheses,
    <vectors>, names, function calls and .x/.y/.z members."""

    def __init__(self, stream, symbols):
        self.s = stream
        self.symbols = symbols

    def expr(self):
        tok = self.s.peek()
        try:
            return self._sum()
        except (TypeError, ValueError, ZeroDivisionError, OverflowError) as e:
            raise self.s.error(tok, "cannot evaluate this expression: %s" % e)

    def number(self, what):
        tok = self.s.peek()
        v = self.expr()
        if isinstance(v, tuple):
            raise self.s.error(tok, "%s must be a number, not a vector" % what)
        if not math.isfinite(v):
            raise self.s.error(tok, "%s is not finite" % what)
        return v

    def vector(self, what):
        """A 3-vector; a number n is promoted to <n, n, n> as POV-Ray does."""
        tok = self.s.peek()
        v = self.expr()
        v = _vec3(v) if not isinstance(v, tuple) or len(v) >= 3 else None
        if v is None:
            raise self.s.error(tok, "%s must be a 3-vector" % what)
        if not all(math.isfinite(c) for c in v):
            raise self.s.error(tok, "%s is not finite" % what)
        return v

    def _sum(self):
        v = self._product()
        while self.s.at("+", "punct") or self.s.at("-", "punct"):
            op = self.s.next().text
            w = self._product()
            v = combine(v, w, (lambda p, q: p + q) if op == "+" else (lambda p, q: p - q))
        return v

    def _product(self):
        v = self._unary()
        while self.s.at("*", "punct") or self.s.at("/", "punct"):
            op = self.s.next().text
            w = self._unary()
            v = combine(v, w, (lambda p, q: p * q) if op == "*" else _div)
        return v

    def _unary(self):
        if self.s.accept("-"):
            return combine(self._unary(), -1.0, lambda p, q: p * q)
        if self.s.accept("+"):
            return self._unary()
        return self._postfix()

    def _postfix(self):
        v = self._primary()
        while self.s.at(".", "punct") and self.s.peek(1).kind == "name":
            self.s.next()
            tok = self.s.next()
            index = MEMBERS.get(tok.text)
            if index is None or not isinstance(v, tuple) or index >= len(v):
                raise self.s.error(tok, "no member '.%s' here" % tok.text)
            v = v[index]
        return v

    def _primary(self):
        tok = self.s.peek()
        if tok.kind == "number":
            self.s.next()
            return float(tok.text)
        if tok.kind == "punct" and tok.text == "(":
            self.s.next()
            v = self._sum()
            self.s.expect(")")
            return v
        if tok.kind == "punct" and tok.text == "<":
            self.s.next()
            items = [self._float_in_vector()]
            while self.s.accept(","):
                items.append(self._float_in_vector())
            self.s.expect(">", "to close the vector")
            if not 2 <= len(items) <= 5:
                raise self.s.error(tok, "a vector has 2 to 5 components, this one %d" % len(items))
            return tuple(items)
        if tok.kind == "name":
            if tok.text in FUNCTIONS:
                return self._call()
            v = self.symbols.get(tok.text)
            if v is None:
                raise self.s.error(tok, "unknown identifier '%s'" % tok.text)
            if isinstance(v, dict):
                raise self.s.error(tok, "'%s' is a %s, not a number or vector" % (
                    tok.text, v.get("kind", "block")))
            self.s.next()
            return v
        raise self.s.error(tok, "expected a number or vector, found %s" % describe(tok))

    def _float_in_vector(self):
        tok = self.s.peek()
        v = self._sum()
        if isinstance(v, tuple):
            raise self.s.error(tok, "a vector's component must be a number")
        return v

    def _call(self):
        tok = self.s.next()
        arity, f = FUNCTIONS[tok.text]
        self.s.expect("(", "after '%s'" % tok.text)
        args = [self._sum()]
        while self.s.accept(","):
            args.append(self._sum())
        self.s.expect(")")
        if arity is not None and len(args) != arity:
            raise self.s.error(tok, "%s takes %d argument%s" % (tok.text, arity,
                                                                "" if arity == 1 else "s"))
        return f(args)


COLOR_WORDS = ("rgb", "rgbf", "rgbt", "rgbft", "srgb", "srgbf", "srgbt", "srgbft",
               "red", "green", "blue", "filter", "transmit")


def srgb_to_linear(c):
    return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4


def parse_color(ex, what="a colour"):
    """`[color] rgb <..> | rgbf/rgbt/rgbft/srgb.. <..> | red r green g blue b | NAME | <..>`:
    a 5-tuple (r, g, b, filter, transmit), linear (assumed_gamma 1)."""
    s = ex.s
    s.accept("color") or s.accept("colour")
    start = s.peek()
    c = [0.0] * 5
    seen = False
    while s.peek().kind == "name" and s.peek().text in COLOR_WORDS:
        word = s.next().text
        seen = True
        if word in ("red", "green", "blue", "filter", "transmit"):
            c[MEMBERS[word]] = ex.number("'%s'" % word)
            continue
        tok = s.peek()
        v = ex.expr()
        srgb = word.startswith("s")
        channels = word[1:] if srgb else word
        extra = {"rgb": [], "rgbf": [3], "rgbt": [4], "rgbft": [3, 4]}[channels]
        if not isinstance(v, tuple):
            v = (v,) * (3 + len(extra))
        if len(v) < 3 + len(extra):
            raise s.error(tok, "'%s' needs %d components" % (word, 3 + len(extra)))
        rgb = [srgb_to_linear(v[i]) if srgb else v[i] for i in range(3)]
        c[0:3] = rgb
        for k, slot in enumerate(extra):
            c[slot] = v[3 + k]
    if not seen:
        v = ex.expr()
        if not isinstance(v, tuple):
            v = (v, v, v)
        c = list((tuple(v) + (0.0,) * 5)[:5])
    for k in range(5):
        if not math.isfinite(c[k]):
            raise s.error(start, "%s is not finite" % what)
    return tuple(c)
