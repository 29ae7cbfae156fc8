"""Bad input raises a ValueError (or ReadError / FileNotFoundError) that says what is
wrong, and never crashes the interpreter or writes over an input."""

import numpy as np
import pytest

import decimate
from conftest import icosphere

V, F = icosphere(1)


@pytest.mark.parametrize(
    "vertices, faces, message",
    [
        (V[:, :2], F, r"vertices: expected shape \(n, 3\)"),
        (V.ravel(), F, r"vertices: expected shape \(n, 3\)"),
        (V, F[:, :2], r"faces: expected shape \(m, 3\)"),
        (V, F.astype(np.float64), "faces: expected integer indices"),
        (V.astype(str), F, "vertices: expected numbers"),
        (np.zeros((0, 3)), np.zeros((0, 3), dtype=np.int32), "vertices: empty"),
        (V, np.zeros((0, 3), dtype=np.int32), "faces: empty"),
        (V, np.where(F == 5, len(V), F), rf"faces: row \d+ .* 0..{len(V) - 1}"),
        (V, np.where(F == 5, -1, F), r"faces: row \d+ .* 0..41"),
        (np.where(np.arange(len(V))[:, None] == 7, np.nan, V), F, "vertices: row 7 is not finite"),
        (np.where(np.arange(len(V))[:, None] == 3, np.inf, V), F, "vertices: row 3 is not finite"),
        (V * 1e300, F, "overflows float32"),
    ],
)
def test_arrays_that_are_not_a_mesh(vertices, faces, message):
    with pytest.raises(ValueError, match=message):
        decimate.simplify(vertices, faces, ratio=0.5)


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({}, "give a target"),
        ({"ratio": 0.5, "keep_triangles": 10}, "give one target"),
        ({"ratio": 1.5}, "ratio: the fraction of triangles kept"),
        ({"ratio": -0.1}, "ratio"),
        ({"keep_vertices": -3}, "keep_vertices"),
        ({"max_error": float("nan")}, "max_error"),
        ({"ratio": 0.5, "algorithm": "fast"}, "algorithm"),
        ({"ratio": 0.5, "colors": np.zeros((3, 3))}, r"colors: expected shape \(42, 3\)"),
        ({"ratio": 0.5, "uvs": np.zeros((42, 3))}, r"uvs: expected shape \(42, 2\)"),
    ],
)
def test_bad_options(kwargs, message):
    with pytest.raises(ValueError, match=message):
        decimate.simplify(V, F, **kwargs)


def test_not_a_mesh_object():
    with pytest.raises(TypeError, match="trimesh"):
        decimate.simplify(object(), ratio=0.5)


def test_a_file_that_is_not_a_mesh_is_a_read_error(tmp_path):
    bad = tmp_path / "notes.ply"
    bad.write_text("this is not a ply file\n")
    with pytest.raises(decimate.ReadError, match="notes.ply"):
        decimate.read(bad)
    assert issubclass(decimate.ReadError, ValueError)
    with pytest.raises(decimate.ReadError):
        decimate.simplify_file(bad, tmp_path / "out.ply", ratio=0.5)
    assert not (tmp_path / "out.ply").exists()


def test_a_missing_file(tmp_path):
    with pytest.raises(FileNotFoundError, match="missing.obj"):
        decimate.read(tmp_path / "missing.obj")


def test_simplify_file_never_writes_over_its_input(bunny, tmp_path):
    src = tmp_path / "bunny.ply"
    src.write_bytes(bunny.read_bytes())
    before = src.read_bytes()
    with pytest.raises(ValueError, match="input file"):
        decimate.simplify_file(src, src, ratio=0.5)
    with pytest.raises(ValueError, match="input file"):
        decimate.simplify_file(src, tmp_path / "." / "bunny.ply", ratio=0.5)
    assert src.read_bytes() == before


def test_an_unknown_output_format(tmp_path):
    with pytest.raises(ValueError, match="unknown output format"):
        decimate.write((V, F), tmp_path / "out.xyz")
