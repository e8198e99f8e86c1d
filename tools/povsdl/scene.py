"""POV-Ray 3.7 statements as a softtrace scene (a JSON-ready dict).

Carried across: `camera` (location, look_at, angle, direction, up, right, sky, orthographic,
focal blur's aperture, focal_point and blur_samples), `light_source`
(point, `parallel`, `spotlight`, `area_light`, `fade_distance`/`fade_power`, `shadowless`), `background`, `sky_sphere` (a vertical two-colour gradient), plane/box/sphere/cylinder/cone/disc objects, `global_settings` (ambient_light,
assumed_gamma 1), `#declare`/`#local` of numbers, vectors, colours, pigments, finishes, textures
and transforms, `#default { finish }`, `#include` of POV-Ray's colour names, `mesh` and `mesh2` objects (their triangles written to OBJ
files beside the scene), and `blob` objects:
sphere and cylinder components (and the old `component` form) with strength, threshold,
per-component and whole-blob translate/rotate/scale/matrix/transform, pigment, finish and texture.
Transparency: a pigment's filter and transmit (rgbf, rgbt, rgbft, `filter`, `transmit`), the
finish's `reflection { [MIN,] MAX fresnel on }` and `conserve_energy`, an object's
`interior { ior }`. Everything else is refused with its line and column.
"""
import math
import os

from . import affine
from .lexer import PovError, Stream, describe, tokenize
from .sky import sky_sphere
from .values import Expressions, Symbols, parse_color

POV_INCLUDE_DIRS = ["/usr/share/povray-3.7/include"]

# POV-Ray 3.7's finish defaults (the manual's "finish" section).
FINISH_DEFAULTS = {"ambient": 0.1, "diffuse": 0.6, "brilliance": 1.0, "phong": 0.0,
                   "phong_size": 40.0, "specular": 0.0, "roughness": 0.05, "metallic": 0.0,
                   "reflection": 0.0}
FINISH_KEYS = ("ambient", "diffuse", "brilliance", "phong", "phong_size", "specular",
               "roughness", "metallic")
# Modifiers that change nothing softtrace draws: root-solver and bounding hints.
HARMLESS = {"sturm", "hierarchy", "hollow", "double_illuminate"}
REFUSED_DIRECTIVES = {
    "while": "loops are not supported; write the objects out literally",
    "for": "loops are not supported; write the objects out literally",
    "macro": "macros are not supported; write the objects out literally",
    "if": "conditionals are not supported", "ifdef": "conditionals are not supported",
    "ifndef": "conditionals are not supported", "switch": "conditionals are not supported",
    "fopen": "file input is not supported", "read": "file input is not supported",
}
TRANSFORMS = ("translate", "rotate", "scale", "matrix", "transform")
SHAPES = ("plane", "box", "sphere", "cylinder", "cone", "disc")
CSG = ("union", "merge", "intersection", "difference")


class Modifiers:
    """What an object's modifiers build up: its transformation (object to world, POV-Ray's
    frame), pigment colour and finish values."""

    def __init__(self):
        self.matrix = affine.IDENTITY
        self.pigment = None
        self.finish = {}
        self.ior = 1.0  # interior { ior }


