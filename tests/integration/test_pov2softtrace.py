"""tools/pov2softtrace.py: POV-Ray 3.7 blob scenes as softtrace scenes.

The frame and transformation maths are checked on small scenes whose answer is worked out by
hand; the refusals by their located lines; and every scene of tools/pov_cases/ and POV-Ray's own
blob samples is converted, loaded by softtrace and, where POV-Ray is installed, rendered by both
with the silhouettes compared (IoU >= 0.999).
"""
import glob
import json
import math
import os
import shutil
import subprocess
import sys

import pytest

SOURCE = os.environ.get("SOFTTRACE_SOURCE_DIR", os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__)))))
TOOL = os.path.join(SOURCE, "tools", "pov2softtrace.py")
sys.path.insert(0, os.path.join(SOURCE, "tools"))
from povsdl.lexer import PovError  # noqa: E402
from povsdl.scene import convert, obj_text  # noqa: E402

CAMERA = "camera { location <0, 0, -10> look_at <0, 0, 0> angle 40 }\n"
POV_SAMPLES = sorted(glob.glob("/usr/share/povray-3.7/scenes/objects/blob*.pov"))
OUR_CASES = sorted(glob.glob(os.path.join(SOURCE, "tools", "pov_cases", "*.pov")))


def scene_of(body, camera=CAMERA):
    return convert("t.pov", camera + body, 320, 240)


def field_of(body):
    return scene_of(body)["objects"][0]["field"]


def close(a, b, tol=1e-9):
    return all(abs(x - y) <= tol for x, y in zip(a, b)) and len(a) == len(b)


def test_points_swap_y_and_z():
    f = field_of("blob { sphere { <1, 2, 3>, 1, 1 } pigment { rgb 1 } }")
    assert f["type"] == "soft_object"
    assert close(f["translate"], [1, 3, 2])
    assert f["distance"] == {"type": "lp_metric", "radii": [1, 1, 1], "n": 2}
    assert f["potential"] == {"type": "murakami"}
    assert "strength" not in f


def test_transformations_apply_in_the_order_written():
    # rotate 90 about x takes POV's (0, 0, 5) to (0, -5, 0): y' = y cos - z sin.
    first_rotate = field_of("blob { sphere { 0, 1, 1 rotate 90*x translate <0, 0, 5> } "
                            "pigment { rgb 1 } }")
    first_translate = field_of("blob { sphere { 0, 1, 1 translate <0, 0, 5> rotate 90*x } "
                               "pigment { rgb 1 } }")
    assert close(first_rotate["translate"], [0, 5, 0])
    assert close(first_translate["translate"], [0, 0, -5])


def test_whole_blob_transform_follows_the_components():
    f = field_of("blob { cylinder { <0, 0, 0>, <2, 0, 0>, 1, 1 } rotate 90*y scale 2 "
                 "translate <1, 0, 0> pigment { rgb 1 } }")
    d = f["distance"]
    # rotate 90 about y: (2, 0, 0) -> (0, 0, -2); scale 2 -> (0, 0, -4); translate -> (1, 0, -4).
    assert d["type"] == "segment"
    assert close(d["p0"], [1, 0, 0]) and close(d["p1"], [1, -4, 0])
    assert d["radius"] == pytest.approx(2)


def test_axis_scale_is_an_ellipsoid_with_swapped_radii():
    f = field_of("blob { sphere { 0, 1.5, 1 scale <1, 2, 3> } pigment { rgb 1 } }")
    assert close(f["distance"]["radii"], [1.5, 4.5, 3.0])
    assert "matrix" not in f and "rotate" not in f


def test_scale_after_rotate_is_a_matrix():
    f = field_of("blob { cylinder { <-1, 0, 0>, <1, 0, 0>, 0.5, 1 rotate 45*z scale <1, 3, 1> } "
                 "pigment { rgb 1 } }")
    m = f["matrix"]
    c = math.sqrt(0.5)
    # POV: scale(1,3,1) Rz(45) = [[c, -c, 0], [3c, 3c, 0], [0, 0, 1]]; swapping y and z in rows
    # and columns gives softtrace's linear part.
    assert close(m[0], [c, 0, -c, 0]) and close(m[1], [0, 1, 0, 0]) and close(m[2], [3 * c, 0, 3 * c, 0])
    assert close(f["distance"]["p0"], [-1, 0, 0]) and f["distance"]["radius"] == 0.5


def test_pov_matrix_is_row_vector_form():
    f = field_of("blob { sphere { 0, 1, 1 matrix <1, 0, 0, 0.5, 1, 0, 0, 0, 1, 3, 4, 5> } "
                 "pigment { rgb 1 } }")
    # POV: x' = x + 0.5 y + 3, y' = y + 4, z' = z + 5; in softtrace's frame (x, z, y).
    assert close(f["matrix"][0], [1, 0, 0.5, 3])
    assert close(f["matrix"][1], [0, 1, 0, 5])
    assert close(f["matrix"][2], [0, 0, 1, 4])


