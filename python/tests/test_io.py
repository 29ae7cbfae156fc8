"""decimate.read / write for every format, and metro."""

import subprocess
import sys

import numpy as np
import pytest

import decimate
from conftest import REPO, icosphere


@pytest.mark.parametrize("ext", ["ply", "obj", "off", "stl", "wrl", "gltf", "glb"])
def test_write_then_read_gives_the_same_mesh(ext, tmp_path):
    v, f = icosphere(2)
    path = tmp_path / f"sphere.{ext}"
    decimate.write((v, f), path)
    scene = decimate.read(path)
    assert len(scene) == 1
    m = scene[0]
    assert m.faces.shape == f.shape
    # STL stores corners, not shared vertices: compare the triangles' corner points.
    got = np.sort(m.vertices[m.faces].reshape(-1, 3), axis=0)
    want = np.sort(v.astype(np.float32)[f].reshape(-1, 3), axis=0)
    assert np.allclose(got, want, atol=1e-5)


def test_transform_and_colours_survive_a_vrml_round_trip(tmp_path):
    v, f = icosphere(1)
    t = np.eye(4, dtype=np.float32)
    t[:3, 3] = [1, 2, 3]
    colors = np.tile(np.array([[0.25, 0.5, 0.75]], dtype=np.float32), (len(v), 1))
    model = decimate.Model(vertices=v, faces=f, transform=t, colors=colors, name="ball")
    path = tmp_path / "ball.wrl"
    decimate.write([model], path)
    back = decimate.read(path)[0]
    world = back.vertices @ back.transform[:3, :3].T + back.transform[:3, 3]
    assert np.allclose(np.sort(world, axis=0), np.sort(v + [1, 2, 3], axis=0), atol=1e-5)
    assert back.colors is not None
    assert np.allclose(back.colors, [0.25, 0.5, 0.75], atol=1e-2)


def test_far_coordinates_come_back_as_an_origin_and_are_written_back_whole(tmp_path):
    src = tmp_path / "far.obj"
    src.write_text("v 300000.125 1200000.35 50.5\nv 300000.475 1200000.35 50.5\n"
                   "v 300000.125 1200000.7 50.25\nf 1 2 3\n")
    (m,) = decimate.read(src)
    assert m.origin == (300000.0, 1200000.0, 51.0)
    assert np.abs(m.vertices).max() < 1.0
    decimate.write([m], tmp_path / "back.obj")
    lines = [l for l in (tmp_path / "back.obj").read_text().splitlines() if l.startswith("v ")]
    assert lines == [l for l in src.read_text().splitlines() if l.startswith("v ")]


def test_reads_the_repository_assets():
    scene = decimate.read(REPO / "assets" / "bunny.ply")
    assert scene[0].vertices.dtype == np.float32 and scene[0].faces.dtype == np.uint32
    assert scene[0].faces.shape == (3674, 3)


def test_metro_of_a_mesh_and_itself_is_zero_and_of_a_shifted_copy_the_shift():
    v, f = icosphere(3)
    same = decimate.metro((v, f), (v, f))
    assert same.max == 0 and same.mean == 0 and same.rms == 0
    shifted = decimate.metro((v, f), (v * 1.01, f))
    assert shifted.max == pytest.approx(0.01, rel=0.05)
    assert shifted.mean == pytest.approx(0.01, rel=0.2)
    assert shifted.a_to_b["samples"] > 10_000


def test_importing_decimate_imports_no_mesh_library():
    code = "import sys, decimate; print(sorted(m for m in ('trimesh','pyvista','open3d','vtk') if m in sys.modules))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_every_function_has_a_docstring():
    for name in decimate.__all__:
        assert getattr(decimate, name).__doc__, name
    assert "fraction of the triangles to keep" in decimate.simplify.__doc__
    assert "-p" in decimate.simplify.__doc__
