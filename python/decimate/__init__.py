"""Mesh decimation on numpy arrays.

``decimate.simplify(vertices, faces, ratio=0.1)`` keeps a tenth of the triangles of a mesh by
quadric edge collapse (``algorithm="qem"``, the default) or Schroeder vertex removal
(``algorithm="schroeder"``: vertices never move). ``decimate.read`` / ``decimate.write`` read
and write VRML 1.0/2.0, Open Inventor, PLY, OBJ, STL, OFF and glTF 2.0 files;
``decimate.simplify_file`` decimates one file into another; ``decimate.metro`` measures the
distance between two surfaces; ``simplify(..., record=True)`` records a progressive mesh.

Meshes are numpy arrays: ``vertices`` of shape (n, 3) (float32 or float64) and ``faces`` of
shape (m, 3) (int32, int64 or uint32), or trimesh, PyVista (triangles only) and Open3D mesh
objects, which come back as the same kind of object.

The work runs with the GIL released: other Python threads go on, several threads can
simplify at once, and Ctrl-C (or ``Cancel.request()`` from another thread) stops a run
within a fraction of a second.
"""

from __future__ import annotations

import importlib
import os
from dataclasses import dataclass, field
from typing import Any, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _decimate
from ._decimate import Cancel, Cancelled, Progressive, ReadError

__all__ = [
    "Cancel",
    "Cancelled",
    "Metro",
    "Model",
    "Progressive",
    "ReadError",
    "Report",
    "Scene",
    "SimplifyResult",
    "metro",
    "read",
    "simplify",
    "simplify_file",
    "write",
]

try:
    from importlib.metadata import version as _version

    __version__ = _version("decimate")
except Exception:  # not installed as a distribution (a source tree on sys.path)
    __version__ = "0.1.0"


@dataclass
class Report:
    """What a simplification did: counts before and after, the largest error of any
    removal made (model units), the seconds it took, whether nothing more could be removed,
    the feature angle in force at the end, and warnings (a relaxed feature angle, dropped
    models, what an output format could not hold)."""

    vertices_before: int
    vertices_after: int
    triangles_before: int
    triangles_after: int
    max_error: float
    seconds: float
    fully_decimated: bool
    feature_angle: float
    warnings: List[str] = field(default_factory=list)


@dataclass
class SimplifyResult:
    """The simplified mesh: ``vertices`` (n, 3) and ``faces`` (m, 3) in the dtypes given,
    the kept per-vertex ``colors``, ``uvs`` and ``normals`` (None when none were given),
    the ``report``, and the ``progressive`` record when ``record=True`` was asked."""

    vertices: np.ndarray
    faces: np.ndarray
    report: Report
    colors: Optional[np.ndarray] = None
    uvs: Optional[np.ndarray] = None
    normals: Optional[np.ndarray] = None
    progressive: Optional[Progressive] = None


@dataclass
class Model:
    """One mesh of a scene file: float32 ``vertices`` (n, 3) in the model's own frame,
    uint32 ``faces`` (m, 3), its 4 x 4 ``transform`` to world space (``transform @ [x, y,
    z, 1]``), and what the file gave besides: ``colors`` and ``normals`` (per vertex or per
    face, as ``colors_per`` / ``normals_per`` say), texture coordinates ``uvs``, the
    ``texture`` image's path, the ``diffuse`` colour, ``solid`` (closed, back faces
    may be culled), and ``origin``: three float64 coordinates added after the transform, so
    a point of the file is ``origin + transform @ [x, y, z, 1]``; zero unless the file's
    coordinates are far from zero (georeferenced scans), where the float32 vertices are
    relative to it."""

    vertices: np.ndarray
    faces: np.ndarray
    name: str = ""
    transform: np.ndarray = field(default_factory=lambda: np.eye(4, dtype=np.float32))
    colors: Optional[np.ndarray] = None
    colors_per: str = "vertex"
    normals: Optional[np.ndarray] = None
    normals_per: str = "vertex"
    uvs: Optional[np.ndarray] = None
    texture: Optional[str] = None
    diffuse: Tuple[float, float, float] = (0.8, 0.8, 0.8)
    solid: bool = False
    origin: Tuple[float, float, float] = (0.0, 0.0, 0.0)


