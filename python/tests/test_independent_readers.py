"""Every format `decimate` writes, read back by readers that are not ours: trimesh and VTK
for PLY, OFF, OBJ and STL, VTK's VRML importer for VRML 2.0, the Khronos validator and a
glTF accessor reader written here for glTF and GLB, and a `.pm` replay written here from
the layout the format's documentation gives (crates/core/src/io/progressive_file.rs).

What is compared is geometry, not counts: the set of points (our text writers print the
shortest round-trip form of each float32, so points are exact where no transform is
applied) and the triangles as triples of points, up to rotation of their corners (the
winding counts) and in any order, and per-vertex colours where the reader reads them. The
reference is the in-memory result of `decimate.simplify`, or for the command line's own
multi-model decimation its OFF output parsed here; a `.pm` level is compared with what the
command line decimates to.

A reader that is not installed is skipped with its reason; under CI (`CI` set) it must be
there, unless tools/test found no wheel for it (DECIMATE_TEST_UNAVAILABLE)."""

import importlib
import json
import os
import struct
import subprocess
from collections import Counter

import numpy as np
import pytest

import decimate
from conftest import REPO, icosphere

# Formats `decimate` writes (docs: `decimate --help`, `-o filename`).
FORMATS = ["ply", "off", "obj", "stl", "wrl", "gltf", "glb"]
# Which independent readers read which format.
READERS = {
    "ply": ["trimesh", "vtk"],
    "off": ["trimesh"],
    "obj": ["trimesh", "vtk"],
    "stl": ["trimesh", "vtk"],
    "wrl": ["vtk"],
    "gltf": ["accessors", "trimesh"],
    "glb": ["accessors", "trimesh"],
}
# The readers that read per-vertex colours of the formats that hold them (trimesh reads no
# OFF colour).
COLOURS = {("ply", "trimesh"), ("ply", "vtk"), ("obj", "trimesh"), ("obj", "vtk"),
           ("wrl", "vtk"), ("gltf", "accessors"), ("glb", "accessors")}


def need(module, package):
    """`module`, or a skip; under CI a failure unless tools/test found no wheel for
    `package` (named as DECIMATE_TEST_UNAVAILABLE names it)."""
    try:
        return importlib.import_module(module)
    except ImportError as e:
        unavailable = os.environ.get("DECIMATE_TEST_UNAVAILABLE", "").split(",")
        if os.environ.get("CI") and package not in unavailable:
            pytest.fail(f"{module} is not installed in the test venv: {e}")
        pytest.skip(f"{module} is not installed: {e}")


# --- comparison -----------------------------------------------------------------------


class PointIndex:
    """The reference's distinct points, found again within `tol` by a grid of cells `tol`
    wide (each lookup checks the 27 cells around a point: linear in the points)."""

    def __init__(self, points, tol):
        self.points = np.unique(np.asarray(points, dtype=np.float64), axis=0)
        self.tol = tol
        self.cell = max(tol, 1e-30)
        self.grid = {}
        for i, p in enumerate(self.points):
            self.grid.setdefault(self.key(p), []).append(i)

    def key(self, p):
        return tuple(int(k) for k in np.floor(p / self.cell))

    def find(self, p):
        """The id of the reference point within `tol` of `p`, or None."""
        kx, ky, kz = self.key(p)
        best, best_d = None, self.tol
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for i in self.grid.get((kx + dx, ky + dy, kz + dz), ()):
                        d = np.abs(self.points[i] - p).max()
                        if d <= best_d:
                            best, best_d = i, d
        return best


def rotated(t):
    """A triangle's corner ids rotated so the smallest comes first; the winding stays."""
    k = t.index(min(t))
    return tuple(t[k:] + t[:k])


