"""Mesh objects of trimesh, PyVista and Open3D go in and the same kind comes out. A library
that is not installed is skipped with its reason; under CI it must be installed unless
tools/test found no wheel for it (DECIMATE_TEST_UNAVAILABLE lists those, with why)."""

import importlib
import os

import numpy as np
import pytest

import decimate
from conftest import icosphere


def need(name):
    unavailable = os.environ.get("DECIMATE_TEST_UNAVAILABLE", "")
    try:
        return importlib.import_module(name)
    except ImportError as e:
        if os.environ.get("CI") and name not in unavailable.split(","):
            pytest.fail(f"{name} is not installed in the test venv: {e}")
        pytest.skip(f"{name} is not installed: {e}")


def test_trimesh_in_trimesh_out():
    trimesh = need("trimesh")
    v, f = icosphere(4)
    mesh = trimesh.Trimesh(v, f, process=False)
    out = decimate.simplify(mesh, ratio=0.1)
    assert isinstance(out, trimesh.Trimesh)
    assert len(out.faces) == 512
    assert out.is_watertight and out.volume > 0


def test_pyvista_in_pyvista_out():
    pv = need("pyvista")
    v, f = icosphere(4)
    mesh = pv.PolyData(v, np.hstack([np.full((len(f), 1), 3), f]).ravel())
    out = decimate.simplify(mesh, ratio=0.1)
    assert isinstance(out, pv.PolyData)
    assert out.n_cells == 512 and out.is_all_triangles
    quads = pv.Plane(i_resolution=2, j_resolution=2)
    with pytest.raises(ValueError, match="triangulate"):
        decimate.simplify(quads, ratio=0.5)


def test_open3d_in_open3d_out():
    o3d = need("open3d")
    v, f = icosphere(4)
    mesh = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(v), o3d.utility.Vector3iVector(f))
    out = decimate.simplify(mesh, ratio=0.1)
    assert isinstance(out, o3d.geometry.TriangleMesh)
    assert len(out.triangles) == 512
    assert out.is_watertight()


def test_metro_takes_mesh_objects():
    trimesh = need("trimesh")
    v, f = icosphere(3)
    d = decimate.metro(trimesh.Trimesh(v, f, process=False), (v, f))
    assert d.max == 0