class Scene(list):
    """The models a file holds (a list of `Model`), with the reader's ``warnings`` (parts
    of the file it skipped)."""

    def __init__(self, models: Sequence[Model] = (), warnings: Sequence[str] = ()):
        super().__init__(models)
        self.warnings: List[str] = list(warnings)


@dataclass
class Metro:
    """Distances between two surfaces A and B, sampled both ways: ``max`` (the Hausdorff
    distance), ``mean`` and ``rms``, each the larger of the two directions, in model units;
    ``diagonal`` is A's bounding-box diagonal; ``a_to_b`` / ``b_to_a`` hold each
    direction's max, mean, rms and sample count."""

    max: float
    mean: float
    rms: float
    diagonal: float
    a_to_b: dict
    b_to_a: dict


# ---------------------------------------------------------------------------------------
# Checking and converting arrays


# Coordinates of this magnitude or more are decimated relative to an origin (the core's
# `io::origin::FAR`): float32's step there is a thousandth.
_FAR = 8192.0


def _origin(v: np.ndarray) -> np.ndarray:
    """The origin the core's readers pick: zero unless the first vertex has a coordinate of
    magnitude `_FAR` or more, else that vertex rounded (float64)."""
    first = np.asarray(v[0], dtype=np.float64) if len(v) else np.zeros(3)
    if v.dtype.kind == "f" and np.isfinite(first).all() and (np.abs(first) >= _FAR).any():
        return np.round(first)
    return np.zeros(3)


def _vertices(a: Any, what: str = "vertices") -> np.ndarray:
    v = np.asarray(a)
    if v.dtype.kind not in "fiu":
        raise ValueError(f"{what}: expected numbers, got dtype {v.dtype}")
    if v.ndim != 2 or v.shape[1] != 3:
        raise ValueError(f"{what}: expected shape (n, 3), got {v.shape}")
    if v.shape[0] == 0:
        raise ValueError(f"{what}: empty (no vertices)")
    if not np.isfinite(v).all():
        row = int(np.argwhere(~np.isfinite(v))[0][0])
        raise ValueError(f"{what}: row {row} is not finite ({v[row].tolist()})")
    with np.errstate(over="ignore"):  # reported just below, with the row
        out = np.ascontiguousarray(v, dtype=np.float32)
    if not np.isfinite(out).all():
        row = int(np.argwhere(~np.isfinite(out))[0][0])
        raise ValueError(f"{what}: row {row} overflows float32 ({v[row].tolist()})")
    return out


def _faces(a: Any, n_vertices: int, what: str = "faces") -> np.ndarray:
    f = np.asarray(a)
    if f.dtype.kind not in "iu":
        raise ValueError(f"{what}: expected integer indices, got dtype {f.dtype}")
    if f.ndim != 2 or f.shape[1] != 3:
        raise ValueError(f"{what}: expected shape (m, 3) (triangles), got {f.shape}")
    if f.shape[0] == 0:
        raise ValueError(f"{what}: empty (no triangles)")
    low, high = f.min(), f.max()
    if low < 0 or high >= n_vertices:
        bad = (f < 0) | (f >= n_vertices)
        row = int(np.argwhere(bad)[0][0])
        raise ValueError(
            f"{what}: row {row} is {f[row].tolist()}, but indices must be in 0..{n_vertices - 1}"
        )
    return np.ascontiguousarray(f, dtype=np.uint32)