def assert_same_mesh(what, points, triangles, want_points, want_triangles, tol, colors=None,
                     want_colors=None):
    """`points`/`triangles` (what a reader saw, world coordinates) are the reference's
    points and triangles: the same set of points within `tol` (max norm) and the same
    multiset of triangles as point triples with the same winding. With `colors` (0..1 per
    point), each point's colour is its reference point's within one step of 255."""
    index = PointIndex(want_points, tol)
    want_ids = [index.find(p) for p in np.asarray(want_points, dtype=np.float64)]
    got_ids = [index.find(p) for p in np.asarray(points, dtype=np.float64)]
    missing = [tuple(p) for p, i in zip(points, got_ids) if i is None]
    assert not missing, f"{what}: {len(missing)} points that are not ours, e.g. {missing[:3]}"
    assert set(got_ids) == set(want_ids), (
        f"{what}: {len(set(want_ids) - set(got_ids))} of our {len(set(want_ids))} points "
        "are not in the file")
    got = Counter(rotated([got_ids[c] for c in t]) for t in np.asarray(triangles).tolist())
    want = Counter(rotated([want_ids[c] for c in t]) for t in np.asarray(want_triangles).tolist())
    assert sum(got.values()) == sum(want.values()), (
        f"{what}: {sum(got.values())} triangles, we wrote {sum(want.values())}")
    extra, lost = got - want, want - got
    assert not extra and not lost, (
        f"{what}: {sum(extra.values())} triangles differ, e.g. read {list(extra)[:2]}, "
        f"written {list(lost)[:2]}")
    if want_colors is not None:
        assert colors is not None, f"{what}: the reader found no colours"
        want = {i: c for i, c in zip(want_ids, np.asarray(want_colors, dtype=np.float64))}
        off = [(k, tuple(c), tuple(want[i])) for k, (i, c) in enumerate(zip(got_ids, colors))
               if np.abs(want[i] - c).max() > 1.01 / 255]
        assert not off, f"{what}: {len(off)} points have another colour, e.g. {off[:2]}"


# --- the independent readers ----------------------------------------------------------


def read_trimesh(path):
    trimesh = need("trimesh", "trimesh")
    mesh = trimesh.load(str(path), force="mesh", process=False)
    colors = None
    if mesh.visual.kind == "vertex":
        colors = np.asarray(mesh.visual.vertex_colors, dtype=np.float64)[:, :3] / 255
    return np.asarray(mesh.vertices), np.asarray(mesh.faces), colors


def _vtk_triangles(vtk, pd, matrix=None, lut=None):
    """Points (world coordinates through `matrix`), triangles and colours of VTK polygon
    data: RGB point scalars, or one scalar a point that `lut` maps (the VRML importer's)."""
    tri = vtk.vtkTriangleFilter()
    tri.SetInputData(pd)
    tri.Update()
    out = tri.GetOutput()
    pts = np.array([out.GetPoint(i) for i in range(out.GetNumberOfPoints())], dtype=np.float64)
    pts = pts.reshape(-1, 3)
    if matrix is not None:
        m = np.array([[matrix.GetElement(r, c) for c in range(4)] for r in range(4)])
        pts = pts @ m[:3, :3].T + m[:3, 3]
    ids = vtk.vtkIdList()
    polys = out.GetPolys()
    polys.InitTraversal()
    faces = []
    while polys.GetNextCell(ids):
        faces.append([ids.GetId(k) for k in range(ids.GetNumberOfIds())])
    scalars = out.GetPointData().GetScalars()
    colors = None
    if scalars is not None and scalars.GetNumberOfComponents() in (3, 4):
        colors = np.array([scalars.GetTuple(i)[:3] for i in range(out.GetNumberOfPoints())])
        colors = colors.reshape(-1, 3) / 255
    elif scalars is not None and lut is not None:
        colors = np.zeros((out.GetNumberOfPoints(), 3))
        for i, rgb in enumerate(colors):
            lut.GetColor(scalars.GetTuple1(i), rgb)
    return pts, np.array(faces, dtype=np.int64).reshape(-1, 3), colors


def read_vtk(path):
    need("pyvista", "pyvista")
    import vtk

    vtk.vtkObject.GlobalWarningDisplayOff()
    ext = path.suffix.lower()
    if ext == ".wrl":
        imp = vtk.vtkVRMLImporter()
        imp.SetFileName(str(path))
        imp.Update()
        actors = imp.GetRenderer().GetActors()
        actors.InitTraversal()
        parts = []
        for _ in range(actors.GetNumberOfItems()):
            actor = actors.GetNextActor()
            mapper = actor.GetMapper()
            parts.append(_vtk_triangles(vtk, mapper.GetInput(), actor.GetMatrix(),
                                        mapper.GetLookupTable()))
        assert parts, f"VTK found no shape in {path}"
        return _concatenate(parts)
    reader = {".ply": vtk.vtkPLYReader, ".obj": vtk.vtkOBJReader, ".stl": vtk.vtkSTLReader}[ext]()
    reader.SetFileName(str(path))
    if ext == ".stl":
        reader.MergingOff()
    reader.Update()
    return _vtk_triangles(vtk, reader.GetOutput())