class Converter:
    def __init__(self, path, width, height):
        self.path = path
        self.width = width
        self.height = height
        self.symbols = Symbols(width, height)
        self.default_finish = dict(FINISH_DEFAULTS)
        self.camera = None
        self.lights = []
        self.background = None
        self.sky = None  # a sky_sphere's gradient background, which hides `background`
        self.ambient_light = (1.0, 1.0, 1.0)
        self.objects = []
        self.names = {}
        self.csg_depth = 0  # how many CSGs enclose the object being read
        self.meshes = []  # each mesh object's triangles, written beside the scene (_mesh)

    # ---- top level -----------------------------------------------------------------------
    def run(self, text):
        self._statements(Stream(tokenize(text)), os.path.dirname(os.path.abspath(self.path)))
        if self.camera is None:
            raise PovError(1, 1, "the scene has no camera")
        if not self.objects:
            raise PovError(1, 1, "the scene has no objects this converter takes")
        lights = list(self.lights)
        if any(c > 0 for c in self.ambient_light):
            lights.append({"type": "ambient", "color": list(self.ambient_light)})
        scene = {"camera": self.camera, "image": {"width": self.width, "height": self.height},
                 "background": self.sky or list(self.background or (0.0, 0.0, 0.0)),
                 "lights": lights,
                 "objects": self.objects}
        return scene

    def _statements(self, s, folder):
        ex = Expressions(s, self.symbols)
        while s.peek().kind != "end":
            tok = s.peek()
            if tok.kind == "directive":
                self._directive(s, ex, folder)
            elif tok.kind == "name":
                self._item(s, ex, tok)
            else:
                raise s.error(tok, "expected a statement, found %s" % describe(tok))

    def _directive(self, s, ex, folder):
        tok = s.next()
        d = tok.text
        if d == "version":
            ex.number("#version")
            s.accept(";")
        elif d in ("declare", "local"):
            self._declare(s, ex)
        elif d == "include":
            name = s.next()
            if name.kind != "string":
                raise s.error(name, "#include needs a file name in quotes")
            self._include(name, folder)
        elif d == "default":
            self._default(s, ex)
        elif d in REFUSED_DIRECTIVES:
            raise s.error(tok, "#%s: %s" % (d, REFUSED_DIRECTIVES[d]))
        else:
            raise s.error(tok, "#%s is not supported" % d)

    def _include(self, tok, folder):
        for base in [folder] + POV_INCLUDE_DIRS:
            path = os.path.join(base, tok.text)
            if os.path.isfile(path):
                break
        else:
            raise PovError(tok.line, tok.col, '#include "%s": not found next to the scene or in '
                           "POV-Ray's include folder" % tok.text)
        with open(path, encoding="utf-8", errors="replace") as f:
            text = f.read()
        if os.path.dirname(os.path.abspath(path)) in POV_INCLUDE_DIRS:
            self._library_names(text)
        else:
            try:
                self._statements(Stream(tokenize(text)), os.path.dirname(path))
            except PovError as e:
                raise PovError(tok.line, tok.col, '#include "%s": %s:%d:%d: %s' % (
                    tok.text, path, e.line, e.col, e.message))

    def _library_names(self, text):
        """POV-Ray's own include files (colors.inc, finish.inc, ...) are full of macros and
        conditionals; only their top-level `#declare`s of values we understand are taken. A name
        that is not taken stays unknown and is refused where the scene uses it."""
        try:
            s = Stream(tokenize(text))
        except PovError:
            return
        ex = Expressions(s, self.symbols)
        while s.peek().kind != "end":
            tok = s.next()
            if tok.kind == "directive" and tok.text == "declare" and s.peek().kind == "name":
                start = s.pos
                try:
                    self._declare(s, ex)
                except PovError:
                    s.pos = start
                    while s.peek().kind != "end" and not s.accept(";"):
                        s.next()

    def _declare(self, s, ex):
        name = s.next()
        if name.kind != "name":
            raise s.error(name, "expected a name after #declare")
        s.expect("=")
        word = s.peek().text if s.peek().kind == "name" else None
        if word in ("pigment", "finish", "texture", "transform"):
            s.next()
            value = getattr(self, "_" + word)(s, ex)
        elif word in ("color", "colour", "rgb", "rgbf", "rgbt", "rgbft", "srgb", "red", "green",
                      "blue"):
            value = parse_color(ex)
        elif word in ("blob", "sphere", "box", "plane", "cylinder", "union", "merge",
                      "difference", "intersection", "object", "camera", "light_source"):
            raise s.error(s.peek(), "#declare of a %s is not supported; write it out where it "
                          "is used" % word)
        else:
            value = ex.expr()
        self.symbols.declared[name.text] = value
        s.accept(";")

    def _default(self, s, ex):
        s.expect("{")
        while not s.closes("#default"):
            tok = s.next()
            if tok.text == "finish":
                self.default_finish.update(self._finish(s, ex))
            elif tok.text == "texture":
                t = self._texture(s, ex)
                self.default_finish.update(t.get("finish", {}))
                if "color" in t:
                    raise s.error(tok, "#default pigments are not supported")
            else:
                raise s.error(tok, "#default { %s } is not supported" % tok.text)

    def _item(self, s, ex, tok):
        word = tok.text
        s.next()
        if word == "camera":
            self.camera = self._camera(s, ex, tok)
        elif word == "light_source":
            self.lights.append(self._light(s, ex))
        elif word == "background":
            s.expect("{")
            c = parse_color(ex, "the background")
            s.expect("}")
            self.background = c[:3]
        elif word == "sky_sphere":
            self.sky = sky_sphere(s, ex, tok)
        elif word == "global_settings":
            self._global_settings(s, ex)
        elif word == "blob":
            self.objects.append(self._blob(s, ex, tok))
        elif word in SHAPES:
            self.objects.append(self._shape(s, ex, tok))
        elif word in CSG:
            self.objects.append(self._csg(s, ex, tok))
        elif word in ("mesh", "mesh2"):
            self.objects.append(self._mesh(s, ex, tok))
        else:
            raise s.error(tok, "'%s' is not supported (this converter takes blob, plane, box, "
                          "sphere, cylinder, cone, disc, mesh and mesh2 objects, their union, "
                          "merge, intersection and difference, camera, light_source, background, "
                          "sky_sphere and global_settings)" % word)

    def _global_settings(self, s, ex):
        s.expect("{")
        while not s.closes("global_settings"):
            tok = s.next()
            if tok.text == "assumed_gamma":
                g = ex.number("assumed_gamma")
                if abs(g - 1.0) > 1e-9:
                    raise s.error(tok, "assumed_gamma %g: only 1.0 (linear colours, POV-Ray "
                                  "3.7's own) is supported" % g)
            elif tok.text == "ambient_light":
                self.ambient_light = parse_color(ex, "ambient_light")[:3]
            elif tok.text in ("max_trace_level", "adc_bailout", "number_of_waves", "noise_generator"):
                ex.number(tok.text)
            else:
                raise s.error(tok, "global_settings { %s } is not supported" % tok.text)

    # ---- camera and lights ---------------------------------------------------------------
    def _camera(self, s, ex, at):
        s.expect("{")
        location, look_at = (0.0, 0.0, 0.0), None
        direction, up, right, sky = (0.0, 0.0, 1.0), (0.0, 1.0, 0.0), (1.33, 0.0, 0.0), None
        angle = None
        orthographic, aperture, focal_point, blur_samples = False, 0.0, None, None
        while not s.closes("camera"):
            tok = s.next()
            w = tok.text
            if w == "perspective":
                continue
            if w == "orthographic":
                orthographic = True
            elif w == "aperture":
                aperture = ex.number("aperture")
                if aperture < 0:
                    raise s.error(tok, "aperture %g: must be >= 0" % aperture)
            elif w == "focal_point":
                focal_point = ex.vector("focal_point")
            elif w == "blur_samples":
                # `blur_samples N` or `blur_samples MIN, MAX`: POV-Ray stops between the two
                # when its confidence test passes; softtrace takes every sample, the most.
                blur_samples = ex.number("blur_samples")
                if s.accept(","):
                    blur_samples = ex.number("blur_samples")
                if not (1 <= blur_samples <= 4096 and blur_samples == int(blur_samples)):
                    raise s.error(tok, "blur_samples %g: must be a whole number from 1 to 4096"
                                  % blur_samples)
            elif w in ("confidence", "variance"):
                ex.number(w)  # the adaptive stop: softtrace takes all blur_samples
            elif w == "location":
                location = ex.vector("location")
            elif w == "look_at":
                look_at = ex.vector("look_at")
            elif w == "direction":
                direction = ex.vector("direction")
            elif w == "up":
                up = ex.vector("up")
            elif w == "right":
                right = ex.vector("right")
            elif w == "sky":
                sky = ex.vector("sky")
            elif w == "angle":
                angle = ex.number("angle")
                if not 0 < angle < 180:
                    raise s.error(tok, "angle %g: must be in (0, 180) degrees" % angle)
            elif w in TRANSFORMS:
                raise s.error(tok, "camera transformations are not supported; use location and "
                              "look_at")
            else:
                raise s.error(tok, "camera { %s } is not supported" % w)
        norm = lambda v: math.sqrt(sum(c * c for c in v))  # noqa: E731
        if norm(right) == 0 or norm(up) == 0 or norm(direction) == 0:
            raise s.error(at, "camera: right, up and direction must be non-zero")
        # POV-Ray's image plane: `right` spans the width, `up` the height, at `direction`'s
        # distance; `angle` sets that distance from the width. A negative x component of `right`
        # is the right-handed trick, which mirrors the picture.
        if right[0] < 0:
            raise s.error(at, "camera: a right vector along -x (a mirrored, right-handed view) "
                          "is not supported")
        dist = norm(direction) if angle is None else norm(right) / 2 / math.tan(math.radians(angle) / 2)
        vfov = math.degrees(2 * math.atan(norm(up) / 2 / dist))
        if look_at is None:
            look_at = tuple(l + d for l, d in zip(location, direction))
        sky = sky or up
        camera = {"eye": list(affine.to_softtrace_point(location)),
                  "target": list(affine.to_softtrace_point(look_at)),
                  "up": list(affine.to_softtrace_point(sky)), "fov": vfov}
        # POV-Ray stretches the picture across when right/up is not the image's aspect (its
        # default right, 1.33, on a 4:3 image: 0.25%, a fifth of a pixel 80 pixels from the
        # centre); softtrace's `aspect` stretches it alike. Within 1e-6 (a hundredth of a pixel
        # at 16384 across) it is the image's, written as a ratio of the sizes.
        if abs(norm(right) / norm(up) - self.width / self.height) > 1e-6 * self.width / self.height:
            camera["aspect"] = norm(right) / norm(up)
        view = norm([t - l for t, l in zip(look_at, location)])
        if orthographic:
            if view == 0:
                raise s.error(at, "camera: an orthographic camera needs look_at away from "
                              "location")
            # POV-Ray's orthographic view is `up` tall (in world units); with `angle` it is as
            # tall as the perspective view at look_at. softtrace's is the latter: the field of
            # view that gives `up`'s height there.
            camera["projection"] = "orthographic"
            if angle is None:
                camera["fov"] = math.degrees(2 * math.atan(norm(up) / 2 / view))
        if aperture > 0:
            if orthographic:
                raise s.error(at, "camera: focal blur with an orthographic camera is not "
                              "supported")
            # POV-Ray moves the eye by up to aperture/4 (its sample grid's radius 1/2 times
            # aperture/2) across the view: a lens of diameter aperture/2. The plane in focus is
            # across the view at focal_point's distance from location (default <0, 0, 0>).
            fp = focal_point if focal_point is not None else (0.0, 0.0, 0.0)
            camera["aperture"] = aperture / 2
            camera["focal_distance"] = norm([f - l for f, l in zip(fp, location)])
            camera["blur_samples"] = int(blur_samples if blur_samples is not None else 4)
        return camera

    def _light(self, s, ex):
        s.expect("{")
        tok = s.peek()
        position = ex.vector("the light's location")
        s.accept(",")
        color = parse_color(ex, "the light's colour")[:3]
        parallel, spot, point_at, shadows = False, None, None, True
        fade, area = {}, None
        m = affine.IDENTITY
        while not s.closes("light_source"):
            t = s.next()
            w = t.text
            if w == "parallel":
                parallel = t
            elif w == "spotlight":
                spot = {}
            elif w in ("radius", "falloff", "tightness"):
                if spot is None:
                    raise s.error(t, "'%s' belongs to a spotlight: write spotlight first" % w)
                spot[w] = ex.number(w)
            elif w == "point_at":
                point_at = ex.vector("point_at")
            elif w == "shadowless":
                shadows = False
            elif w in ("fade_distance", "fade_power"):
                fade[w] = ex.number(w)
            elif w == "area_light":
                area = self._area_light(s, ex, t)
            elif w in ("adaptive", "jitter") and area is not None:
                if w == "adaptive":
                    area["adaptive"] = int(ex.number("adaptive"))
                else:
                    area["jitter"] = True
            elif w in TRANSFORMS:
                m = affine.mul(self._transform_step(s, ex, t), m)
            else:
                raise s.error(t, "light_source { %s } is not supported" % w)
        if parallel and (spot is not None or area is not None):
            raise s.error(parallel, "a parallel spotlight or area light is not supported")
        # POV-Ray's point_at defaults: <0, 0, 0> for parallel lights, <0, 0, 1> for spotlights.
        if point_at is None:
            point_at = (0.0, 0.0, 1.0) if spot is not None else (0.0, 0.0, 0.0)
        position = affine.apply(m, position)
        point_at = affine.apply(m, point_at)
        light = {"color": list(color), "shadows": shadows}
        if parallel:
            d = tuple(p - q for p, q in zip(point_at, position))
            if not any(d):
                raise s.error(tok, "a parallel light needs point_at away from its location")
            light.update(type="directional", direction=list(affine.to_softtrace_point(d)))
            return light
        light.update(type="point", position=list(affine.to_softtrace_point(position)))
        if spot is not None:
            if point_at == position:
                raise s.error(tok, "a spotlight needs point_at away from its location")
            light.update(type="spot", point_at=list(affine.to_softtrace_point(point_at)))
            light.update(spot)
        light.update(fade)
        if area is not None:
            lin = affine.linear(m)
            for key in ("axis1", "axis2"):
                v = [sum(lin[i][j] * area[key][j] for j in range(3)) for i in range(3)]
                area[key] = list(affine.to_softtrace_point(v))
            light["area"] = area
        return light

    def _area_light(self, s, ex, tok):
        axis1 = ex.vector("area_light's first axis")
        s.expect(",")
        axis2 = ex.vector("area_light's second axis")
        s.expect(",")
        size1 = ex.number("area_light's first size")
        s.expect(",")
        size2 = ex.number("area_light's second size")
        for w in ("circular", "orient", "area_illumination"):
            if s.at(w, "name"):
                raise s.error(s.peek(), "area_light's '%s' is not supported" % w)
        if size1 != int(size1) or size2 != int(size2) or not (1 <= size1 <= 64 and 1 <= size2 <= 64):
            raise s.error(tok, "area_light sizes must be whole numbers from 1 to 64")
        return {"axis1": axis1, "axis2": axis2, "size1": int(size1), "size2": int(size2)}

    # ---- appearance ----------------------------------------------------------------------
    def _pigment(self, s, ex):
        tok = s.expect("{")
        if s.peek().kind == "name" and isinstance(self.symbols.get(s.peek().text), dict):
            ref = self._reference(s, "pigment")
            s.expect("}")
            return dict(ref)
        c = parse_color(ex, "the pigment")
        if not (0 <= c[3] <= 1 and 0 <= c[4] <= 1 and c[3] + c[4] <= 1):
            raise s.error(tok, "filter %g and transmit %g: softtrace takes each in [0, 1] with "
                          "filter + transmit <= 1" % (c[3], c[4]))
        s.expect("}", "(only a plain colour pigment is supported)")
        # r, g, b, filter, transmit (POV's rgbft); _material splits them.
        return {"kind": "pigment", "color": list(c[:5])}

    def _finish(self, s, ex):
        s.expect("{")
        f = {"kind": "finish"}
        while not s.closes("finish"):
            tok = s.next()
            w = tok.text
            if tok.kind == "name" and isinstance(self.symbols.get(w), dict):
                s.pos -= 1
                f.update(self._reference(s, "finish"))
            elif w in FINISH_KEYS:
                f[w] = ex.number(w) if w != "metallic" or self._number_follows(s) else 1.0
            elif w == "reflection":
                if s.accept("{"):
                    self._reflection_block(s, ex, tok, f)
                else:
                    f[w] = parse_color(ex, "reflection")[0]
            elif w == "conserve_energy":
                f[w] = self._flag(s)
            else:
                raise s.error(tok, "finish { %s } is not supported" % w)
        return f

    def _reflection_block(self, s, ex, tok, f):
        """reflection { [MIN,] MAX [fresnel [on|off]] }: a constant reflection, or with fresnel
        the Fresnel reflectance's blend from MIN (0 where only MAX is given) to MAX."""
        first = parse_color(ex, "reflection")[0]
        second = parse_color(ex, "reflection")[0] if s.accept(",") else None
        fresnel = False
        while not s.closes("reflection"):
            t = s.next()
            if t.text != "fresnel":
                raise s.error(t, "reflection { %s } is not supported" % t.text)
            fresnel = self._flag(s)
        low, high = (0.0, first) if second is None else (first, second)
        if not fresnel:
            if second is not None and first != second:
                raise s.error(tok, "a reflection that varies with the angle is supported with "
                              "fresnel only")
            f["reflection"], f["fresnel"] = high, False
            f.pop("reflection_min", None)
            return
        f["reflection"], f["fresnel"], f["reflection_min"] = high, True, low

    @staticmethod
    def _flag(s):
        """An optional on/off (true/false, yes/no, 1/0) after a keyword; on where absent."""
        t = s.peek()
        if t.kind == "name" and t.text in ("on", "off", "true", "false", "yes", "no"):
            s.next()
            return t.text in ("on", "true", "yes")
        if t.kind == "number" and t.text in ("0", "1"):
            s.next()
            return t.text == "1"
        return True

    def _interior(self, s, ex, tok):
        """interior { ior N }: the object's index of refraction (caustics, which softtrace does
        not draw, is taken and left out)."""
        s.expect("{")
        ior = 1.0
        while not s.closes("interior"):
            t = s.next()
            if t.text == "ior":
                ior = ex.number("ior")
                if not 0.01 <= ior <= 100:
                    raise s.error(t, "ior %g: softtrace takes 0.01 to 100" % ior)
            elif t.text == "caustics":
                ex.number("caustics")
            else:
                raise s.error(t, "interior { %s } is not supported" % t.text)
        return ior

    @staticmethod
    def _number_follows(s):
        t = s.peek()
        return t.kind == "number" or (t.kind == "punct" and t.text in "(-+<")

    def _texture(self, s, ex):
        s.expect("{")
        t = {"kind": "texture"}
        while not s.closes("texture"):
            tok = s.next()
            if tok.kind == "name" and isinstance(self.symbols.get(tok.text), dict):
                s.pos -= 1
                t.update(self._reference(s, "texture"))
            elif tok.text == "pigment":
                t["color"] = self._pigment(s, ex)["color"]
            elif tok.text == "finish":
                t.setdefault("finish", {}).update(self._finish(s, ex))
            else:
                raise s.error(tok, "texture { %s } is not supported" % tok.text)
        return t

    def _reference(self, s, kind):
        tok = s.next()
        value = self.symbols.get(tok.text)
        if value.get("kind") != kind:
            raise s.error(tok, "'%s' is a %s, not a %s" % (tok.text, value.get("kind"), kind))
        return {k: v for k, v in value.items() if k != "kind"}

    def _transform(self, s, ex):
        s.expect("{")
        m = affine.IDENTITY
        while not s.closes("transform"):
            tok = s.next()
            if tok.text not in TRANSFORMS:
                raise s.error(tok, "transform { %s } is not supported" % tok.text)
            m = affine.mul(self._transform_step(s, ex, tok), m)
        return {"kind": "transform", "matrix": m}

    def _transform_step(self, s, ex, tok):
        w = tok.text
        if w == "translate":
            return affine.translate(ex.vector("translate"))
        if w == "rotate":
            return affine.rotate(ex.vector("rotate"))
        if w == "scale":
            v = ex.vector("scale")
            if any(c == 0 for c in v):
                raise s.error(tok, "scale by zero")
            return affine.scale(v)
        if w == "matrix":
            s.expect("<", "after matrix")
            m = [ex.number("a matrix entry")]
            while s.accept(","):
                m.append(ex.number("a matrix entry"))
            s.expect(">", "to close the matrix")
            if len(m) != 12:
                raise s.error(tok, "matrix needs 12 numbers, found %d" % len(m))
            t = affine.pov_matrix(m)
            if abs(affine.det3(affine.linear(t))) < 1e-12:
                raise s.error(tok, "the matrix is singular")
            return t
        # transform { ... } or transform NAME
        if s.at("{"):
            return self._transform(s, ex)["matrix"]
        return self._reference(s, "transform")["matrix"]

    def _material(self, pigment, finish, at, s, ior=1.0):
        """The object's material; None for an object inside a CSG without a pigment of its own,
        which takes the enclosing CSG's (docs/scene-format.md "CSG of objects")."""
        if pigment is None:
            if self.csg_depth > 0:
                if finish:
                    raise s.error(at, "the %s has a finish but no pigment; a CSG's part takes "
                                  "its whole texture from the CSG, so give it a pigment too"
                                  % at.text)
                return None
            raise s.error(at, "the %s has no pigment" % at.text)
        f = dict(self.default_finish)
        f.update({k: v for k, v in finish.items() if k != "kind"})
        material = {"color": [float(c) for c in pigment[:3]]}
        for key in FINISH_KEYS + ("reflection",):
            value = f[key]
            if key in ("ambient", "diffuse") or value != FINISH_DEFAULTS[key]:
                material[key] = value
        if f.get("fresnel"):
            material["fresnel"] = True
            if f.get("reflection_min"):
                material["reflection_min"] = f["reflection_min"]
        if f.get("conserve_energy"):
            material["conserve_energy"] = True
        # POV's rgbft: the light behind passes filtered by the colour, and transmitted as it is.
        for key, value in zip(("filter", "transmit"), list(pigment[3:5]) + [0.0, 0.0]):
            if value:
                material[key] = float(value)
        if ior != 1.0:
            material["ior"] = ior
        return material

    def _modifier(self, s, ex, tok, mods):
        """Takes an object's transformation, pigment, finish or texture into `mods` (blobs and
        shapes share them); False for any other keyword, which the caller decides on."""
        w = tok.text
        if w in TRANSFORMS:
            mods.matrix = affine.mul(self._transform_step(s, ex, tok), mods.matrix)
        elif w == "pigment":
            mods.pigment = self._pigment(s, ex)["color"]
        elif w == "finish":
            mods.finish.update(self._finish(s, ex))
        elif w == "texture":
            t = self._texture(s, ex)
            mods.pigment = t.get("color", mods.pigment)
            mods.finish.update(t.get("finish", {}))
        elif w == "interior":
            mods.ior = self._interior(s, ex, tok)
        else:
            return False
        return True

    # ---- plain shapes ----------------------------------------------------------------------
    def _shape(self, s, ex, at):
        """POV-Ray's finite primitives and its plane as softtrace shape objects (docs/pov.md)."""
        word = at.text
        s.expect("{")
        pt = lambda what: list(affine.to_softtrace_point(ex.vector(what)))  # noqa: E731
        if word == "plane":
            shape = {"normal": pt("the plane's normal")}
            s.expect(",")
            shape["distance"] = ex.number("the plane's distance")
        elif word == "box":
            shape = {"corner1": pt("the first corner")}
            s.expect(",")
            shape["corner2"] = pt("the second corner")
        elif word == "sphere":
            shape = {"center": pt("the centre")}
            s.expect(",")
            shape["radius"] = ex.number("the radius")
        elif word == "cylinder":
            shape = {"base": pt("the base point")}
            s.expect(",")
            shape["cap"] = pt("the cap point")
            s.expect(",")
            shape["radius"] = ex.number("the radius")
        elif word == "cone":
            shape = {"base": pt("the base point")}
            s.expect(",")
            shape["base_radius"] = ex.number("the base radius")
            s.expect(",")
            shape["cap"] = pt("the cap point")
            s.expect(",")
            shape["cap_radius"] = ex.number("the cap radius")
        else:
            shape = {"center": pt("the centre")}
            s.expect(",")
            shape["normal"] = pt("the normal")
            s.expect(",")
            shape["radius"] = ex.number("the radius")
            if s.accept(","):
                shape["hole_radius"] = ex.number("the hole radius")
        shape = dict({"type": word}, **shape)
        mods = Modifiers()
        while not s.closes(word):
            tok = s.next()
            if self._modifier(s, ex, tok, mods) or tok.text in HARMLESS:
                continue
            raise s.error(tok, "%s { %s } is not supported" % (word, tok.text))
        if mods.matrix != affine.IDENTITY:
            full = affine.to_softtrace(mods.matrix)
            if affine.linear(full) == affine.linear(affine.IDENTITY):
                shape["translate"] = [full[i][3] for i in range(3)]
            else:
                shape["matrix"] = [list(full[i]) for i in range(3)]
        material = self._material(mods.pigment, mods.finish, at, s, mods.ior)
        return self._named(word, material, shape=shape)

    # ---- triangle meshes -----------------------------------------------------------------
    def _mesh(self, s, ex, at, operand=False):
        """POV-Ray's `mesh` (triangle and smooth_triangle) and `mesh2` (vertex_vectors,
        normal_vectors, face_indices, normal_indices) as a softtrace mesh object. The triangles
        go to an OBJ file beside the scene (Converter.meshes; tools/pov2softtrace.py writes them
        and names the file in the object's "mesh"); POV-Ray's y-up points become z-up ones. A
        CSG operand needs `inside_vector`: without one POV-Ray gives a mesh no inside, softtrace
        takes a closed mesh's."""
        word = at.text
        s.expect("{")
        pt = lambda what: tuple(affine.to_softtrace_point(ex.vector(what)))  # noqa: E731
        positions, normals, faces, face_normals = [], [], [], []
        mods = Modifiers()
        solid = False
        if word == "mesh":
            index = {}

            def vertex(p):
                if p not in index:
                    index[p] = len(positions)
                    positions.append(p)
                return index[p]

            while not s.closes("mesh"):
                tok = s.next()
                if tok.text in ("triangle", "smooth_triangle"):
                    smooth = tok.text == "smooth_triangle"
                    s.expect("{")
                    corners, corner_normals = [], []
                    for k in range(3):
                        if k:
                            s.expect(",")
                        corners.append(vertex(pt("a corner")))
                        if smooth:
                            s.expect(",")
                            corner_normals.append(pt("a corner's normal"))
                    if not s.closes(tok.text):
                        raise s.error(s.peek(), "%s { %s }: a triangle's own texture is not "
                                      "supported (give the mesh one)" % (tok.text, s.peek().text))
                    faces.append(corners)
                    if smooth:
                        face_normals.append(list(range(len(normals), len(normals) + 3)))
                        normals.extend(corner_normals)
                    else:
                        face_normals.append(None)
                elif tok.text == "inside_vector":
                    ex.vector("inside_vector")  # softtrace finds a closed mesh's inside itself
                    solid = True
                elif not (self._modifier(s, ex, tok, mods) or tok.text in HARMLESS):
                    raise s.error(tok, "mesh { %s } is not supported" % tok.text)
        else:
            def block(what, read):
                s.expect("{")
                n = ex.number("the number of " + what)
                if n != int(n) or n < 0:
                    raise s.error(s.peek(), "%s: expected a whole count, not %g" % (what, n))
                items = []
                for k in range(int(n)):
                    s.expect(",")
                    items.append(read())
                if not s.closes(what):
                    raise s.error(s.peek(), "%s: more items than its count, %d" % (what, n))
                return items

            def triple(what):
                tok = s.peek()
                v = ex.vector(what)
                if any(c != int(c) for c in v):
                    raise s.error(tok, "%s: expected whole vertex numbers" % what)
                return [int(c) for c in v]

            while not s.closes("mesh2"):
                tok = s.next()
                if tok.text == "vertex_vectors":
                    positions = block("vertex_vectors", lambda: pt("a vertex"))
                elif tok.text == "normal_vectors":
                    normals = block("normal_vectors", lambda: pt("a normal"))
                elif tok.text == "face_indices":
                    faces = block("face_indices", lambda: triple("face_indices"))
                elif tok.text == "normal_indices":
                    face_normals = block("normal_indices", lambda: triple("normal_indices"))
                elif tok.text == "inside_vector":
                    ex.vector("inside_vector")
                    solid = True
                elif tok.text in ("uv_vectors", "uv_indices", "texture_list"):
                    raise s.error(tok, "mesh2 { %s } is not supported (one texture for the "
                                  "whole mesh)" % tok.text)
                elif not (self._modifier(s, ex, tok, mods) or tok.text in HARMLESS):
                    raise s.error(tok, "mesh2 { %s } is not supported" % tok.text)
            for f in faces:
                if any(not 0 <= i < len(positions) for i in f):
                    raise s.error(at, "mesh2: face_indices <%d, %d, %d> names a vertex beyond "
                                  "the %d of vertex_vectors" % (f[0], f[1], f[2], len(positions)))
            if face_normals and len(face_normals) != len(faces):
                raise s.error(at, "mesh2: %d normal_indices for %d faces" % (
                    len(face_normals), len(faces)))
            if not face_normals and normals:
                if len(normals) != len(positions):
                    raise s.error(at, "mesh2: normal_vectors without normal_indices must be one "
                                  "per vertex (%d for %d)" % (len(normals), len(positions)))
                face_normals = [list(f) for f in faces]
            for f in face_normals:
                if any(not 0 <= i < len(normals) for i in f):
                    raise s.error(at, "mesh2: normal_indices <%d, %d, %d> names a normal beyond "
                                  "the %d of normal_vectors" % (f[0], f[1], f[2], len(normals)))
        if not faces:
            raise s.error(at, "%s: no triangles" % word)
        if operand and not solid:
            raise s.error(at, "a %s in a CSG needs inside_vector (without it POV-Ray gives the "
                          "mesh no inside)" % word)
        # One face without normals makes the mesh flat, as softtrace reads OBJ files.
        if any(f is None for f in face_normals) or not face_normals:
            normals, face_normals = [], []
        obj = self._named(word, self._material(mods.pigment, mods.finish, at, s))
        obj["mesh"] = len(self.meshes)  # replaced by the OBJ file's name when written
        self.meshes.append({"positions": positions, "normals": normals, "faces": faces,
                            "face_normals": face_normals})
        if mods.matrix != affine.IDENTITY:
            full = affine.to_softtrace(mods.matrix)
            obj["matrix"] = [list(full[i]) for i in range(3)]
        return obj

    # ---- blob ----------------------------------------------------------------------------
    def _blob(self, s, ex, at):
        s.expect("{")
        threshold = 1.0
        components = []
        mods = Modifiers()
        while not s.closes("blob"):
            tok = s.next()
            w = tok.text
            if self._modifier(s, ex, tok, mods):
                continue
            if w == "threshold":
                threshold = ex.number("threshold")
                if threshold <= 0:
                    raise s.error(tok, "threshold %g: must be positive" % threshold)
            elif w in ("sphere", "cylinder", "component"):
                components.append(self._component(s, ex, tok))
            elif w in HARMLESS:
                if w == "hierarchy" and s.peek().kind == "name" and s.peek().text in (
                        "on", "off", "true", "false", "yes", "no"):
                    s.next()
            else:
                raise s.error(tok, "blob { %s } is not supported" % w)
        children = []
        for comp in components:
            child = self._soft_object(comp, mods.matrix)
            if child is not None:
                children.append(child)
        if not any(c.get("strength", 1.0) > 0 for c in children):
            raise s.error(at, "the blob has no component of positive strength, so no surface")
        # Components with textures of their own (docs/scene-format.md "Component materials"):
        # mixed at a hit by |strength * field| as POV-Ray mixes them. A lone component's is the
        # object's; a blob whose every component has one needs none of its own.
        if len(children) == 1 and "material" in children[0]:
            material = children[0].pop("material")
        elif mods.pigment is None and children and all("material" in c for c in children):
            material = None
        else:
            material = self._material(mods.pigment, mods.finish, at, s, mods.ior)
        field = children[0] if len(children) == 1 else {"type": "soft_blend",
                                                          "children": children}
        return self._named("blob", material, convention="soft", iso=threshold, field=field)

    def _named(self, word, material, **keys):
        """An object named after its kind and count (blob1, box2, difference1), with its
        material where it has one."""
        n = self.names.get(word, 0) + 1
        self.names[word] = n
        obj = {"name": "%s%d" % (word, n)}
        if material is not None:
            obj["material"] = material
        obj.update(keys)
        return obj

    # ---- CSG -----------------------------------------------------------------------------
    def _csg(self, s, ex, at):
        """POV-Ray's union, merge, intersection and difference of blobs, shapes and CSGs as a
        softtrace CSG object. Its parts are converted where they stand, so a transformation of
        the CSG itself is refused (transform its parts instead)."""
        word = at.text
        s.expect("{")
        operands = []
        mods = Modifiers()
        cutaway = False
        self.csg_depth += 1
        while not s.closes(word):
            tok = s.next()
            w = tok.text
            if w == "cutaway_textures":
                if word not in ("intersection", "difference"):
                    raise s.error(tok, "cutaway_textures can only be used with intersection "
                                  "and difference")
                cutaway = True
            elif w == "blob":
                operands.append(self._blob(s, ex, tok))
            elif w in SHAPES:
                operands.append(self._shape(s, ex, tok))
            elif w in CSG:
                operands.append(self._csg(s, ex, tok))
            elif w in ("mesh", "mesh2"):
                operands.append(self._mesh(s, ex, tok, operand=True))
            elif w in TRANSFORMS:
                raise s.error(tok, "a transformation of a %s is not supported; transform its "
                              "objects instead" % word)
            elif self._modifier(s, ex, tok, mods) or w in HARMLESS:
                continue
            else:
                raise s.error(tok, "%s { %s } is not supported" % (word, w))
        self.csg_depth -= 1
        if len(operands) < 2:
            raise s.error(at, "the %s has %d object(s); softtrace needs at least two"
                          % (word, len(operands)))
        for op in operands:
            if op.get("shape", {}).get("type") == "disc":
                raise s.error(at, "a disc in a %s is not supported (it has no inside)" % word)
        # A top-level CSG needs no pigment where every part has one of its own.
        def textured(obj):
            return "material" in obj or ("csg" in obj and all(map(textured, obj["operands"])))
        # With cutaway_textures an untextured part shows what it cuts (softtrace's loader finds
        # it), so a CSG with any textured part needs no pigment either.
        def any_textured(obj):
            return "material" in obj or ("csg" in obj and any(map(any_textured, obj["operands"])))
        if mods.pigment is None and self.csg_depth == 0 and (
                all(map(textured, operands)) or (cutaway and any(map(any_textured, operands)))):
            material = None
        else:
            material = self._material(mods.pigment, mods.finish, at, s, mods.ior)
        keys = {"cutaway_textures": True} if cutaway else {}
        return self._named(word, material, csg=word, **keys, operands=operands)

    def _component(self, s, ex, tok):
        w = tok.text
        c = {"at": tok}
        if w == "component":
            c["strength"] = ex.number("strength")
            s.expect(",")
            c["radius"] = ex.number("radius")
            s.expect(",")
            c["center"] = ex.vector("centre")
            c["kind"] = "sphere"
            c["matrix"] = affine.IDENTITY
            return c
        s.expect("{")
        c["kind"] = w
        if w == "sphere":
            c["center"] = ex.vector("centre")
        else:
            c["p0"] = ex.vector("base point")
            s.expect(",")
            c["p1"] = ex.vector("cap point")
        s.expect(",")
        c["radius"] = ex.number("radius")
        s.accept(",")
        s.accept("strength")
        c["strength"] = ex.number("strength")
        m = affine.IDENTITY
        own = Modifiers()  # the component's own texture (POV-Ray: it replaces the blob's)
        textured_at = None
        while not s.closes("a component"):
            t = s.next()
            if t.text in TRANSFORMS:
                m = affine.mul(self._transform_step(s, ex, t), m)
            elif t.text in ("pigment", "texture", "finish"):
                self._modifier(s, ex, t, own)
                textured_at = textured_at or t
            else:
                raise s.error(t, "%s component { %s } is not supported" % (w, t.text))
        if textured_at is not None:
            if own.pigment is None:
                raise s.error(textured_at, "a component's texture needs a pigment: POV-Ray gives "
                              "a component with a texture of its own nothing of the blob's")
            c["material"] = self._material(own.pigment, own.finish, tok, s)
        if c["radius"] <= 0:
            raise s.error(tok, "a %s component's radius must be positive" % w)
        if w == "cylinder" and c["p0"] == c["p1"]:
            raise s.error(tok, "a cylinder component's two points are the same")
        c["matrix"] = m
        return c

    def _soft_object(self, c, blob_matrix):
        """One component as a murakami soft object: (1 - (d/r)^2)^2 inside r, POV-Ray's density,
        times its strength. Placement is kept as plain as it can be: a sphere or segment moved
        and turned (and uniformly scaled) is written in world coordinates, an axis-aligned
        stretch as an ellipsoid's radii, anything else as an affine `matrix`."""
        if c["strength"] == 0:
            return None  # POV-Ray: a component of strength 0 adds nothing
        full = affine.to_softtrace(affine.mul(blob_matrix, c["matrix"]))
        a = affine.linear(full)
        k = affine.column_scales(a)
        r = c["radius"]
        node = {"type": "soft_object", "potential": {"type": "murakami"}}
        if "material" in c:
            node["material"] = c["material"]
        if c["strength"] != 1:
            node["strength"] = c["strength"]
        uniform = k is not None and max(k) - min(k) <= 1e-12 * max(k)
        if c["kind"] == "sphere":
            center = affine.apply(full, affine.to_softtrace_point(c["center"]))
            if uniform:
                node["distance"] = {"type": "lp_metric", "radii": [r * k[0]] * 3, "n": 2}
                node["translate"] = list(center)
                return node
            if k is not None:
                rot = tuple(tuple(a[i][j] / k[j] for j in range(3)) for i in range(3))
                node["distance"] = {"type": "lp_metric", "radii": [r * kk for kk in k], "n": 2}
                axis, deg = affine.axis_angle(rot)
                node["translate"] = list(center)
                if axis is not None:
                    node["rotate"] = {"axis": list(axis), "deg": deg}
                return node
            node["distance"] = {"type": "lp_metric", "radii": [r, r, r], "n": 2}
            full = affine.mul(full, affine.translate(affine.to_softtrace_point(c["center"])))
        else:
            p0 = affine.to_softtrace_point(c["p0"])
            p1 = affine.to_softtrace_point(c["p1"])
            if uniform:
                node["distance"] = {"type": "segment", "p0": list(affine.apply(full, p0)),
                                    "p1": list(affine.apply(full, p1)), "radius": r * k[0]}
                return node
            node["distance"] = {"type": "segment", "p0": list(p0), "p1": list(p1), "radius": r}
        node["matrix"] = [list(full[i]) for i in range(3)]
        return node