def _attribute(a: Any, width: int, n: int, what: str) -> Optional[np.ndarray]:
    if a is None:
        return None
    v = np.asarray(a)
    if v.dtype.kind not in "fiu" or v.ndim != 2 or v.shape != (n, width):
        raise ValueError(f"{what}: expected shape ({n}, {width}) numbers, got {v.shape} {v.dtype}")
    if not np.isfinite(v).all():
        raise ValueError(f"{what}: not all values are finite")
    return np.ascontiguousarray(v, dtype=np.float32)


def _goal(ratio, keep_triangles, keep_vertices, max_error):
    given = [k for k, v in (("ratio", ratio), ("keep_triangles", keep_triangles),
                            ("keep_vertices", keep_vertices)) if v is not None]
    if len(given) > 1:
        raise ValueError(f"give one target, not {' and '.join(given)}")
    if not given and max_error is None:
        raise ValueError("give a target: ratio, keep_triangles, keep_vertices or max_error")
    if ratio is not None and not (0.0 <= float(ratio) <= 1.0):
        raise ValueError(f"ratio: the fraction of triangles kept, in 0..1, got {ratio}")
    for name, value in (("keep_triangles", keep_triangles), ("keep_vertices", keep_vertices)):
        if value is not None and (int(value) != value or value < 0):
            raise ValueError(f"{name}: expected a count >= 0, got {value}")
    if max_error is not None and not (np.isfinite(max_error) and max_error >= 0):
        raise ValueError(f"max_error: expected a distance >= 0, got {max_error}")
    return (
        None if ratio is None else float(ratio),
        None if keep_triangles is None else int(keep_triangles),
        None if keep_vertices is None else int(keep_vertices),
        None if max_error is None else float(max_error),
    )


def _options(algorithm: str, feature_angle: float) -> None:
    if algorithm not in ("qem", "schroeder"):
        raise ValueError(f"algorithm: expected 'qem' or 'schroeder', got {algorithm!r}")
    if not (0.0 <= float(feature_angle) <= 180.0):
        raise ValueError(f"feature_angle: degrees in 0..180, got {feature_angle}")


# ---------------------------------------------------------------------------------------
# Mesh objects of other libraries, recognised by their class's module (never imported here
# unless the object is one of theirs).


def _kind(obj: Any) -> Optional[str]:
    module = type(obj).__module__ or ""
    root = module.split(".")[0]
    if root == "trimesh" and hasattr(obj, "vertices") and hasattr(obj, "faces"):
        return "trimesh"
    if root == "pyvista" and hasattr(obj, "points") and hasattr(obj, "faces"):
        return "pyvista"
    if root == "open3d" and hasattr(obj, "vertices") and hasattr(obj, "triangles"):
        return "open3d"
    if isinstance(obj, (SimplifyResult, Model)):
        return "arrays"
    if isinstance(obj, tuple) and len(obj) == 2:
        return "tuple"
    return None


def _unpack(obj: Any) -> Tuple[np.ndarray, np.ndarray]:
    kind = _kind(obj)
    if kind in ("trimesh", "arrays"):
        return np.asarray(obj.vertices), np.asarray(obj.faces)
    if kind == "tuple":
        return obj[0], obj[1]
    if kind == "open3d":
        return np.asarray(obj.vertices), np.asarray(obj.triangles)
    if kind == "pyvista":
        flat = np.asarray(obj.faces)
        if flat.size % 4 or (flat.size and not (flat.reshape(-1, 4)[:, 0] == 3).all()):
            raise ValueError("PyVista mesh: only triangles are taken (call .triangulate() first)")
        return np.asarray(obj.points), flat.reshape(-1, 4)[:, 1:]
    raise TypeError(
        f"expected (vertices, faces) arrays or a trimesh / PyVista / Open3D mesh, got {type(obj).__name__}"
    )