def _concatenate(parts):
    """One mesh of (points, triangles, colours or None) parts; colours only if all have them."""
    points, faces, colors, base = [], [], [], 0
    for p, f, c in parts:
        points.append(p)
        faces.append(f + base)
        colors.append(c)
        base += len(p)
    colored = all(c is not None for c in colors)
    return (np.concatenate(points), np.concatenate(faces),
            np.concatenate(colors) if colored else None)


GLTF_COMPONENTS = {5121: "<u1", 5123: "<u2", 5125: "<u4", 5126: "<f4"}
GLTF_WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}


def _gltf_document(path):
    """The JSON and the binary chunk (GLB) or None."""
    data = path.read_bytes()
    if data[:4] != b"glTF":
        return json.loads(data), None
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    assert version == 2 and length == len(data), f"{path}: GLB header"
    pos, doc, bin_chunk = 12, None, None
    while pos < length:
        size, kind = struct.unpack_from("<II", data, pos)
        chunk = data[pos + 8: pos + 8 + size]
        if kind == 0x4E4F534A:
            doc = json.loads(chunk)
        elif kind == 0x004E4942:
            bin_chunk = chunk
        pos += 8 + size
    return doc, bin_chunk


def _gltf_accessor(doc, buffers, index):
    a = doc["accessors"][index]
    assert "sparse" not in a, "our writer writes no sparse accessor"
    view = doc["bufferViews"][a["bufferView"]]
    dtype = np.dtype(GLTF_COMPONENTS[a["componentType"]])
    width = GLTF_WIDTH[a["type"]]
    start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
    stride = view.get("byteStride", dtype.itemsize * width)
    raw = buffers[view["buffer"]]
    rows = [np.frombuffer(raw, dtype, width, start + k * stride) for k in range(a["count"])]
    values = np.array(rows).reshape(a["count"], width)
    if a.get("normalized"):
        return values / np.iinfo(dtype).max
    return values


def _node_matrix(node):
    if "matrix" in node:
        return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T
    x, y, z, w = node.get("rotation", [0, 0, 0, 1])
    r = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    m = np.eye(4)
    m[:3, :3] = r * np.array(node.get("scale", [1, 1, 1]))
    m[:3, 3] = node.get("translation", [0, 0, 0])
    return m


def read_gltf_accessors(path):
    """Our own reading of a glTF 2.0 file: the default scene's node tree, each triangle
    primitive's POSITION and indices accessors, positions taken to world space. A node
    whose world transform mirrors (negative determinant) shows its triangles' clockwise
    side (glTF 2.0, 3.7.2.1): they are reversed here to be counter-clockwise."""
    doc, bin_chunk = _gltf_document(path)
    assert doc["asset"]["version"] == "2.0"
    buffers = []
    for b in doc["buffers"]:
        data = bin_chunk if "uri" not in b else (path.parent / b["uri"]).read_bytes()
        assert len(data) >= b["byteLength"], f"{path}: buffer shorter than its byteLength"
        buffers.append(data)
    parts = []
    stack = [(n, np.eye(4)) for n in doc["scenes"][doc.get("scene", 0)]["nodes"]]
    while stack:
        n, parent = stack.pop()
        node = doc["nodes"][n]
        world = parent @ _node_matrix(node)
        stack += [(c, world) for c in node.get("children", [])]
        if "mesh" not in node:
            continue
        for prim in doc["meshes"][node["mesh"]]["primitives"]:
            assert prim.get("mode", 4) == 4, "triangles"
            p = _gltf_accessor(doc, buffers, prim["attributes"]["POSITION"]).astype(np.float64)
            f = _gltf_accessor(doc, buffers, prim["indices"]).reshape(-1, 3).astype(np.int64)
            if np.linalg.det(world[:3, :3]) < 0:
                f = f[:, [0, 2, 1]]
            c = prim["attributes"].get("COLOR_0")
            c = None if c is None else _gltf_accessor(doc, buffers, c)[:, :3]
            parts.append((p @ world[:3, :3].T + world[:3, 3], f, c))
    return _concatenate(parts)


