"""POV-Ray 3.7 versions of softtrace scenes, for tools/pov_compare.py and the scene generators
(tools/blob_scene.py, tools/segment_tracing_scene.py, tools/pov_cloud.py), and their output.

softtrace is right-handed with z up; POV-Ray is left-handed with y up. Swapping y and z turns one
into the other (a swap of two axes flips the handedness), so a softtrace point (x, y, z) is POV's
<x, z, y> and the picture is the same, not mirrored. softtrace's `fov` is vertical; POV's `angle`
is horizontal.

Two kinds of object are written:
- `blob`: a soft_blend of murakami soft objects over spheres (lp_metric, n = 2, equal radii) at
  iso t is POV's blob of the same spheres with strength 1 and threshold t: both sum
  (1 - (d/r)^2)^2 inside each sphere.
- `isosurface`: the Fig. 12(b) blend (scenes/fig000_12b_soft_blend.json), written out in POV's
  function syntax.
"""
import json
import math
import sys


def pov_vec(v):
    """softtrace (x, y, z) as POV's <x, z, y>."""
    return "<%.9g, %.9g, %.9g>" % (v[0], v[2], v[1])


def header(scene, width, height, alpha=True):
    """Camera, lights and background of a softtrace scene (a parsed JSON object).

    With alpha the background is transparent (POV's +UA alpha is then the coverage mask);
    without, it is the scene's colour, which reflections see too (tools/pov_finish.py)."""
    cam = scene["camera"]
    vfov = math.radians(cam.get("fov", 40.0))
    hfov = math.degrees(2 * math.atan(math.tan(vfov / 2) * width / height))
    bg = scene.get("background", [0, 0, 0])
    sky = None
    if isinstance(bg, dict):  # a gradient sky: POV's sky_sphere, opaque, over a black background
        sky, bg = bg, [0, 0, 0]
    level = scene.get("image", {}).get("max_trace_level", 5)
    out = ["#version 3.7;",
           "global_settings { assumed_gamma 1.0 ambient_light rgb 1 max_trace_level %d }" % level,
           ("background { rgbt <%g, %g, %g, 1> }" if alpha else
            "background { rgb <%g, %g, %g> }") % tuple(bg),
           "camera { perspective location %s look_at %s sky %s" % (
               pov_vec(cam["eye"]), pov_vec(cam["target"]), pov_vec(cam.get("up", [0, 0, 1]))),
           "  right x*%d/%d up y angle %.9g }" % (width, height, hfov)]
    if sky:
        up = sky.get("up", [0, 0, 1])
        n = math.sqrt(sum(c * c for c in up))
        up = [c / n for c in up]
        # The pattern's value at direction d is (d.up + 1) / 2: bottom straight down, top up.
        out.append("sky_sphere { pigment { gradient %s color_map { [0 rgb <%g, %g, %g>] "
                   "[1 rgb <%g, %g, %g>] } scale 2 translate -%s } }" % (
                       pov_vec(up), *sky["gradient"][0], *sky["gradient"][1], pov_vec(up)))
    ambient = 0.0
    for light in scene.get("lights", []):
        kind = light.get("type")
        power = [c * light.get("intensity", 1.0) for c in light.get("color", [1, 1, 1])]
        if kind == "ambient":
            ambient += light.get("intensity", 1.0)
            continue
        shadow = "" if light.get("shadows", True) else " shadowless"
        if kind == "directional":
            d = light["direction"]
            far = [-1e5 * c for c in d]
            out.append("light_source { %s rgb <%g, %g, %g> parallel point_at <0, 0, 0>%s }" % (
                pov_vec(far), *power, shadow))
            continue
        items = [pov_vec(light["position"]), "rgb <%g, %g, %g>" % tuple(power)]
        if kind == "spot":
            items.append("spotlight point_at %s radius %.9g falloff %.9g tightness %.9g" % (
                pov_vec(light["point_at"]), light.get("radius", 30), light.get("falloff", 45),
                light.get("tightness", 0)))
        if "fade_distance" in light:
            items.append("fade_distance %.9g fade_power %.9g" % (
                light["fade_distance"], light.get("fade_power", 2)))
        area = light.get("area")
        if area:
            items.append("area_light %s, %s, %d, %d" % (
                pov_vec(area["axis1"]), pov_vec(area["axis2"]), area["size1"], area["size2"]))
            if "adaptive" in area:
                items.append("adaptive %d" % area["adaptive"])
        out.append("light_source { %s%s }" % (" ".join(items), shadow))
    out.append("#declare Ambient = %g;" % ambient)
    return "\n".join(out) + "\n"


def grey_or_rgb(v):
    return ("rgb <%g, %g, %g>" % tuple(v)) if isinstance(v, list) else "%g" % v