def _repack(like: Any, vertices: np.ndarray, faces: np.ndarray) -> Any:
    kind = _kind(like)
    if kind == "trimesh":
        return type(like)(vertices=vertices, faces=faces, process=False)
    if kind == "pyvista":
        flat = np.hstack([np.full((len(faces), 1), 3, dtype=faces.dtype), faces]).ravel()
        return type(like)(vertices, flat)
    if kind == "open3d":
        o3d = importlib.import_module(type(like).__module__.split(".")[0])
        return type(like)(
            o3d.utility.Vector3dVector(np.asarray(vertices, dtype=np.float64)),
            o3d.utility.Vector3iVector(np.asarray(faces, dtype=np.int32)),
        )
    return None


# ---------------------------------------------------------------------------------------
# The functions


def simplify(
    vertices: Any,
    faces: Any = None,
    *,
    ratio: Optional[float] = None,
    keep_triangles: Optional[int] = None,
    keep_vertices: Optional[int] = None,
    max_error: Optional[float] = None,
    algorithm: str = "qem",
    keep_border: bool = False,
    feature_angle: float = 30.0,
    colors: Any = None,
    uvs: Any = None,
    normals: Any = None,
    record: bool = False,
    weld: bool = True,
    cancel: Optional[Cancel] = None,
    threads: Optional[int] = None,
) -> Any:
    """Simplify a triangle mesh.

    ``vertices`` is an (n, 3) float array and ``faces`` an (m, 3) integer array of vertex
    indices, counter-clockwise seen from outside. Far coordinates (a first vertex with a
    coordinate of 8192 or more: georeferenced scans) are decimated relative to that vertex
    rounded and moved back, so float64 vertices keep their precision. Instead of the two arrays, a trimesh,
    PyVista (triangles only) or Open3D mesh may be given alone: the same kind of mesh comes
    back. Otherwise a `SimplifyResult` comes back, with ``vertices`` and ``faces`` in the
    dtypes given, the kept attributes and a `Report`.

    Give one target:

    - ``ratio``: the fraction of the triangles to keep (0.1 keeps a tenth), as in trimesh,
      Open3D and fast-simplification. Not the command line's ``-p``, which is the
      percentage of vertices removed (``-p 90`` keeps about a tenth of the vertices).
    - ``keep_triangles`` / ``keep_vertices``: stop at this many (``--keep-triangles`` and
      ``--keep-vertices`` on the command line).
    - ``max_error`` alone: remove while each removal's error stays under this distance
      (model units); with a count target, the count stops earlier if the error would grow
      beyond it. The error of a removal is the RMS distance to the input's planes that the
      new surface stands for: the RMS distance `metro` measures stays under it, while the
      largest (Hausdorff) distance may reach a few times it.

    ``algorithm`` is ``"qem"`` (quadric edge collapse, the default) or ``"schroeder"``
    (vertex removal: the kept vertices never move). ``keep_border=True`` never moves or
    removes a vertex on the open border. ``feature_angle`` (degrees) is the dihedral angle
    above which an edge is a feature. ``colors`` (n, 3), ``uvs`` (n, 2) and ``normals``
    (n, 3), per vertex, are carried to the result. ``record=True`` also records a
    `Progressive` mesh (qem) in the result's ``progressive``. Before decimating, as the
    ``decimate`` program does, vertices at exactly the same place (and with the same
    ``uvs``) are merged and triangles with no area or repeated are removed (the report's
    warnings say what changed); ``weld=False`` keeps coincident vertices apart. ``cancel``: a `Cancel` that
    another thread may request; the run then raises `Cancelled`. ``threads``: how many
    threads decimate (this call's own included; 1 uses no other), all cores when None;
    the result is the same for every count.

    Raises ValueError on arrays that are not a mesh (wrong shape or dtype, empty, an index
    out of range, NaN or infinite coordinates). Arrays that are not contiguous or not
    writable are copied; the inputs are never changed.

    >>> out = decimate.simplify(vertices, faces, ratio=0.1)
    >>> out.faces.shape[0], out.report.max_error
    """
    like = None
    if faces is None:
        like = vertices
        vertices, faces = _unpack(vertices)
    v_in, f_in = np.asarray(vertices), np.asarray(faces)
    # Far coordinates (georeferenced) are decimated relative to an origin, in float32 there,
    # and moved back in float64.
    origin = _origin(v_in) if v_in.ndim == 2 and v_in.shape[-1:] == (3,) else np.zeros(3)
    far = bool(origin.any())
    v = _vertices(np.asarray(v_in, dtype=np.float64) - origin if far else v_in)
    f = _faces(f_in, len(v))
    goal = _goal(ratio, keep_triangles, keep_vertices, max_error)
    _options(algorithm, feature_angle)
    n = len(v)
    c = _attribute(colors, 3, n, "colors")
    t = _attribute(uvs, 2, n, "uvs")
    nm = _attribute(normals, 3, n, "normals")
    raw = _decimate.simplify(
        v, f, goal, algorithm, bool(keep_border), float(feature_angle), c, t, nm, bool(record), bool(weld), cancel,
        _threads(threads),
    )
    v_dtype = v_in.dtype if v_in.dtype.kind == "f" else np.dtype(np.float64)
    if far:
        out_v = (raw["vertices"].astype(np.float64) + origin).astype(v_dtype, copy=False)
    else:
        out_v = raw["vertices"].astype(v_dtype, copy=False)
    out_f = raw["faces"].astype(f_in.dtype, copy=False)
    if like is not None and _kind(like) not in ("arrays", "tuple"):
        return _repack(like, out_v, out_f)
    return SimplifyResult(
        vertices=out_v,
        faces=out_f,
        report=Report(**raw["report"]),
        colors=raw.get("colors"),
        uvs=raw.get("uvs"),
        normals=raw.get("normals"),
        progressive=raw["progressive"],
    )