def test_strengths_threshold_and_the_old_component_form():
    obj = scene_of("blob { threshold 0.4 component 2, 1.5, <0, 0, 0> "
                   "sphere { <1, 0, 0>, 1, strength -0.5 } sphere { <2, 0, 0>, 1, 0 } "
                   "pigment { rgb 1 } }")["objects"][0]
    assert obj["iso"] == 0.4 and obj["convention"] == "soft"
    children = obj["field"]["children"]
    assert [c.get("strength", 1) for c in children] == [2, -0.5]  # strength 0 adds nothing
    assert children[0]["distance"]["radii"] == [1.5, 1.5, 1.5]


def test_camera_angle_is_horizontal_and_fov_vertical():
    cam = scene_of("blob { sphere { 0, 1, 1 } pigment { rgb 1 } }",
                   "camera { location <1, 2, -10> look_at <0, 1, 0> right x*4/3 angle 60 "
                   "sky <0, 1, 0> }\n")["camera"]
    assert close(cam["eye"], [1, -10, 2]) and close(cam["target"], [0, 0, 1])
    assert close(cam["up"], [0, 0, 1])
    assert cam["fov"] == pytest.approx(2 * math.degrees(math.atan(math.tan(math.radians(30)) * 0.75)))
    # Without angle: direction's length sets the field of view.
    cam = scene_of("blob { sphere { 0, 1, 1 } pigment { rgb 1 } }",
                   "camera { location <0, 0, -5> direction <0, 0, 1.7> look_at 0 }\n")["camera"]
    assert cam["fov"] == pytest.approx(2 * math.degrees(math.atan(0.5 / 1.7)))


def test_orthographic_and_focal_blur_cameras():
    body = "blob { sphere { 0, 1, 1 } pigment { rgb 1 } }"
    # Orthographic without angle: `up` tall in world units, the fov that gives that at look_at.
    cam = scene_of(body, "camera { orthographic location <0, 0, -10> look_at 0 right 8*x "
                   "up 6*y }\n")["camera"]
    assert cam["projection"] == "orthographic"
    assert 2 * 10 * math.tan(math.radians(cam["fov"]) / 2) == pytest.approx(6)
    # With angle: as tall as the perspective view at look_at, which is softtrace's own rule.
    cam = scene_of(body, "camera { orthographic location <0, 0, -10> look_at 0 right x*4/3 "
                   "angle 60 }\n")["camera"]
    assert cam["projection"] == "orthographic"
    assert cam["fov"] == pytest.approx(2 * math.degrees(math.atan(math.tan(math.radians(30)) * 0.75)))
    # Focal blur: POV-Ray's lens is aperture/2 across; in focus at focal_point's distance.
    cam = scene_of(body, "camera { location <0, 0, -10> look_at 0 right x*4/3 aperture 0.8 "
                   "focal_point <3, 0, 0> blur_samples 8, 40 confidence 0.95 variance 0 }\n")["camera"]
    assert cam["aperture"] == pytest.approx(0.4)
    assert cam["focal_distance"] == pytest.approx(math.sqrt(109))
    assert cam["blur_samples"] == 40 and "projection" not in cam


def test_lights_background_and_finish():
    sc = scene_of("#declare Warm = rgb <1, 0.9, 0.8>;\n"
                  "light_source { <0, 10, 0> color Warm }\n"
                  "light_source { <0, 10, -10> rgb 0.5 parallel point_at <0, 0, 0> shadowless }\n"
                  "background { color rgb <0.1, 0.2, 0.3> }\n"
                  "global_settings { assumed_gamma 1 ambient_light rgb 0.5 }\n"
                  "blob { sphere { 0, 1, 1 } pigment { rgb <1, 0, 0> } "
                  "finish { phong 0.7 diffuse 0.8 } }")
    point, parallel, ambient = sc["lights"]
    assert point == {"type": "point", "position": [0, 0, 10], "color": [1, 0.9, 0.8],
                     "shadows": True}
    assert parallel["type"] == "directional" and not parallel["shadows"]
    assert close(parallel["direction"], [0, 10, -10])
    assert ambient == {"type": "ambient", "color": [0.5, 0.5, 0.5]}
    assert sc["background"] == [0.1, 0.2, 0.3]
    # POV-Ray's defaults (ambient 0.1, diffuse 0.6) are written out: they differ from ours.
    assert sc["objects"][0]["material"] == {"color": [1, 0, 0], "ambient": 0.1, "diffuse": 0.8,
                                            "phong": 0.7}