def convert(path, text, width, height, meshes=None):
    """The scene as a dict; `meshes`, a list, receives each mesh object's triangles
    ({"positions", "normals", "faces", "face_normals"}, softtrace's axes, 0-based), whose index
    the object's "mesh" holds until the caller writes them (obj_text) and names the file."""
    c = Converter(path, width, height)
    scene = c.run(text)
    if meshes is not None:
        meshes.extend(c.meshes)
    return scene


def obj_text(mesh):
    """A converted mesh as a Wavefront OBJ file's text (docs/scene-format.md "Triangle meshes")."""
    lines = ["# Converted by tools/pov2softtrace.py: %d vertices, %d triangles" % (
        len(mesh["positions"]), len(mesh["faces"]))]
    lines += ["v %.17g %.17g %.17g" % tuple(p) for p in mesh["positions"]]
    lines += ["vn %.17g %.17g %.17g" % tuple(n) for n in mesh["normals"]]
    if mesh["face_normals"]:
        lines += ["f %d//%d %d//%d %d//%d" % (f[0] + 1, n[0] + 1, f[1] + 1, n[1] + 1, f[2] + 1,
                                               n[2] + 1)
                  for f, n in zip(mesh["faces"], mesh["face_normals"])]
    else:
        lines += ["f %d %d %d" % (f[0] + 1, f[1] + 1, f[2] + 1) for f in mesh["faces"]]
    return "\n".join(lines) + "\n"