def simplify_file(
    src: Union[str, "os.PathLike[str]"],
    dst: Union[str, "os.PathLike[str]"],
    *,
    ratio: Optional[float] = None,
    keep_triangles: Optional[int] = None,
    keep_vertices: Optional[int] = None,
    max_error: Optional[float] = None,
    algorithm: str = "qem",
    keep_border: bool = False,
    feature_angle: float = 30.0,
    cancel: Optional[Cancel] = None,
    threads: Optional[int] = None,
) -> Report:
    """Read the mesh file ``src``, simplify it and write ``dst``, in the format its
    extension names (.wrl for VRML 2.0, .ply, .obj, .stl, .off, .gltf, .glb), as the ``decimate``
    program does. Targets and options as for `simplify` (``ratio`` counts the triangles of
    the whole scene). Returns the `Report`, whose warnings include what ``dst``'s format
    cannot hold. Refuses to write over ``src`` (ValueError); raises `ReadError` when
    ``src`` is not a mesh file and FileNotFoundError when it does not exist."""
    goal = _goal(ratio, keep_triangles, keep_vertices, max_error)
    _options(algorithm, feature_angle)
    raw = _decimate.simplify_file(
        str(src), str(dst), goal, algorithm, bool(keep_border), float(feature_angle), cancel,
        _threads(threads),
    )
    return Report(**raw)


def _threads(threads: Any) -> Optional[int]:
    """``threads`` checked: None, or a whole number of at least 1."""
    if threads is None:
        return None
    if isinstance(threads, bool) or not isinstance(threads, (int, np.integer)) or threads < 1:
        raise ValueError(f"threads must be a whole number of at least 1, not {threads!r}")
    return int(threads)


def read(path: Union[str, "os.PathLike[str]"]) -> Scene:
    """Read a mesh file (VRML 1.0/2.0, Open Inventor, PLY, OBJ with MTL, STL, OFF, glTF
    2.0, gzipped VRML/Inventor) into a `Scene`: a list of `Model` (float32 vertices, uint32
    faces, transform, colours, normals, texture coordinates and path), with the reader's
    warnings. Raises `ReadError` (a ValueError) naming the file, the line and what is wrong
    when the file is not a mesh, FileNotFoundError when it does not exist."""
    models, warnings = _decimate.read(str(path))
    return Scene([Model(**_model_fields(m)) for m in models], warnings)