def test_transparency_filter_transmit_ior_and_fresnel():
    # rgbft's filter and transmit, reflection { min, max fresnel on }, conserve_energy and the
    # interior's ior: POV-Ray's glass.
    glass = scene_of("blob { sphere { 0, 1, 1 } pigment { rgbft <0.9, 1, 0.95, 0.1, 0.8> }\n"
                     "  finish { reflection { 0.1, 1 fresnel on } conserve_energy phong 0.8 }\n"
                     "  interior { ior 1.5 caustics 0.5 } }")["objects"][0]["material"]
    assert glass == {"color": [0.9, 1, 0.95], "ambient": 0.1, "diffuse": 0.6, "phong": 0.8,
                     "reflection": 1, "fresnel": True, "reflection_min": 0.1,
                     "conserve_energy": True, "filter": 0.1, "transmit": 0.8, "ior": 1.5}
    # rgbf, rgbt and the filter/transmit words; one reflection value with fresnel is its maximum.
    rgbf = scene_of("sphere { 0, 1 pigment { rgbf <1, 0, 0, 0.6> } "
                    "finish { reflection { 0.5 fresnel } } }")["objects"][0]["material"]
    assert rgbf["filter"] == 0.6 and "transmit" not in rgbf
    assert rgbf["reflection"] == 0.5 and rgbf["fresnel"] and "reflection_min" not in rgbf
    rgbt = scene_of("box { 0, 1 pigment { rgbt <0, 1, 0, 0.4> } }")["objects"][0]["material"]
    assert rgbt["transmit"] == 0.4 and "filter" not in rgbt
    words = scene_of("sphere { 0, 1 pigment { color red 1 filter 0.25 transmit 0.5 } "
                     "finish { reflection { 0.3 fresnel off } } }")["objects"][0]["material"]
    assert words["filter"] == 0.25 and words["transmit"] == 0.5
    assert words["reflection"] == 0.3 and "fresnel" not in words
    # Opaque, without an interior: nothing new is written.
    plain = scene_of("sphere { 0, 1 pigment { rgb 1 } }")["objects"][0]["material"]
    assert set(plain) == {"color", "ambient", "diffuse"}


REFUSALS = [
    ("sphere { 0, 1 pigment { rgbft <1, 1, 1, 0.7, 0.7> } }", 2, 23, "filter + transmit <= 1"),
    ("sphere { 0, 1 pigment { rgb 1 } finish { reflection { 0.1, 0.9 } } }", 2, 42,
     "varies with the angle"),
    ("sphere { 0, 1 pigment { rgb 1 } finish { reflection { 1 falloff 2 } } }", 2, 57,
     "reflection { falloff }"),
    ("sphere { 0, 1 pigment { rgbt 0.5 } interior { ior 1.5 fade_distance 2 } }", 2, 55,
     "interior { fade_distance }"),
    ("sphere { 0, 1 pigment { rgbt 0.5 } interior { ior 0 } }", 2, 47, "ior 0"),
    ("#while (I < 3) sphere { 0, 1 } #end", 2, 1, "#while: loops are not supported"),
    ("blob { sphere { <rand(S), 0, 0>, 1, 1 } }", 2, 18, "unknown identifier 'rand'"),
    ("blob { sphere { 0, 1, 1 finish { phong 1 } } sphere { x, 1, 1 } pigment { rgb 1 } }", 2,
     25, "a component's texture needs a pigment"),
    ("global_settings { assumed_gamma 2.2 }", 2, 19, "only 1.0"),
    ("torus { 1, 0.2 }", 2, 1, "'torus' is not supported"),
    ("cylinder { 0, y, 1 open pigment { rgb 1 } }", 2, 20, "cylinder { open } is not supported"),
    ("blob { sphere { 0, 1, 1 } pigment { rgb 1 } inverse }", 2, 45, "blob { inverse }"),
    ("blob { sphere { 0, 1, -1 } pigment { rgb 1 } }", 2, 1, "no component of positive strength"),
    ("blob { sphere { 0, 1, 1 matrix <1,0,0, 0,0,0, 0,0,1, 0,0,0> } pigment { rgb 1 } }", 2, 25,
     "the matrix is singular"),
    ("blob { sphere { 0, 1, 1 scale <1, 0, 1> } pigment { rgb 1 } }", 2, 25, "scale by zero"),
    ("blob { threshold -1 sphere { 0, 1, 1 } pigment { rgb 1 } }", 2, 8, "must be positive"),
    ("/* never closed", 2, 1, "never closed"),
    ("blob { sphere { 0, 1, 1 } pigment { rgb 1 }", 2, 44, "the file ends inside blob { }"),
    ("union { sphere { 0, 1 } box { 0, 1 } translate x pigment { rgb 1 } }", 2, 38,
     "a transformation of a union is not supported"),
    ("merge { sphere { 0, 1 pigment { rgb 1 } } }", 2, 1, "softtrace needs at least two"),
    ("union { sphere { 0, 1 pigment { rgb 1 } } box { 0, 1 } }", 2, 1,
     "the union has no pigment"),
    ("union { sphere { 0, 1 pigment { rgb 1 } } box { 0, 1 } cutaway_textures }", 2, 56,
     "cutaway_textures can only be used with intersection and difference"),
    ("difference { sphere { 0, 1 pigment { rgb 1 } } box { 0, 1 } }", 2, 1,
     "the difference has no pigment"),
    ("difference { sphere { 0, 1 } disc { 0, y, 1 } pigment { rgb 1 } }", 2, 1,
     "a disc in a difference"),
    ("intersection { sphere { 0, 1 } box { 0, 1 finish { phong 1 } } pigment { rgb 1 } }", 2,
     32, "a finish but no pigment"),
    # sky_sphere: only what softtrace's vertical two-colour gradient expresses.
    ("sky_sphere { pigment { gradient x color_map { [0 rgb 0] [1 rgb 1] } } }", 2, 24,
     "only gradient y"),
    ("sky_sphere { pigment { gradient y color_map { [0 rgb 0] [1 rgb 1] } } }", 2, 14,
     "runs over [-1, 1] across the sky and POV-Ray wraps it"),
    ("sky_sphere { pigment { gradient y color_map { [0.2 rgb 0] [1 rgb 1] } scale 2 "
     "translate -y } }", 2, 14, "beyond the color_map's [0.2, 1]"),
    ("sky_sphere { pigment { gradient y color_map { [0 rgb 0] [0.5 rgb 1] [1 rgb 0] } } }", 2,
     35, "has 3 entries"),
    ("sky_sphere { pigment { gradient y color_map { [0 rgb 0] [1 rgb 1] } rotate 90*x } }", 2,
     69, "pigment { rotate } is not supported"),
    ("sky_sphere { pigment { rgb 1 } }", 2, 24, "pigment { rgb } is not supported"),
    ("sky_sphere { pigment { gradient y color_map { [0 rgb 0] [1 rgb 1] } scale 2 "
     "translate -y } pigment { rgb 1 } }", 2, 92, "sky_sphere { pigment } is not supported"),
    ("sky_sphere { pigment { gradient y color_map { [0 rgbt <0, 0, 0, 0.5>] [1 rgb 1] } } }", 2,
     50, "filter and transmit"),
    ("sky_sphere { }", 2, 1, "sky_sphere has no pigment"),
]


