"""decimate.simplify on arrays: exact counts, the same result as the command line, checks
by an independent library, the error bound, and the dtypes and layouts it accepts."""

import subprocess

import numpy as np
import pytest

import decimate
from conftest import grid, icosphere


def test_version_is_the_packages():
    assert decimate.__version__ == "0.1.0"


def test_closed_sphere_keeps_exactly_the_triangles_asked_and_stays_closed():
    v, f = icosphere(4)  # 5120 triangles, 2562 vertices
    out = decimate.simplify(v, f, keep_triangles=1000)
    # On a closed genus-0 surface every collapse removes two triangles and one vertex.
    assert out.faces.shape == (1000, 3)
    assert out.vertices.shape == (502, 3)
    r = out.report
    assert (r.vertices_before, r.triangles_before) == (2562, 5120)
    assert (r.vertices_after, r.triangles_after) == (502, 1000)
    # Every vertex used, every index in range.
    assert np.array_equal(np.unique(out.faces), np.arange(502))


def test_ratio_is_the_fraction_of_triangles_kept():
    v, f = icosphere(4)
    out = decimate.simplify(v, f, ratio=0.25)
    assert out.faces.shape[0] == 1280


def test_keep_vertices():
    v, f = icosphere(3)
    out = decimate.simplify(v, f, keep_vertices=100, algorithm="schroeder")
    assert out.vertices.shape[0] == 100
    assert out.faces.shape[0] == 2 * 100 - 4


def test_flat_grid_with_its_border_kept_keeps_only_the_border():
    v, f = grid(10)  # 121 vertices, 40 of them on the border
    out = decimate.simplify(v, f, keep_vertices=0, keep_border=True, algorithm="schroeder")
    assert out.vertices.shape[0] == 40
    assert out.faces.shape[0] == 38  # a 40-gon in triangles
    border = {(x, y) for x in range(11) for y in range(11) if x in (0, 10) or y in (0, 10)}
    assert {(int(x), int(y)) for x, y, _ in out.vertices} == border


def test_a_count_target_out_of_reach_is_a_warning():
    v, f = grid(10)
    out = decimate.simplify(v, f, keep_triangles=10, keep_border=True, algorithm="schroeder")
    assert out.faces.shape[0] == 38
    assert any("target was not reached: 38 triangles left, 10 asked" in w for w in out.report.warnings)


def test_dtypes_come_back_as_given():
    v, f = icosphere(2)
    for vt, ft in [(np.float32, np.int32), (np.float64, np.int64), (np.float64, np.uint32)]:
        out = decimate.simplify(v.astype(vt), f.astype(ft), ratio=0.5)
        assert out.vertices.dtype == vt and out.faces.dtype == ft


def test_non_contiguous_and_read_only_inputs_give_the_same_result_and_stay_unchanged():
    v, f = icosphere(3)
    expected = decimate.simplify(v, f, ratio=0.3)
    wide = np.zeros((len(v), 6))
    wide[:, ::2] = v
    strided = wide[:, ::2]
    fortran = np.asfortranarray(f)
    ro_v, ro_f = v.copy(), f.copy()
    ro_v.flags.writeable = False
    ro_f.flags.writeable = False
    before = (v.copy(), f.copy())
    for vv, ff in [(strided, f), (v, fortran), (ro_v, ro_f)]:
        out = decimate.simplify(vv, ff, ratio=0.3)
        assert np.array_equal(out.vertices, expected.vertices)
        assert np.array_equal(out.faces, expected.faces)
    assert np.array_equal(v, before[0]) and np.array_equal(f, before[1])


def test_attributes_are_carried_per_vertex():
    v, f = icosphere(3)
    colors = (v + 1) / 2  # the colour encodes the position
    out = decimate.simplify(v, f, ratio=0.2, colors=colors, algorithm="schroeder")
    assert out.colors.shape == (len(out.vertices), 3)
    # Vertex removal never moves vertices: each kept vertex keeps its own colour.
    assert np.allclose(out.colors, (out.vertices + 1) / 2, atol=1e-6)


def _canonical(vertices, faces):
    """The vertex rows sorted, and each triangle as its corners' coordinates, rotated to
    start at its smallest corner (orientation kept), sorted: equal for the same mesh in
    any vertex order."""
    corners = np.asarray(vertices)[np.asarray(faces, dtype=np.int64)]
    tris = []
    for t in corners.tolist():
        k = t.index(min(t))
        tris.append(tuple(map(tuple, t[k:] + t[:k])))
    return sorted(map(tuple, np.asarray(vertices).tolist())), sorted(tris)


def test_same_result_as_the_command_line(cli, bunny, tmp_path):
    scene = decimate.read(bunny)
    m = scene[0]
    out = decimate.simplify(m.vertices, m.faces, keep_triangles=700)
    dst = tmp_path / "out.ply"
    subprocess.run([cli, str(bunny), "nogui", "-a", "qem", "--keep-triangles", "700", "-q",
                    "-o", str(dst)], check=True)
    theirs = decimate.read(dst)[0]
    assert theirs.faces.shape == out.faces.shape
    assert theirs.vertices.shape == out.vertices.shape
    # The same collapses: the same points and triangles (PLY stores float32 exactly).
    assert _canonical(theirs.vertices, theirs.faces) == _canonical(out.vertices, out.faces)