def validate_gltf(path):
    """The Khronos validator (tools/check/gltf-validate.js) finds no error in `path`."""
    script = REPO / "tools" / "check" / "gltf-validate.js"
    try:
        o = subprocess.run(["node", str(script), str(path)], capture_output=True, text=True)
    except OSError as e:
        if os.environ.get("CI"):
            pytest.fail(f"node cannot run: {e}")
        pytest.skip(f"node cannot run: {e}")
    if o.returncode == 2:
        if os.environ.get("CI"):
            pytest.fail(f"the glTF validator cannot run: {o.stderr}")
        pytest.skip(f"the glTF validator cannot run (tools/setup --test): {o.stderr}")
    assert o.returncode == 0, f"gltf-validator on {path.name}:\n{o.stdout}{o.stderr}"


def read_with(reader, path):
    if reader == "trimesh":
        return read_trimesh(path)
    if reader == "vtk":
        return read_vtk(path)
    validate_gltf(path)
    return read_gltf_accessors(path)


def cases():
    return [pytest.param(fmt, r, id=f"{fmt}-{r}") for fmt in FORMATS for r in READERS[fmt]]


# --- the tests ------------------------------------------------------------------------


@pytest.fixture(scope="module")
def bunny_decimated(bunny):
    """The bunny as qem leaves it at 700 triangles, in memory."""
    m = decimate.read(bunny)[0]
    out = decimate.simplify(m.vertices, m.faces, keep_triangles=700, algorithm="qem")
    assert out.faces.shape == (700, 3)
    return out.vertices, out.faces


@pytest.mark.parametrize("fmt,reader", cases())
def test_the_command_lines_output_is_the_decimated_mesh(fmt, reader, cli, bunny,
                                                        bunny_decimated, tmp_path):
    out = tmp_path / f"bunny.{fmt}"
    subprocess.run([cli, str(bunny), "nogui", "-a", "qem", "--keep-triangles", "700", "-q",
                    "-o", str(out)], check=True)
    points, triangles, _ = read_with(reader, out)
    want_v, want_f = bunny_decimated
    # Every float32 is written exactly (binary, or its shortest round-trip text): exact
    # once read back as float32.
    points = np.asarray(points, dtype=np.float32)
    assert_same_mesh(f"{out.name} by {reader}", points, triangles, want_v, want_f, tol=0.0)


def two_model_scene():
    """Two spheres: the first moved, turned and scaled, the second mirrored (its triangles
    must be written reversed to face outwards), each with per-vertex colours."""
    v1, f1 = icosphere(2)
    v2, f2 = icosphere(1)
    a = decimate.simplify(v1, f1, keep_triangles=120)
    b = decimate.simplify(v2, f2, keep_triangles=60)
    turn = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    t1 = np.eye(4, dtype=np.float32)
    t1[:3, :3] = 2.0 * turn
    t1[:3, 3] = [3.0, -1.0, 0.5]
    t2 = np.eye(4, dtype=np.float32)
    t2[0, 0] = -1.0
    t2[:3, 3] = [-4.0, 0.0, 0.0]
    models = []
    for (r, t, name) in [(a, t1, "moved"), (b, t2, "mirrored")]:
        colors = np.clip(np.abs(r.vertices), 0, 1).astype(np.float32)
        models.append(decimate.Model(vertices=r.vertices, faces=r.faces.astype(np.uint32),
                                     transform=t, colors=colors, name=name))
    return models


def world(model):
    """A model's points in world space, its triangles facing outwards and its colours."""
    t = model.transform.astype(np.float64)
    p = model.vertices.astype(np.float64) @ t[:3, :3].T + t[:3, 3]
    f = np.asarray(model.faces, dtype=np.int64)
    if np.linalg.det(t[:3, :3]) < 0:
        f = f[:, [0, 2, 1]]
    return p, f, model.colors


@pytest.mark.parametrize("fmt,reader", cases())
def test_two_transformed_models_are_written_where_they_stand(fmt, reader, tmp_path):
    models = two_model_scene()
    path = tmp_path / f"scene.{fmt}"
    decimate.write(models, path)
    points, triangles, colors = read_with(reader, path)
    want_v, want_f, want_c = _concatenate([world(m) for m in models])
    # Transforms are applied in float32 by us (formats that store world positions) or by
    # the reader: a few units in the last place of a model about 5 across.
    assert_same_mesh(f"{path.name} by {reader}", points, triangles, want_v, want_f, tol=1e-5,
                     colors=colors, want_colors=want_c if (fmt, reader) in COLOURS else None)