def _model_fields(d: dict) -> dict:
    d = dict(d)
    d["diffuse"] = tuple(d["diffuse"])
    d["origin"] = tuple(d["origin"])
    return d


def write(scene: Any, path: Union[str, "os.PathLike[str]"]) -> None:
    """Write meshes to ``path`` in the format its extension names (.wrl for VRML 2.0, .ply,
    .obj, .stl, .off, .gltf, .glb; Inventor is read, not written). ``scene`` is a `Scene` or a list of `Model`, or a single
    mesh: a `Model`, a `SimplifyResult`, a ``(vertices, faces)`` tuple or a trimesh /
    PyVista / Open3D mesh. What the format cannot hold (colours in STL, say) is left out.
    The file is replaced whole (written beside it, then renamed)."""
    items = list(scene) if isinstance(scene, list) else [scene]
    _decimate.write([_model_dict(m, k) for k, m in enumerate(items)], str(path))


def _model_dict(m: Any, k: int) -> dict:
    if isinstance(m, dict):
        m = Model(**m)
    if isinstance(m, Model):
        v = _vertices(m.vertices, f"model {k} vertices")
        f = _faces(m.faces, len(v), f"model {k} faces")
        d = {k2: getattr(m, k2) for k2 in Model.__dataclass_fields__}
        d.update(vertices=v, faces=f, name=m.name or f"model{k}")
        d["transform"] = np.ascontiguousarray(m.transform, dtype=np.float32)
        for key in ("colors", "normals", "uvs"):
            if d[key] is not None:
                d[key] = np.ascontiguousarray(d[key], dtype=np.float32)
        d["diffuse"] = [float(x) for x in m.diffuse]
        d["origin"] = [float(x) for x in m.origin]
        return d
    vertices, faces = _unpack(m)
    v = _vertices(vertices, f"model {k} vertices")
    d = {"vertices": v, "faces": _faces(faces, len(v), f"model {k} faces"), "name": f"model{k}"}
    if isinstance(m, SimplifyResult):
        for key in ("colors", "normals", "uvs"):
            if getattr(m, key) is not None:
                d[key] = np.ascontiguousarray(getattr(m, key), dtype=np.float32)
    return d


def metro(
    a: Any,
    b: Any,
    *,
    samples: Optional[int] = None,
    seed: int = 1,
    cancel: Optional[Cancel] = None,
) -> Metro:
    """Measure the distance between surfaces ``a`` and ``b`` (each a ``(vertices, faces)``
    pair, a `Model`, a `SimplifyResult` or a trimesh / PyVista / Open3D mesh), as the
    ``metro`` program does: points sampled on each surface (``samples`` face samples per
    direction; by default ten per triangle, at least 10 000), their distances to the other
    surface. Returns a `Metro` with the Hausdorff distance ``max``, ``mean`` and ``rms``.
    The same ``seed`` gives the same numbers."""
    arrays = []
    for side, mesh in (("a", a), ("b", b)):
        vertices, faces = _unpack(mesh)
        v = _vertices(vertices, f"{side} vertices")
        f = _faces(faces, len(v), f"{side} faces")
        arrays += [np.ascontiguousarray(np.asarray(vertices), dtype=np.float64), f]
    if samples is not None and (int(samples) != samples or samples <= 0):
        raise ValueError(f"samples: expected a count > 0, got {samples}")
    raw = _decimate.metro(*arrays, None if samples is None else int(samples), int(seed), cancel)
    return Metro(
        max=raw["max"], mean=raw["mean"], rms=raw["rms"], diagonal=raw["diagonal"],
        a_to_b=raw["a_to_b"], b_to_a=raw["b_to_a"],
    )

