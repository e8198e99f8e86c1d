"""Scenes and fields from Python: files and their errors, dicts and builders, settings copied on
write, pickling, the Jupyter picture, signatures, stubs and the docstrings' examples."""
import ast
import copy
import doctest
import inspect
import json
import os
import pickle
import struct
import subprocess
import sys

import numpy as np
import pytest
from conftest import BIN, SRC, TWO_BLOBS

import softtrace


def test_missing_files_and_nul_bytes_are_os_errors(tmp_path):
    with pytest.raises(FileNotFoundError):
        softtrace.load_scene(tmp_path / "missing.json")
    with pytest.raises(IsADirectoryError):
        softtrace.load_scene(tmp_path)
    with pytest.raises(ValueError, match="null byte"):
        softtrace.load_scene(TWO_BLOBS + "\0junk")
    assert softtrace.load_scene(TWO_BLOBS).objects == ["two_blobs"]  # a path-like works too


def test_endless_input_is_bounded_and_located():
    # /dev/zero never ends: the read stops at the first block with a NUL and the parser names it.
    with pytest.raises(softtrace.SceneError) as e:
        softtrace.load_scene("/dev/zero")
    assert str(e.value).startswith("/dev/zero:1:1")


def test_ill_formed_utf8_gives_the_cli_location(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_bytes(b'{"camera": {"eye": [0, 0, 1],\n "fo\xffv": 30}}')
    cli = subprocess.run([BIN, "render", str(bad)], capture_output=True)
    assert cli.returncode == 2
    with pytest.raises(softtrace.SceneError) as e:
        softtrace.load_scene(bad)
    assert (e.value.file, e.value.line, e.value.column) == (str(bad), 2, 5)
    assert cli.stderr.startswith(b"softtrace: %s:2:5: " % str(bad).encode())
    assert "\\xff" in str(e.value) and "ill-formed UTF-8" in e.value.message


def test_scene_error_attributes():
    text = open(TWO_BLOBS).read()
    with pytest.raises(softtrace.SceneError) as e:
        softtrace.parse_scene(text.replace('"n": 20', '"n": -20'), "mine")
    assert e.value.file == "mine" and e.value.line is None
    assert e.value.pointer == "/objects/0/field/children/0/distance/n"
    assert str(e.value) == "mine: %s: %s" % (e.value.pointer, e.value.message)
    with pytest.raises(softtrace.SceneError) as e:
        softtrace.parse_scene('{"camera": [', "broken")
    assert (e.value.file, e.value.line, e.value.column, e.value.pointer) == ("broken", 1, 13, None)
    assert isinstance(e.value, ValueError)


def two_blobs_with_builders():
    st = softtrace
    return {
        "camera": {"eye": [0, -150, 40], "target": np.array([10, 0, 0]), "fov": 40},
        "image": {"width": 64, "height": 48},
        "objects": [{"name": "two_blobs", "field": st.soft_blend([
            st.soft_object(st.lp_metric([30, 30, 12], 20), st.wyvill()),
            st.soft_object(st.lp_metric([10, 10, 10], 2), st.murakami(), translate=[25, 0, 0]),
        ])}]}


def test_dicts_and_builders_make_the_file_scene():
    scene = softtrace.load_dict(two_blobs_with_builders())
    from_file = softtrace.load_scene(TWO_BLOBS)
    points = np.random.default_rng(2).uniform(-40, 40, (500, 3))
    assert np.array_equal(softtrace.Field(scene).eval(points),
                          softtrace.Field(from_file).eval(points))
    assert np.array_equal(softtrace.render(scene)["rgba"], softtrace.render(from_file)["rgba"])
    assert softtrace.soft_blend([1, 2]) == {"type": "soft_blend", "children": [1, 2]}
    assert softtrace.ricci_union(4, []) == {"type": "ricci_union", "n": 4, "children": []}
    with pytest.raises(TypeError, match=r"lp_metric\(\) has no parameter 'radius'"):
        softtrace.lp_metric(radius=3)
    with pytest.raises(TypeError, match="got 'n' twice"):
        softtrace.lp_metric([1, 1, 1], 2, n=3)
    with pytest.raises(TypeError, match="has no parameter 'translate'"):
        softtrace.wyvill(translate=[1, 0, 0])  # potentials are not placed
    with pytest.raises(softtrace.SceneError, match=r"<dict>: /objects/0/field/children"):
        softtrace.load_dict({**two_blobs_with_builders(), "objects": [
            {"field": softtrace.soft_blend(3)}]})
    with pytest.raises(ValueError, match="no NaN or infinity"):
        softtrace.load_dict({**two_blobs_with_builders(), "background": [np.nan, 0, 0]})
    with pytest.raises(TypeError, match="not a scene value"):
        softtrace.load_dict({**two_blobs_with_builders(), "background": {1, 2, 3}})


def test_a_builder_per_kind_with_the_tables_parameters():
    for kind in softtrace.nodes():
        build = getattr(softtrace, kind["name"])
        params = [p["name"] for p in kind["params"]]
        assert list(inspect.signature(build).parameters)[:len(params)] == params
        assert kind["summary"] in build.__doc__
        node = build(**{p: 1 for p in params})
        assert node == {"type": kind["name"], **{p: 1 for p in params}}


def test_settings_are_checked_and_copied_on_write():
    scene = softtrace.load_scene(TWO_BLOBS)
    other = copy.copy(scene)
    camera = scene.camera
    assert camera == {"projection": "perspective", "eye": [0, -150, 40], "target": [10, 0, 0],
                      "up": [0, 0, 1], "fov": 40, "aperture": 0, "focal_distance": 0,
                      "blur_samples": 16}
    scene.camera = dict(camera, fov=30)
    assert scene.camera["fov"] == 30 and other.camera["fov"] == 40  # other keeps its own
    with pytest.raises(softtrace.SceneError) as e:
        scene.camera = dict(camera, fov=200)
    assert e.value.pointer == "/camera/fov"
    assert scene.camera["fov"] == 30  # a refused value changes nothing
    scene.camera = dict(camera, fov=30, aspect=1.33)  # kept only when given
    assert scene.camera["aspect"] == 1.33 and "aspect" not in other.camera
    scene.camera = dict(camera, fov=30)
    scene.width, scene.height, scene.spp = 20, 10, 2
    assert scene.image == {"width": 20, "height": 10, "spp": 2, "max_trace_level": 5}
    assert softtrace.render(scene)["rgba"].shape == (10, 20, 4)
    with pytest.raises(softtrace.SceneError, match="/image/width"):
        scene.width = 0
    assert scene.default_lights and len(scene.lights) == 2
    scene.lights = [{"type": "point", "position": [0, -100, 100], "intensity": 2}]
    assert not scene.default_lights
    assert scene.lights[0]["position"] == [0, -100, 100] and scene.lights[0]["shadows"]
    with pytest.raises(softtrace.SceneError, match=r"/lights/0/position"):
        scene.lights = [{"type": "point"}]
    scene.lights = None
    assert scene.default_lights
    scene.background = {"gradient": [[0.5, 0.4, 0.3], [0.1, 0.2, 0.9]]}
    assert scene.background == {"gradient": [[0.5, 0.4, 0.3], [0.1, 0.2, 0.9]], "up": [0, 0, 1]}
    scene.background = [0.1, 0.2, 0.3]
    assert scene.background == [0.1, 0.2, 0.3]
    assert json.loads(scene.text)["background"] == [0.1, 0.2, 0.3]
    assert other.background == [0, 0, 0] and other.image["width"] == 64


def test_scenes_and_fields_pickle_as_their_json():
    scene = softtrace.load_scene(TWO_BLOBS)
    scene.spp = 2
    again = pickle.loads(pickle.dumps(scene))
    assert isinstance(again, softtrace.Scene) and again.text == scene.text
    assert again.path == scene.path and again.hash == scene.hash
    assert np.array_equal(softtrace.render(again)["rgba"], softtrace.render(scene)["rgba"])
    points = np.random.default_rng(4).uniform(-40, 40, (100, 3))
    node = softtrace.soft_object(softtrace.lp_metric([20, 30, 40], 2), softtrace.wyvill())
    for field in (softtrace.Field(scene), softtrace.Field(node, name="mine")):
        back = pickle.loads(pickle.dumps(field))
        assert back.convention == field.convention
        assert np.array_equal(back.eval(points), field.eval(points))


def test_points_of_any_shape():
    field = softtrace.Field(softtrace.load_scene(TWO_BLOBS))
    points = np.random.default_rng(6).uniform(-40, 40, (4, 5, 6, 3))
    flat_v, flat_g = field.gradient(points.reshape(-1, 3))
    v, g = field.gradient(points)
    assert v.shape == (4, 5, 6) and g.shape == (4, 5, 6, 3)
    assert np.array_equal(v.reshape(-1), flat_v) and np.array_equal(g.reshape(-1, 3), flat_g)
    assert field.eval([20.0, 1.0, 2.0]).shape == ()
    assert field.eval(points[..., ::2, :]).shape == (4, 5, 3)  # a strided view is copied
    assert field.eval(np.zeros((0, 3))).shape == (0,)
    with pytest.raises(ValueError, match=r"shape \(\.\.\., 3\)"):
        field.eval(np.zeros((3, 2)))


def test_jupyter_picture_is_a_small_png():
    scene = softtrace.load_scene(os.path.join(SRC, "scenes", "fig000_12b_soft_blend.json"))
    png = scene._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = struct.unpack(">II", png[16:24])
    assert max(width, height) == 320 and abs(width / height - scene.width / scene.height) < 0.01


def public_callables():
    for name in softtrace.__all__:
        value = getattr(softtrace, name)
        if callable(value) and not isinstance(value, type):
            yield name, value
    for cls in (softtrace.Scene, softtrace.Field):
        for name, value in vars(cls).items():
            if callable(value) and (not name.startswith("_") or name == "__init__"):
                yield cls.__name__ + "." + name, value


def test_every_public_callable_has_a_signature_and_a_docstring():
    checked = 0
    for name, value in public_callables():
        inspect.signature(value)  # raises ValueError for a bare native function
        assert value.__doc__ and len(value.__doc__) > 20, name
        checked += 1
    assert checked > 40


def test_the_stub_lists_what_the_package_has():
    stub = ast.parse(open(os.path.join(os.path.dirname(softtrace.__file__),
                                       "__init__.pyi")).read())
    functions = {n.name: n for n in stub.body if isinstance(n, ast.FunctionDef)}
    classes = {n.name for n in stub.body if isinstance(n, ast.ClassDef)}
    exported = set(softtrace.__all__) - {"SceneError", "__version__"}
    assert exported | {"min", "max"} == set(functions) | classes
    assert "min" not in softtrace.__all__ and softtrace.min([])["type"] == "min"
    assert os.path.exists(os.path.join(os.path.dirname(softtrace.__file__), "py.typed"))
    for kind in softtrace.nodes():
        args = functions[kind["name"]].args
        assert [a.arg for a in args.args] == [p["name"] for p in kind["params"]]
    for name, build in softtrace._BUILDERS.items():  # the scene objects' builders too
        args = functions[name].args
        assert [a.arg for a in args.args + args.kwonlyargs] == list(
            inspect.signature(build).parameters), name
    for name in ("load_scene", "render", "write_exr", "Field"):
        value = getattr(softtrace, name)
        real = inspect.signature(value.__init__ if isinstance(value, type) else value)
        node = functions.get(name) or next(
            f for c in stub.body if isinstance(c, ast.ClassDef) and c.name == name
            for f in c.body if isinstance(f, ast.FunctionDef) and f.name == "__init__")
        stubbed = [a.arg for a in node.args.args + node.args.kwonlyargs]
        assert stubbed == list(real.parameters), name


def test_stubtest_finds_the_stubs_match_the_module(tmp_path):
    pytest.importorskip("mypy", reason="mypy (Debian's python3-mypy) checks the stubs")
    # pybind11 classes have their own metaclass, which stubs cannot spell.
    allow = tmp_path / "allow.txt"
    allow.write_text("".join("softtrace.%s\n" % c for c in
                             ("Scene", "Field", "_native.Scene", "_native.Field")))
    run = subprocess.run([sys.executable, "-m", "mypy.stubtest", "softtrace", "--allowlist",
                          str(allow)], capture_output=True, text=True,
                         cwd=os.path.dirname(os.path.dirname(softtrace.__file__)))
    assert run.returncode == 0, run.stdout + run.stderr


def test_the_docstring_examples_run():
    failed, attempted = doctest.testmod(softtrace, optionflags=doctest.ELLIPSIS)
    assert attempted > 8 and failed == 0


def keys_of(list_name):
    return next(keys for name, keys in softtrace._native.scene_keys() if name == list_name)


SHAPES_SCENE = os.path.join(SRC, "scenes", "shapes_blob_floor.json")


def test_settings_read_back_every_key_and_assign_back_unchanged():
    # A lens on an orthographic view, a reflection depth and every kind of light: each setting
    # reads as the file's keys, all of them, so `scene.x = dict(scene.x, ...)` keeps the others.
    scene = softtrace.load_scene(SHAPES_SCENE)
    scene.width, scene.height = 32, 24
    scene.camera = dict(scene.camera, projection="orthographic", aspect=1.5, aperture=0.5,
                        focal_distance=40, blur_samples=2)
    scene.max_trace_level = 3
    scene.image = dict(scene.image, antialias={"threshold": 0.3, "depth": 2},
                       ambient_occlusion={"samples": 2, "distance": 5})
    area = {"axis1": [4, 0, 0], "axis2": [0, 4, 0], "size1": 2, "size2": 2}
    scene.lights = [
        {"type": "directional", "direction": [-0.6, 1, -1.6], "intensity": 0.9},
        {"type": "point", "position": [10, -30, 40], "fade_distance": 30, "area": area},
        {"type": "spot", "position": [0, -20, 50], "point_at": [1, 2, 3], "radius": 17.3,
         "falloff": 29.1, "tightness": 2, "area": dict(area, jitter=True)},
        {"type": "ambient", "intensity": 0.2}]
    assert list(scene.camera) == keys_of("camera")
    assert scene.camera["projection"] == "orthographic" and scene.camera["blur_samples"] == 2
    assert list(scene.image) == keys_of("image") and scene.image["max_trace_level"] == 3
    for light in scene.lights:
        assert set(light) <= set(keys_of("light: " + light["type"])), light
    spot = scene.lights[2]
    assert (spot["point_at"], spot["radius"], spot["falloff"]) == ([1, 2, 3], 17.3, 29.1)
    assert spot["area"] == dict(area, jitter=True)
    before = softtrace.render(scene)["rgba"]
    same = copy.copy(scene)
    same.camera, same.image, same.lights = scene.camera, scene.image, scene.lights
    assert same.to_dict()["camera"] == scene.to_dict()["camera"]
    assert np.array_equal(softtrace.render(same)["rgba"], before)
    scene.camera = dict(scene.camera, fov=scene.camera["fov"] + 4)  # still a lens, orthographic
    wider = softtrace.render(scene)["rgba"]
    assert scene.camera["projection"] == "orthographic" and scene.camera["aperture"] == 0.5
    assert not np.array_equal(wider, before)
    with pytest.raises(softtrace.SceneError, match="/image/max_trace_level"):
        scene.max_trace_level = 0


def test_builders_of_shapes_materials_and_lights_make_the_file_scene():
    st = softtrace
    built = {  # scenes/shapes_blob_floor.json, smaller
        "camera": {"eye": [34, -46, 24], "target": [0, 0, 4], "fov": 32},
        "image": {"width": 40, "height": 30, "spp": 1},
        "background": [0.45, 0.55, 0.75],
        "lights": [st.directional_light([-0.6, 1, -1.6], intensity=0.9),
                   st.ambient_light(0.2)],
        "objects": [
            {"name": "floor", "material": st.material([0.62, 0.6, 0.55]),
             "shape": st.plane([0, 0, 1], 0)},
            {"name": "blob", "material": st.material([0.85, 0.45, 0.35]),
             "field": st.soft_blend([
                 st.soft_object(st.lp_metric([9, 9, 9], 2), translate=[0, 0, 5]),
                 st.soft_object(st.lp_metric([6, 6, 6], 2), translate=[5, 3, 9])])},
            {"name": "crate", "material": st.material(color=[0.75, 0.7, 0.35]),
             "shape": st.box([-3, -3, 0], [3, 3, 6], rotate={"axis": [0, 0, 1], "deg": 25},
                             translate=[-13, 4, 0])},
            {"name": "pillar", "material": st.material([0.45, 0.7, 0.5]),
             "shape": st.cylinder([0, 0, 0], [0, 0, 12], 1.8, translate=[9, 12, 0])},
            {"name": "ball", "material": st.material([0.35, 0.55, 0.85]),
             "shape": st.sphere([12, -6, 3], 3)}]}
    scene = st.load_dict(built)
    from_file = st.load_scene(SHAPES_SCENE)
    from_file.width, from_file.height = 40, 30
    from_file.spp = 1
    assert scene.lights == from_file.lights and scene.objects == from_file.objects
    assert np.array_equal(st.render(scene)["rgba"], st.render(from_file)["rgba"])
    # The others: the dicts the format writes, refused by the loader where it refuses them.
    assert st.spot_light([0, 0, 9], [0, 0, 0], area=st.area_light([1, 0, 0], [0, 1, 0], 2, 2)) == {
        "type": "spot", "position": [0, 0, 9], "point_at": [0, 0, 0],
        "area": {"axis1": [1, 0, 0], "axis2": [0, 1, 0], "size1": 2, "size2": 2}}
    assert st.cone([0, 0, 0], 2, [0, 0, 3], 1)["cap_radius"] == 1
    assert st.disc([0, 0, 0], [0, 0, 1], 2, hole_radius=1)["type"] == "disc"
    assert st.point_light([1, 2, 3], 0.5)["intensity"] == 0.5
    with pytest.raises(TypeError, match=r"sphere\(\) has no parameter 'potential'"):
        st.sphere([0, 0, 0], 1, potential=st.wyvill())
    with pytest.raises(TypeError, match=r"material\(\) has no parameter 'colour'"):
        st.material(colour=[1, 0, 0])
    with pytest.raises(softtrace.SceneError, match=r"/objects/0/shape/radius"):
        st.load_dict(dict(built, objects=[{"shape": st.sphere([0, 0, 0], -1)}]))


def test_a_builder_per_scene_object_with_its_keys():
    made = {}
    for name, keys in softtrace._native.scene_keys():
        group, _, kind = name.partition(": ")
        builder = {"shape": kind, "light": kind + "_light"}.get(group, name.replace(" ", "_"))
        if not hasattr(softtrace, builder):
            continue
        made[name] = builder
        build = getattr(softtrace, builder)
        own = [k for k in keys if k != "type"]
        assert sorted(inspect.signature(build).parameters) == sorted(own), name
        node = build(**{k: 1 for k in own})
        assert node == {**({"type": kind} if kind else {}), **{k: 1 for k in own}}
        assert "docs/scene-format.md" in build.__doc__
        runner = doctest.DocTestRunner()
        for test in doctest.DocTestFinder().find(build, builder, globs=vars(softtrace)):
            runner.run(test)
        assert runner.summarize(verbose=False) == (0, 1), builder
    # Written by hand in a scene: the top level, camera, image, object, animation, turntable.
    assert sorted(made) == sorted(n for n, _ in softtrace._native.scene_keys()
                                  if n.split(": ")[0] in ("shape", "light", "material",
                                                          "area light"))
    assert len(made) == 12 and not set(made.values()) & {k["name"] for k in softtrace.nodes()}


def test_a_scenes_field_is_its_first_field_object_as_eval_takes_it():
    scene = softtrace.load_scene(SHAPES_SCENE)  # its first object is the floor, a plane shape
    field = softtrace.Field(scene)
    cli = subprocess.run([BIN, "eval", SHAPES_SCENE], input="0 0 5\n", capture_output=True,
                         text=True, check=True)
    assert float(field.eval([0, 0, 5])) == float(cli.stdout.split()[0])
    assert field.name.endswith("/objects/1/field")
    with pytest.raises(softtrace.SceneError, match=r"/objects/0: a plane shape, not a field"):
        softtrace.Field(scene, "floor")
    shapes_only = softtrace.load_dict({"objects": [{"shape": softtrace.sphere([0, 0, 0], 1)}]})
    with pytest.raises(softtrace.SceneError, match="no object has a field"):
        softtrace.Field(shapes_only)