def material(obj):
    """The material of `obj` (an object or a blend's component) as POV's pigment and finish: the keys are POV's, with softtrace's
    defaults (ambient 1, diffuse 1) written out; ambient scales the scene's ambient lights."""
    m = obj.get("material", {})
    c = m.get("color", [0.8, 0.8, 0.8])
    amb = m.get("ambient", 1.0)
    amb = amb if isinstance(amb, list) else [amb] * 3
    finish = ["ambient rgb <%g, %g, %g>*Ambient" % tuple(amb),
              "diffuse %g" % m.get("diffuse", 1.0),
              "brilliance %g" % m.get("brilliance", 1.0),
              "phong %g phong_size %g" % (m.get("phong", 0.0), m.get("phong_size", 40.0)),
              "specular %g roughness %g" % (m.get("specular", 0.0), m.get("roughness", 0.05))]
    if m.get("metallic", 0):
        finish.append("metallic %g" % m["metallic"])
    if m.get("reflection", 0):
        if m.get("fresnel"):  # the mirror reflection is the maximum
            finish.append("reflection { %s, %s fresnel on }" % (
                grey_or_rgb(m.get("reflection_min", 0.0)), grey_or_rgb(m["reflection"])))
        else:
            finish.append("reflection { %s }" % grey_or_rgb(m["reflection"]))
    if m.get("conserve_energy"):
        finish.append("conserve_energy")
    return "  pigment { rgbft <%g, %g, %g, %g, %g> } finish { %s }" % (
        *c, m.get("filter", 0.0), m.get("transmit", 0.0), " ".join(finish))


def interior(obj):
    """The object's interior (its ior), or nothing where its material keeps the default 1."""
    ior = obj.get("material", {}).get("ior", 1.0)
    return "  interior { ior %.9g }\n" % ior if ior != 1.0 else ""


def blob(scene):
    """The scene's first object as a POV blob; it must be a soft_blend of murakami spheres."""
    obj = scene["objects"][0]
    field = obj["field"]
    if field["type"] != "soft_blend":
        raise ValueError("a blob needs a soft_blend")
    lines = ["blob { threshold %.9g" % obj.get("iso", 0.5)]
    for child in field["children"]:
        dist = child["distance"]
        radii = dist["radii"]
        if (child["potential"]["type"] != "murakami" or dist["type"] != "lp_metric" or
                dist.get("n") != 2 or len(set(radii)) != 1):
            raise ValueError("a blob's children must be murakami spheres")
        # A component's own material is its texture (POV-Ray mixes them by field value).
        own = (" " + material(child).strip()) if "material" in child else ""
        lines.append("  sphere { %s, %.9g, 1%s }" % (pov_vec(child.get("translate", [0, 0, 0])),
                                                     radii[0], own))
    lines.append(material(obj))
    if interior(obj):
        lines.append(interior(obj).rstrip("\n"))
    lines.append("}")
    return "\n".join(lines) + "\n"


# Blanc's potential with s = 0 (docs/math.md §3.2): 1 - 2d^2 up to 0.5, (1-d^2)^2 / (0.75 + 1.5 d^2)
# up to 1, 0 beyond. POV's select(a, b, c) is b where a < 0, else c.
FIG12B_FUNCTIONS = """\
#declare Blanc = function(d) {
  select(d - 0.5, 1 - 2*d*d, select(d - 1, pow(1 - d*d, 2) / (0.75 + 1.5*d*d), 0)) }
// The bar: superquadric radii (8, 8, 24), n1 = 1, n2 = 20 (softtrace's z is POV's y).
#declare Bar = function(x, y, z) {
  pow(pow(abs(x/8) + abs(z/8), 20) + pow(abs(y/24), 20), 1/20) }
// The cube: lp_metric radii (30, 30, 12), n = 20.
#declare Cube = function(x, y, z) {
  pow(pow(abs(x/30), 20) + pow(abs(z/30), 20) + pow(abs(y/12), 20), 1/20) }
"""


def isosurface_fig12b(scene, max_gradient, accuracy):
    """scenes/fig000_12b_soft_blend.json's object: inside where Blanc(bar) + Blanc(cube) >= 0.5.

    POV's isosurface is inside where the function is below the threshold, so the function is
    0.5 - the blend and the threshold 0. The container is the blend's support box: the cube's
    (+-30, +-30, +-12) and the bar's (+-8, +-8, +-24) radii.
    """
    obj = scene["objects"][0]
    return FIG12B_FUNCTIONS + "\n".join([
        "isosurface {",
        "  function { 0.5 - Blanc(Bar(x, y, z)) - Blanc(Cube(x, y, z)) }",
        "  threshold 0",
        "  contained_by { box { %s, %s } }" % (pov_vec([-30, -30, -24]), pov_vec([30, 30, 24])),
        "  max_gradient %.9g" % max_gradient,
        "  accuracy %.9g" % accuracy,
        material(obj),
        "}"]) + "\n"


def write_text(text, path):
    """text to the file at path, or to standard output without one (the generators' -o)."""
    if path:
        with open(path, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


def write_scene(scene, output, pov, pov_object, width, height):
    """A generated softtrace scene as JSON (write_text's output), and with `pov` POV-Ray's
    version of it there: header() at width x height and pov_object(scene)."""
    if pov:
        write_text(header(scene, width, height) + pov_object(scene), pov)
    write_text(json.dumps(scene, indent=1) + "\n", output)
