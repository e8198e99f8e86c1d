"""The Python module against the command line: same values, same errors, batched speed."""
import json
import os
import subprocess
import time

import numpy as np
import pytest
from conftest import BIN, TWO_BLOBS

import softtrace


def cli_eval(scene, points):
    text = "".join("%.17g %.17g %.17g\n" % tuple(p) for p in points)
    out = subprocess.run([BIN, "eval", scene], input=text, capture_output=True, text=True,
                         check=True).stdout
    rows = np.array([[float(v) for v in line.split()] for line in out.splitlines()])
    return rows[:, 0], rows[:, 1:]


def test_values_and_gradients_match_softtrace_eval(blob_scene):
    field = softtrace.Field(softtrace.load_scene(blob_scene))
    rng = np.random.default_rng(3)
    points = rng.uniform(-25, 25, size=(2000, 3))
    want_v, want_g = cli_eval(blob_scene, points)
    values = field.eval(points)
    v, g = field.gradient(points)
    assert values.shape == (2000,) and g.shape == (2000, 3)
    assert np.count_nonzero(want_v) > 500  # the points meet the blobs
    assert np.max(np.abs(values - want_v)) <= 1e-12
    assert np.max(np.abs(v - want_v)) <= 1e-12
    assert np.max(np.abs(g - want_g)) <= 1e-12


def test_field_from_json_text():
    scene = json.load(open(TWO_BLOBS))
    field = softtrace.Field(json.dumps(scene["objects"][0]["field"]))
    from_scene = softtrace.Field(softtrace.load_scene(TWO_BLOBS), "two_blobs")
    points = np.array([[20.0, 1.0, 2.0], [0.0, 0.0, 0.0], [40.0, 0.0, 0.0]])
    assert np.array_equal(field.eval(points), from_scene.eval(points))
    assert field.eval(points)[0] == cli_eval(TWO_BLOBS, points[:1])[0][0]


def test_errors_carry_the_located_message(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text(open(TWO_BLOBS).read().replace('"radii": [10, 10, 10]', '"radii": [10, -1, 10]'))
    cli = subprocess.run([BIN, "eval", str(bad)], input="", capture_output=True, text=True)
    assert cli.returncode == 2
    with pytest.raises(softtrace.SceneError) as e:
        softtrace.load_scene(str(bad))
    assert cli.stderr.strip() == "softtrace: " + str(e.value)
    assert "/objects/0/field/children/1/distance/radii/1" in str(e.value)
    with pytest.raises(ValueError, match=r"<field>:1:\d+: "):
        softtrace.Field('{"type": "soft_blend", ')
    with pytest.raises(softtrace.SceneError, match=r"<field>: /children: "):
        softtrace.Field('{"type": "soft_blend", "children": 3}')
    with pytest.raises(softtrace.SceneError, match="no object named 'nope'"):
        softtrace.Field(softtrace.load_scene(TWO_BLOBS), "nope")
    field = softtrace.Field(softtrace.load_scene(TWO_BLOBS))
    with pytest.raises(ValueError, match=r"shape \(\.\.\., 3\)"):
        field.eval(np.zeros((4, 2)))
    with pytest.raises(ValueError, match="point 1: expected three finite coordinates"):
        field.eval(np.array([[0.0, 0, 0], [np.nan, 0, 0]]))


def test_batch_is_much_faster_than_a_loop(blob_scene):
    field = softtrace.Field(softtrace.load_scene(blob_scene))
    rng = np.random.default_rng(5)
    points = rng.uniform(-25, 25, size=(1_000_000, 3))
    start = time.perf_counter()
    values = field.eval(points)
    batch = time.perf_counter() - start
    sample = points[:5000]
    start = time.perf_counter()
    single = [field.eval(p.reshape(1, 3))[0] for p in sample]
    loop = (time.perf_counter() - start) * len(points) / len(sample)
    assert np.array_equal(np.array(single), values[:5000])
    print("\n10^6 points of 1000 blobs: batch %.3f s, Python loop over single points %.1f s "
          "(extrapolated from %d), %.0fx" % (batch, loop, len(sample), loop / batch))


def test_render_matches_the_image_size():
    scene = softtrace.load_scene(TWO_BLOBS)
    image = softtrace.render(scene, width=32, height=24)["rgba"]
    assert image.shape == (24, 32, 4) and image.dtype == np.float32
    assert 0 < image[..., 3].mean() < 1  # some coverage, some background
    assert np.all(image[..., :3] <= image[..., 3:] + 1e-6)  # premultiplied
    assert softtrace.render(scene)["rgba"].shape == (scene.height, scene.width, 4)
    with pytest.raises(ValueError):
        softtrace.render(scene, width=-3)


def test_render_writes_the_files_the_cli_writes(tmp_path):
    scene = softtrace.load_scene(TWO_BLOBS)
    exr, png = str(tmp_path / "py.exr"), str(tmp_path / "py.png")
    image = softtrace.render(scene, width=32, height=24, outputs=[exr, png])["rgba"]
    assert image.shape == (24, 32, 4)
    cli = str(tmp_path / "cli.exr")
    subprocess.run([BIN, "render", TWO_BLOBS, "--width", "32", "--height", "24", "-o", cli,
                    "--quiet"], check=True)
    # Same pixels as the command line's render (exit 0: no pixel differs beyond 0).
    diff = subprocess.run([BIN, "diff", exr, cli, "-fail", "0"], capture_output=True, text=True)
    assert diff.returncode == 0, diff.stdout + diff.stderr
    assert os.path.getsize(png) > 0
    with pytest.raises(ValueError):  # a bad output is refused before rendering, nothing written
        softtrace.render(scene, width=8, height=8, outputs=[str(tmp_path / "x.tif")])
    assert not os.path.exists(tmp_path / "x.tif")


def test_nodes_lists_every_kind():
    kinds = softtrace.nodes()
    names = {k["name"] for k in kinds}
    assert {"soft_blend", "lp_metric", "murakami", "T_n"} <= names
    cli = subprocess.run([BIN, "nodes"], capture_output=True, text=True, check=True).stdout
    for name in names:
        assert name in cli
    lp = next(k for k in kinds if k["name"] == "lp_metric")
    assert [p["name"] for p in lp["params"]] == ["radii", "n"]