@pytest.mark.parametrize("body,line,col,phrase", REFUSALS)
def test_refusals_are_located(body, line, col, phrase):
    with pytest.raises(PovError) as e:
        scene_of(body)
    assert (e.value.line, e.value.col) == (line, col), e.value.message
    assert phrase in e.value.message


def test_component_textures_become_component_materials():
    # POV-Ray: a component's own texture replaces the blob's; the others keep the blob's.
    obj = scene_of("blob { sphere { 0, 1, 2 pigment { rgb <1, 0, 0> } finish { phong 0.5 } }\n"
                   "       sphere { x, 1, 1 texture { pigment { rgb 1 } } }\n"
                   "       sphere { -x, 1, 1 }\n"
                   "       pigment { rgb <0, 0, 1> } }")["objects"][0]
    red, white, plain = obj["field"]["children"]
    assert red["material"]["color"] == [1, 0, 0] and red["material"]["phong"] == 0.5
    assert white["material"]["color"] == [1, 1, 1] and "phong" not in white["material"]
    assert "material" not in plain and obj["material"]["color"] == [0, 0, 1]
    # Every component textured: the blob needs no pigment; a lone component's is the object's.
    both = scene_of("blob { sphere { 0, 1, 1 pigment { rgb 1 } } "
                    "sphere { x, 1, 1 pigment { rgb 0.5 } } }")["objects"][0]
    assert "material" not in both
    lone = scene_of("blob { sphere { 0, 1, 1 pigment { rgb <0, 1, 0> } } }")["objects"][0]
    assert lone["material"]["color"] == [0, 1, 0] and "material" not in lone["field"]


def test_plain_shapes():
    objs = scene_of("plane { y, -1 pigment { rgb 0.5 } }\n"
                    "box { <0, 0, 0>, <1, 2, 3> rotate 90*y pigment { rgb 1 } }\n"
                    "cone { 0, 1, <0, 2, 0>, 0 translate <1, 2, 3> pigment { rgb 1 } }\n"
                    "disc { <0, 1, 0>, y, 2, 0.5 pigment { rgb 1 } finish { phong 1 } }")["objects"]
    plane, box, cone, disc = (o["shape"] for o in objs)
    assert plane == {"type": "plane", "normal": [0, 0, 1], "distance": -1}
    assert box["corner2"] == [1, 3, 2] and len(box["matrix"]) == 3
    # rotate 90 about y takes POV's x to -z: softtrace's x to -y.
    assert close([row[0] for row in box["matrix"]], [0, -1, 0])
    assert cone == {"type": "cone", "base": [0, 0, 0], "base_radius": 1, "cap": [0, 0, 2],
                    "cap_radius": 0, "translate": [1, 3, 2]}
    assert disc["hole_radius"] == 0.5 and disc["normal"] == [0, 0, 1]
    assert objs[3]["material"]["phong"] == 1 and objs[0]["name"] == "plane1"