def read_off(path):
    """Our OFF output, parsed here: `[C]OFF`, a comment, counts, `x y z [r g b a]` per
    vertex, `3 a b c` per triangle."""
    lines = [l.split() for l in path.read_text().splitlines() if l and not l.startswith("#")]
    assert lines[0][0] in ("OFF", "COFF"), lines[0]
    n_v, n_f = int(lines[1][0]), int(lines[1][1])
    rows = lines[2: 2 + n_v]
    points = np.array([[float(x) for x in r[:3]] for r in rows])
    colors = np.array([[float(x) for x in r[3:6]] for r in rows]) if lines[0][0] == "COFF" else None
    faces = lines[2 + n_v: 2 + n_v + n_f]
    assert all(f[0] == "3" for f in faces)
    return points, np.array([[int(x) for x in f[1:4]] for f in faces], dtype=np.int64), colors


@pytest.fixture(scope="module")
def scene_decimated(cli, tmp_path_factory):
    """The two-model scene as VRML 2.0, decimated by the command line to 50 %, and its OFF
    output as we read it here."""
    d = tmp_path_factory.mktemp("scene")
    src = d / "in.wrl"
    decimate.write(two_model_scene(), src)
    run = lambda out: subprocess.run([cli, str(src), "nogui", "-p", "50", "-q", "-o", str(out)],
                                     check=True)
    run(d / "out.off")
    return run, read_off(d / "out.off")


@pytest.mark.parametrize("fmt,reader", cases())
def test_every_format_of_a_two_model_decimation_gives_the_same_mesh(fmt, reader,
                                                                    scene_decimated, tmp_path):
    # Through the command line, where a multi-model scene is decimated and written: each
    # format against the OFF output (which the OFF case itself, and VRML through VTK, tie
    # to the independent readers).
    run, (want_v, want_f, want_c) = scene_decimated
    # 62 + 32 vertices less half leave 47; two closed spheres have 2V - 4 triangles each.
    assert (len(want_v), len(want_f)) == (47, 2 * 47 - 8) and want_c is not None
    out = tmp_path / f"out.{fmt}"
    run(out)
    points, triangles, colors = read_with(reader, out)
    assert_same_mesh(f"{out.name} by {reader}", points, triangles, want_v, want_f, tol=1e-5,
                     colors=colors, want_colors=want_c if (fmt, reader) in COLOURS else None)


# --- the progressive file, replayed from its documented layout ------------------------


class _Bytes:
    """A cursor over little-endian bytes, as the `.pm` layout lays them out."""

    def __init__(self, data):
        self.data, self.pos = data, 0

    def take(self, fmt):
        values = struct.unpack_from("<" + fmt, self.data, self.pos)
        self.pos += struct.calcsize("<" + fmt)
        return values

    def u32(self):
        return self.take("I")[0]

    def u8(self):
        return self.take("B")[0]

    def skip_string(self):
        n = self.u32()
        self.pos += n

    def reals(self, n):
        return np.array(self.take(f"{n}f"), dtype=np.float32)


