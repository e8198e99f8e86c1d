"""softtrace.mesh and softtrace.write_mesh against the command line and the mesher's promises."""
import os
import struct
import subprocess

import numpy as np
import pytest

import softtrace

BIN = os.environ["SOFTTRACE_BIN"]
SRC = os.environ["SOFTTRACE_SOURCE_DIR"]
FIG12B = os.path.join(SRC, "scenes", "fig000_12b_soft_blend.json")


def edge_counts(faces):
    """Each directed edge must appear once and its reverse once (closed, manifold, oriented)."""
    directed = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    keys = directed[:, 0] * (faces.max() + 1) + directed[:, 1]
    reverse = directed[:, 1] * (faces.max() + 1) + directed[:, 0]
    return len(np.unique(keys)), len(keys), np.isin(reverse, keys).all()


def test_mesh_is_closed_oriented_and_on_the_surface():
    scene = softtrace.load_scene(FIG12B)
    v, f, n, c = softtrace.mesh(scene, cells=48)
    assert v.shape[1] == 3 and f.shape[1] == 3 and n.shape == v.shape and c.shape == v.shape
    assert f.dtype == np.int64 and len(f) > 0
    unique, total, closed = edge_counts(f)
    assert unique == total and closed
    np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1, atol=1e-12)
    a, b, d = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    assert np.einsum("ij,ij->i", a, np.cross(b, d)).sum() > 0  # outward: positive volume
    field = softtrace.Field(scene)
    values, grads = field.gradient(v)
    voxel = (v.max(0) - v.min(0)).max() / 48
    assert np.max(np.abs(values - 0.5) / np.linalg.norm(grads, axis=1)) < 1e-3 * voxel


def test_path_and_scene_give_the_same_mesh():
    v1, f1, _, _ = softtrace.mesh(FIG12B, object=None, cells=24, threads=1)
    v2, f2, _, _ = softtrace.mesh(softtrace.load_scene(FIG12B), cells=24, threads=2)
    assert np.array_equal(v1, v2) and np.array_equal(f1, f2)


def test_write_mesh_matches_the_command_line(tmp_path):
    v, f, n, c = softtrace.mesh(FIG12B, cells=24)
    ours = tmp_path / "py.stl"
    softtrace.write_mesh(str(ours), v, f, n, c)
    cli = tmp_path / "cli.stl"
    subprocess.run([BIN, "mesh", FIG12B, "-o", str(cli), "--cells", "24", "-q"], check=True)
    assert ours.read_bytes() == cli.read_bytes()
    data = ours.read_bytes()
    assert struct.unpack_from("<I", data, 80)[0] == len(f)
    assert len(data) == 84 + 50 * len(f)


def test_write_mesh_fills_normals_and_refuses_bad_arrays(tmp_path):
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    f = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
    out = tmp_path / "tet.obj"
    softtrace.write_mesh(str(out), v, f)
    lines = out.read_text().splitlines()
    assert sum(line.startswith("v ") for line in lines) == 4
    assert sum(line.startswith("vn ") for line in lines) == 4
    assert sum(line.startswith("f ") for line in lines) == 4
    with pytest.raises(ValueError, match="names vertex 9"):
        softtrace.write_mesh(str(out), v, np.array([[0, 1, 9]]))
    with pytest.raises(ValueError, match="unsupported mesh format"):
        softtrace.write_mesh(str(tmp_path / "x.fbx"), v, f)
    with pytest.raises(ValueError, match="shape"):
        softtrace.write_mesh(str(out), v[:, :2], f)
    assert len(out.read_text().splitlines()) == len(lines)  # the failed writes left it as it was


def test_bad_arguments_raise():
    scene = softtrace.load_scene(FIG12B)
    with pytest.raises(ValueError, match="no object named"):
        softtrace.mesh(scene, object="nope")
    with pytest.raises(ValueError, match="bounds"):
        softtrace.mesh(scene, bounds=[1, 0, 0, 1, 0, 1])
    with pytest.raises(ValueError, match="cells"):
        softtrace.mesh(scene, cells=0)