def test_csg_nests_blobs_and_shapes_and_passes_its_pigment_on():
    objs = scene_of("difference {\n"
                    "  blob { sphere { 0, 2, 1 } pigment { rgb <1, 0, 0> } }\n"
                    "  intersection { box { -1, 1 } sphere { 0, 1.2 } }\n"
                    "  pigment { rgb <0, 0, 1> } }\n"
                    "merge { sphere { 0, 1 pigment { rgb 1 } } box { 0, 1 pigment { rgb 1 } } }"
                    )["objects"]
    cut, merged = objs
    assert cut["csg"] == "difference" and cut["name"] == "difference1"
    blob, inner = cut["operands"]
    assert blob["material"]["color"] == [1, 0, 0] and "field" in blob
    assert inner["csg"] == "intersection" and "material" not in inner
    assert [o["shape"]["type"] for o in inner["operands"]] == ["box", "sphere"]
    assert all("material" not in o for o in inner["operands"])  # they take the difference's
    assert cut["material"]["color"] == [0, 0, 1]
    # Every part has its own pigment: the merge needs none.
    assert merged["csg"] == "merge" and "material" not in merged


def test_cutaway_textures_is_carried_across_and_needs_no_pigment_of_the_csg():
    objs = scene_of("difference {\n"
                    "  blob { sphere { 0, 2, 1 } pigment { rgb <1, 0, 0> } }\n"
                    "  box { <0, -3, -3>, <3, 3, 3> }\n"
                    "  cutaway_textures }")["objects"]
    cut, = objs
    assert cut["csg"] == "difference" and cut["cutaway_textures"] is True
    assert "material" not in cut  # the box shows the blob's red: softtrace's loader finds it
    blob, box = cut["operands"]
    assert blob["material"]["color"] == [1, 0, 0] and "material" not in box
    # Without the keyword the difference carries none.
    plain = scene_of("difference { sphere { 0, 1 } box { 0, 1 } pigment { rgb 1 } }")
    assert "cutaway_textures" not in plain["objects"][0]


def test_camera_refusals_are_located():
    body = "blob { sphere { 0, 1, 1 } pigment { rgb 1 } }"
    for camera, col, phrase in [
            ("camera { orthographic location <0, 0, -10> look_at 0 aperture 1 }", 1,
             "focal blur with an orthographic camera"),
            ("camera { location <0, 0, -10> look_at 0 aperture -1 }", 41, "must be >= 0"),
            ("camera { location <0, 0, -10> look_at 0 blur_samples 2.5 }", 41,
             "must be a whole number")]:
        with pytest.raises(PovError) as e:
            scene_of(body, camera + "\n")
        assert (e.value.line, e.value.col) == (1, col), e.value.message
        assert phrase in e.value.message


def test_meshes_become_obj_triangles():
    meshes = []
    sc = convert("t.pov", CAMERA + """
        mesh { triangle { <0, 0, 0>, <1, 0, 0>, <0, 1, 0> }
               triangle { <1, 0, 0>, <0, 1, 0>, <0, 0, 2> } pigment { rgb 1 } translate x }
        mesh2 { vertex_vectors { 3, <0, 0, 0>, <1, 0, 0>, <0, 1, 0> }
                normal_vectors { 3, <0, 0, -1>, <0, 0, -1>, <0, 1, 0> }
                face_indices { 1, <0, 1, 2> } pigment { rgb 1 } }""", 320, 240, meshes)
    a, b = sc["objects"]
    assert a["mesh"] == 0 and b["mesh"] == 1 and a["name"] == "mesh1"
    assert a["matrix"] == [[1, 0, 0, 1], [0, 1, 0, 0], [0, 0, 1, 0]]
    # Shared corners are one vertex; y and z swap (softtrace is z-up).
    assert meshes[0]["positions"] == [(0, 0, 0), (1, 0, 0), (0, 0, 1), (0, 2, 0)]
    assert meshes[0]["faces"] == [[0, 1, 2], [1, 2, 3]] and meshes[0]["normals"] == []
    # mesh2's normal_vectors without normal_indices go with the vertices: smooth.
    assert meshes[1]["face_normals"] == [[0, 1, 2]]
    assert meshes[1]["normals"][2] == (0, 0, 1)
    assert obj_text(meshes[1]).splitlines()[1:] == [
        "v 0 0 0", "v 1 0 0", "v 0 0 1", "vn 0 -1 0", "vn 0 -1 0", "vn 0 0 1", "f 1//1 2//2 3//3"]