def read_pm(path):
    """Each model of a `.pm` file (layout version 1) as a dict: its transform, base
    positions and triangles, and its splits (keep, keep's fine position, the new position,
    renamed face ids, added faces). Attributes are read past, not kept."""
    b = _Bytes(path.read_bytes())
    assert b.data[:8] == b"DECIMPM\0"
    b.pos = 8
    assert b.u32() == 1
    models = []
    for _ in range(b.u32()):
        b.skip_string()  # name
        transform = b.reals(16).reshape(4, 4).T  # column-major
        b.reals(3)  # diffuse
        b.u8(), b.reals(1), b.u8()  # crease flag and angle, solid
        attrs = b.u8()
        for bit in (16, 32):  # image name, material name
            if attrs & bit:
                b.skip_string()
        n_v, n_f = b.u32(), b.u32()
        positions = b.reals(3 * n_v).reshape(n_v, 3)
        per_vertex = 3 * bool(attrs & 1) + 3 * bool(attrs & 4) + 2 * bool(attrs & 8)
        b.reals(per_vertex * n_v)
        faces = np.array(b.take(f"{3 * n_f}I"), dtype=np.int64).reshape(n_f, 3)
        b.reals(3 * n_f * bool(attrs & 2))
        splits = []
        for _ in range(b.u32()):
            keep = b.u32()
            b.reals(3)  # keep's coarse position
            fine, new = b.reals(3), b.reals(3)
            b.reals(per_vertex * 3)
            renamed = b.take(f"{b.u32()}I")
            n_added = b.u8()
            added = np.array(b.take(f"{3 * n_added}I"), dtype=np.int64).reshape(n_added, 3)
            b.reals(3 * n_added * bool(attrs & 2))
            splits.append((keep, fine, new, renamed, added))
        b.pos += 4 * (n_v + len(splits))  # original vertex ids
        b.pos += 4 * (n_f + sum(len(s[4]) for s in splits))  # original face ids
        models.append({"transform": transform, "positions": positions, "faces": faces,
                       "splits": splits})
    assert b.pos == len(b.data), f"{path}: {len(b.data) - b.pos} bytes after the last model"
    return models


def replay(model, n_vertices):
    """The level with `n_vertices` vertices: the base refined by its first splits, each
    adding vertex V + i, moving `keep` and giving the renamed faces' `keep` corner to it."""
    positions = [p for p in model["positions"]]
    faces = [list(f) for f in model["faces"]]
    for keep, fine, new, renamed, added in model["splits"][: n_vertices - len(positions)]:
        positions[keep] = fine
        positions.append(new)
        for face in renamed:
            faces[face] = [len(positions) - 1 if c == keep else c for c in faces[face]]
        faces += [list(f) for f in added]
    return np.array(positions), np.array(faces, dtype=np.int64)


def test_the_progressive_file_replayed_gives_the_levels_qem_decimates_to(cli, bunny, tmp_path):
    pm = tmp_path / "bunny.pm"
    base = tmp_path / "base.ply"
    subprocess.run([cli, str(bunny), "nogui", "-a", "qem", "-p", "90", "--progressive", str(pm),
                    "-q", "-o", str(base)], check=True)
    [model] = read_pm(pm)
    assert np.array_equal(model["transform"], np.eye(4))
    n_base = len(model["positions"])
    assert n_base == 184 and len(model["faces"]) == 364  # 1839 vertices, 90 % removed
    # The base is the decimated output; all splits give the input back.
    for n, path in [(n_base, base), (n_base + len(model["splits"]), bunny)]:
        v, f = replay(model, n)
        points, triangles, _ = read_trimesh(path)
        assert_same_mesh(f"{path.name} against the replay to {n}", np.float32(points), triangles,
                         v, f, tol=0.0)
    # Levels between: what qem leaves when asked for that many vertices.
    for n in (200, 500, 1000):
        out = tmp_path / f"level{n}.ply"
        subprocess.run([cli, str(bunny), "nogui", "-a", "qem", "--keep-vertices", str(n), "-q",
                        "-o", str(out)], check=True)
        v, f = replay(model, n)
        points, triangles, _ = read_trimesh(out)
        assert_same_mesh(f"{out.name} against the replay", np.float32(points), triangles, v, f,
                         tol=0.0)


def test_a_coloured_models_progressive_file_replays_to_its_output_and_its_input(cli, tmp_path):
    # Colours add per-vertex and per-split records that the replay must read past.
    v, f = icosphere(3)
    colors = np.clip(np.abs(v), 0, 1).astype(np.float32)
    src = tmp_path / "ball.ply"
    decimate.write([decimate.Model(vertices=v, faces=f.astype(np.uint32), colors=colors)], src)
    pm, out = tmp_path / "ball.pm", tmp_path / "out.ply"
    subprocess.run([cli, str(src), "nogui", "-p", "80", "--progressive", str(pm), "-q", "-o",
                    str(out)], check=True)
    [model] = read_pm(pm)
    n_base = len(model["positions"])
    assert n_base == 642 - round(0.8 * 642)
    for n, path in [(n_base, out), (642, src)]:
        got_v, got_f = replay(model, n)
        points, triangles, _ = read_trimesh(path)
        assert_same_mesh(f"{path.name} against the replay to {n}", np.float32(points), triangles,
                         got_v, got_f, tol=0.0)