def test_simplify_file_matches_simplify_on_the_read_arrays(bunny, tmp_path):
    dst = tmp_path / "out.obj"
    report = decimate.simplify_file(bunny, dst, ratio=0.2)
    m = decimate.read(bunny)[0]
    out = decimate.simplify(m.vertices, m.faces, ratio=0.2)
    assert report.triangles_after == out.faces.shape[0]
    assert decimate.read(dst)[0].faces.shape == out.faces.shape


def test_closed_output_checked_by_trimesh():
    trimesh = pytest.importorskip("trimesh")
    v, f = icosphere(4)
    out = decimate.simplify(v, f, ratio=0.1)
    mesh = trimesh.Trimesh(out.vertices, out.faces, process=False)
    assert mesh.is_watertight
    assert mesh.is_winding_consistent
    sphere = 4 / 3 * np.pi
    assert mesh.volume > 0.95 * sphere * 0.97  # outward faces: positive volume, near a ball's


@pytest.mark.parametrize("algorithm", ["qem", "schroeder"])
@pytest.mark.parametrize("bound", [0.003, 0.01])
def test_max_error_is_honoured_as_metro_measures_it(algorithm, bound):
    v, f = icosphere(4)
    bumpy = v * (1 + 0.05 * np.sin(8 * v[:, :1]) * np.cos(6 * v[:, 1:2]))
    out = decimate.simplify(bumpy, f, max_error=bound, algorithm=algorithm)
    assert out.faces.shape[0] < 0.8 * len(f)  # it did remove something
    assert out.report.max_error <= bound
    # The bound is on each removal's RMS distance to the planes it stands for (see the
    # docstring): the surface's RMS distance stays under it; its maximum does not.
    d = decimate.metro((bumpy, f), out)
    assert d.rms <= bound
    # Twice the bound, so that an error check that was skipped altogether fails.
    looser = decimate.metro((bumpy, f), decimate.simplify(bumpy, f, max_error=2 * bound, algorithm=algorithm))
    assert looser.rms > d.rms


def test_progressive_levels_run_from_the_result_back_to_the_input():
    v, f = icosphere(3)  # 642 vertices
    out = decimate.simplify(v, f, keep_vertices=100, record=True)
    p = out.progressive
    assert (p.min_vertices, p.max_vertices) == (100, 642)
    lv, lf = p.level(100)
    assert lv.shape == (100, 3) and lf.shape == (196, 3)
    lv, lf = p.level(642)
    assert lv.shape == (642, 3) and lf.shape == (1280, 3)
    # The finest level is the input, renumbered: the same set of points.
    assert np.allclose(np.sort(lv, axis=0), np.sort(v.astype(np.float32), axis=0))
    lv, lf = p.level(300)
    assert lv.shape == (300, 3) and lf.shape == (2 * 300 - 4, 3)
    lv, lf = p.level(10)  # clamped to the coarsest
    assert lv.shape == (100, 3)


def test_report_warns_about_repaired_input():
    v, f = icosphere(2)
    soup_v = v[f.ravel()]  # every triangle with its own three corners (an STL soup)
    soup_f = np.arange(len(soup_v)).reshape(-1, 3)
    out = decimate.simplify(soup_v, soup_f, ratio=0.5)
    assert out.report.vertices_before == len(v)  # welded back into one surface
    loose = decimate.simplify(soup_v, soup_f, ratio=0.5, weld=False)
    assert loose.report.vertices_before == len(soup_v)


def _bumpy_patch(n: int, t):
    """A 0.35-unit patch of n x n float64 vertices with bumps, moved by `t`."""
    v, f = grid(n - 1)
    xy = v[:, :2].astype(np.float64) * (0.35 / (n - 1))
    z = 0.01 * np.sin(xy[:, 0] * 40.0) * np.cos(xy[:, 1] * 30.0)
    return np.column_stack([xy, z]) + np.asarray(t, dtype=np.float64), f


@pytest.mark.parametrize("algorithm", ["qem", "schroeder"])
@pytest.mark.parametrize("t", [(3e5, 1.2e6, 50.0), (1e7, -1e7, 1e7)])
def test_far_float64_vertices_decimate_as_they_do_at_the_origin(algorithm, t):
    near_v, f = _bumpy_patch(33, (0.0, 0.0, 0.0))
    far_v, _ = _bumpy_patch(33, t)
    near = decimate.simplify(near_v, f, ratio=0.2, algorithm=algorithm)
    far = decimate.simplify(far_v, f, ratio=0.2, algorithm=algorithm)
    assert far.vertices.dtype == np.float64
    assert np.array_equal(far.faces, near.faces)
    # Moved back, the far result is the origin run's (float32 at 1.2e6 moves points by up
    # to 0.06, at 1e7 by 0.5).
    assert np.abs(far.vertices - np.asarray(t) - near.vertices).max() < 1e-6