MESH_REFUSALS = [
    ("union { sphere { 0, 1 } mesh { triangle { 0, x, y } } pigment { rgb 1 } }", 1, 25,
     "a mesh in a CSG needs inside_vector"),
    ("mesh { triangle { 0, x, y texture { pigment { rgb 1 } } } }", 1, 27,
     "a triangle's own texture"),
    ("mesh2 { vertex_vectors { 1, 0 } face_indices { 1, <0, 1, 2> } }", 1, 1,
     "names a vertex beyond the 1 of vertex_vectors"),
    ("mesh2 { vertex_vectors { 3, 0, x, y } uv_vectors { 1, <0, 0> } }", 1, 39,
     "mesh2 { uv_vectors } is not supported"),
    ("mesh { }", 1, 1, "mesh: no triangles"),
]


@pytest.mark.parametrize("body,line,col,phrase", MESH_REFUSALS)
def test_mesh_refusals_are_located(body, line, col, phrase):
    with pytest.raises(PovError) as e:
        convert("t.pov", CAMERA + body, 320, 240)
    assert (e.value.line - 1, e.value.col) == (line, col), e.value.message
    assert phrase in e.value.message


def test_meshes_are_written_beside_the_output(tmp_path):
    pov = tmp_path / "m.pov"
    pov.write_text(CAMERA + "mesh { triangle { 0, x, y } pigment { rgb 1 } }\n")
    p = run_tool(str(pov))  # to standard output: there is nowhere to put the OBJ file
    assert p.returncode == 2 and "give -o" in p.stderr
    p = run_tool(str(pov), "-o", str(tmp_path / "out.json"))
    assert p.returncode == 0, p.stderr
    assert '"mesh": "out_mesh1.obj"' in (tmp_path / "out.json").read_text()
    assert (tmp_path / "out_mesh1.obj").read_text().count("\nf ") == 1


def test_no_camera_is_refused():
    with pytest.raises(PovError, match="no camera"):
        convert("t.pov", "blob { sphere { 0, 1, 1 } pigment { rgb 1 } }", 320, 240)


def run_tool(*args):
    return subprocess.run(["/usr/bin/python3", TOOL] + list(args), capture_output=True,
                          text=True)


def test_command_line_refusal_keeps_the_existing_output(tmp_path):
    bad = tmp_path / "bad.pov"
    bad.write_text(CAMERA + "blob {\n  sphere { 0, 1, 1 }\n  torus { 1, 0.2 }\n}\n")
    out = tmp_path / "scene.json"
    out.write_text("precious")
    p = run_tool(str(bad), "-o", str(out))
    assert p.returncode == 2
    assert p.stderr.strip() == "%s:4:3: blob { torus } is not supported" % bad
    assert out.read_text() == "precious"
    assert not [f for f in os.listdir(tmp_path) if f.startswith(".pov2softtrace")]


def softtrace():
    exe = os.environ.get("SOFTTRACE_BIN")
    if not exe or not os.access(exe, os.X_OK):
        pytest.skip("SOFTTRACE_BIN is not set (run through CTest)")
    return exe


@pytest.mark.parametrize("pov", OUR_CASES + POV_SAMPLES, ids=os.path.basename)
def test_scene_converts_and_softtrace_loads_it(pov, tmp_path):
    exe = softtrace()
    out = tmp_path / "scene.json"
    p = run_tool(pov, "-o", str(out), "--width", "40", "--height", "30")
    assert p.returncode == 0, p.stderr
    r = subprocess.run([exe, "render", str(out), "-o", str(tmp_path / "x.png"), "--quiet"],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


def coverage(png):
    from PIL import Image
    return [a >= 128 for a in Image.open(png).convert("RGBA").getchannel("A").getdata()]


@pytest.mark.parametrize("pov", OUR_CASES + POV_SAMPLES, ids=os.path.basename)
def test_silhouette_matches_povray(pov, tmp_path):
    exe = softtrace()
    if not shutil.which("povray"):
        pytest.skip("POV-Ray is not installed")
    pytest.importorskip("PIL")
    w, h = 160, 120
    out = tmp_path / "scene.json"
    assert run_tool(pov, "-o", str(out), "--width", str(w), "--height", str(h)).returncode == 0
    subprocess.run([exe, "render", str(out), "-o", str(tmp_path / "st.png"), "--png-alpha",
                    "--quiet"], check=True)
    # POV-Ray's alpha is the coverage only where the background is transparent.
    copy = tmp_path / os.path.basename(pov)
    copy.write_text(open(pov).read() + "\nbackground { rgbt <0, 0, 0, 1> }\n")
    subprocess.run(["povray", "+I" + str(copy), "+O" + str(tmp_path / "pov.png"), "+W%d" % w,
                    "+H%d" % h, "+UA", "-D", "-A", "+FN8", "-V", "-GA", "+L" + os.path.dirname(pov)],
                   check=True, cwd=tmp_path, capture_output=True)
    a, b = coverage(tmp_path / "st.png"), coverage(tmp_path / "pov.png")
    both = sum(1 for x, y in zip(a, b) if x and y)
    either = sum(1 for x, y in zip(a, b) if x or y)
    assert either > 0.01 * w * h, "nothing drawn"
    assert both / either >= 0.999, "IoU %.5f" % (both / either)
    # The colours, linear RGB over the whole frame (both backgrounds transparent black):
    # POV-Ray's finish and lights carried across (docs/pov.md). Mean <= 1/255, and off the
    # edges (pixels whose 3x3 neighbourhood in POV-Ray's picture spans more than 16/255:
    # silhouettes and shadow edges, where a sub-pixel shift shows) 99% within 4/255.
    diffs, edges = colour_differences(tmp_path / "st.png", tmp_path / "pov.png", w)
    mean = sum(diffs) / len(diffs)
    smooth = sorted(d for d, e in zip(diffs, edges) if not e)
    p99 = smooth[int(0.99 * (len(smooth) - 1))]
    assert mean <= 1 / 255 and p99 <= 4 / 255, "mean %.2f/255, 99%% off edges %.2f/255" % (
        mean * 255, p99 * 255)


def colour_differences(ours, theirs, width):
    """Per pixel: the largest difference of premultiplied linear RGB, and whether the pixel is on
    an edge of `theirs` (its 3x3 neighbourhood spans more than 16/255 in some channel)."""
    from PIL import Image

    def linear(c):
        c /= 255
        return c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4

    def premultiplied(px):
        return [linear(px[i]) * px[3] / 255 for i in range(3)]

    a = [premultiplied(px) for px in Image.open(ours).convert("RGBA").getdata()]
    b = [premultiplied(px) for px in Image.open(theirs).convert("RGBA").getdata()]
    diffs = [max(abs(p - q) for p, q in zip(x, y)) for x, y in zip(a, b)]
    height = len(b) // width
    edges = []
    for k in range(len(b)):
        i, j = k % width, k // width
        near = [b[jj * width + ii] for jj in range(max(0, j - 1), min(height, j + 2))
                for ii in range(max(0, i - 1), min(width, i + 2))]
        edges.append(any(max(px[c] for px in near) - min(px[c] for px in near) > 16 / 255
                         for c in range(3)))
    return diffs, edges


def test_a_stretched_camera_keeps_povrays_aspect():
    # POV-Ray's default right, 1.33, on a 4:3 image stretches the picture 0.25 % across: up to
    # a fifth of a pixel at old_syntax.pov's sides at 320x240, where square pixels lost IoU 0.003.
    body = "blob { sphere { 0, 1, 1 } pigment { rgb 1 } }"
    cam = convert("t.pov", "camera { location -6*z direction 1.5*z look_at 0 }\n" + body,
                  320, 240)["camera"]
    assert cam["aspect"] == pytest.approx(1.33)
    assert cam["fov"] == pytest.approx(2 * math.degrees(math.atan(0.5 / 1.5)))  # up's height
    cam = convert("t.pov", "camera { location -6*z up 2*y right 5*x look_at 0 }\n" + body,
                  320, 240)["camera"]
    assert cam["aspect"] == pytest.approx(2.5) and cam["fov"] == pytest.approx(90)
    for right in ("x*image_width/image_height", "x*4/3"):
        cam = convert("t.pov", "camera { location -6*z right %s look_at 0 }\n" % right + body,
                      320, 240)["camera"]
        assert "aspect" not in cam


def test_spot_area_and_fading_lights():
    lights = scene_of("light_source { <0, 10, 0> rgb 1 spotlight point_at <0, 0, 2> radius 10 "
                      "falloff 20 tightness 5 fade_distance 4 fade_power 1 }\n"
                      "light_source { <1, 2, 3> rgb 1 area_light <2, 0, 0>, <0, 0, 2>, 4, 3 "
                      "adaptive 1 jitter translate <0, 1, 0> }\n"
                      "blob { sphere { 0, 1, 1 } pigment { rgb 1 } }")["lights"]
    spot, area = lights[0], lights[1]
    assert spot["type"] == "spot" and close(spot["point_at"], [0, 2, 0])
    assert (spot["radius"], spot["falloff"], spot["tightness"]) == (10, 20, 5)
    assert (spot["fade_distance"], spot["fade_power"]) == (4, 1)
    assert area["type"] == "point" and close(area["position"], [1, 3, 3])
    assert area["area"] == {"axis1": [2, 0, 0], "axis2": [0, 2, 0], "size1": 4, "size2": 3,
                            "adaptive": 1, "jitter": True}
    with pytest.raises(PovError, match="circular"):
        scene_of("light_source { 0, 1 area_light x, y, 2, 2 circular }")


def test_sky_sphere_becomes_the_gradient_background():
    # The exact case: the pattern's value (1 + d.y) / 2 runs from 0 straight down to 1 straight
    # up, softtrace's t; the colours are the color_map's.
    sky = ("sky_sphere { pigment { gradient y color_map { [0 color rgb <0.3, 0.2, 0.1>] "
           "[1 color rgb <0.1, 0.3, 0.9>] } scale 2 translate -y } }\n"
           "background { rgb 1 }\nblob { sphere { 0, 1, 1 } pigment { rgb 1 } }")
    bottom, top = scene_of(sky)["background"]["gradient"]
    assert close(bottom, [0.3, 0.2, 0.1]) and close(top, [0.1, 0.3, 0.9])
    # Translated first, then scaled by a half: the pattern's value is 2 d.y + 1, which runs
    # over [-1, 3] and wraps, whatever the map.
    other = ("sky_sphere { pigment { gradient y color_map { [-3 rgb 0] [5 rgb 1] } "
             "translate -y scale 0.5 } }\nblob { sphere { 0, 1, 1 } pigment { rgb 1 } }")
    with pytest.raises(PovError, match="wraps it"):
        scene_of(other)
    quarter = ("sky_sphere { pigment { gradient y color_map { [-0.5 rgb 0] [1.5 rgb 1] } "
               "scale 4 translate -2*y } }\nblob { sphere { 0, 1, 1 } pigment { rgb 1 } }")
    bottom, top = scene_of(quarter)["background"]["gradient"]
    # value (d.y + 2) / 4: 0.25 straight down, 0.75 straight up, inside the map's [-0.5, 1.5],
    # so the map's colours three eighths and five eighths of the way.
    assert close(bottom, [0.375] * 3) and close(top, [0.625] * 3)


def test_antialias_options_become_the_image_antialias(tmp_path):
    scene = tmp_path / "s.pov"
    scene.write_text(CAMERA.replace("angle 40", "angle 40 right x*4/3") +
                     "blob { sphere { 0, 1, 1 } pigment { rgb 1 } }\n")
    out = tmp_path / "s.json"
    p = run_tool(str(scene), "-o", str(out), "--antialias", "0.2", "--antialias-depth", "4")
    assert p.returncode == 0, p.stderr
    text = out.read_text()
    image = json.loads(text[text.index("{"):])["image"]
    assert image["antialias"] == {"threshold": 0.2, "depth": 4}
    p = run_tool(str(scene), "-o", str(out), "--antialias", "0.2", "--antialias-gamma", "2.2")
    assert p.returncode == 0, p.stderr
    text = out.read_text()
    image = json.loads(text[text.index("{"):])["image"]
    assert image["antialias"] == {"threshold": 0.2, "depth": 3, "gamma": 2.2}
    p = run_tool(str(scene), "-o", str(out))
    assert p.returncode == 0, p.stderr
    text = out.read_text()
    assert "antialias" not in json.loads(text[text.index("{"):])["image"]
    for bad in (["--antialias", "-1"], ["--antialias-depth", "10"], ["--antialias-depth", "0"],
                ["--antialias", "0.3", "--antialias-gamma", "0"], ["--antialias-gamma", "2.2"]):
        p = run_tool(str(scene), "-o", str(tmp_path / "never.json"), *bad)
        assert p.returncode == 2 and p.stderr.count("\n") == 1, (bad, p.stderr)
        assert not (tmp_path / "never.json").exists()


def test_sky_and_antialias_render_in_softtrace(tmp_path):
    exe = softtrace()
    scene = tmp_path / "s.pov"
    scene.write_text(CAMERA.replace("angle 40", "angle 40 right x*4/3") +
                     "sky_sphere { pigment { gradient y color_map { [0 rgb <0.3, 0.2, 0.1>] "
                     "[1 rgb <0.1, 0.3, 0.9>] } scale 2 translate -y } }\n"
                     "blob { sphere { 0, 1, 1 } pigment { rgb 1 } }\n")
    out = tmp_path / "s.json"
    p = run_tool(str(scene), "-o", str(out), "--width", "40", "--height", "30",
                 "--antialias", "0.3")
    assert p.returncode == 0, p.stderr
    r = subprocess.run([exe, "render", str(out), "-q", "-o", str(tmp_path / "s.exr")],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
