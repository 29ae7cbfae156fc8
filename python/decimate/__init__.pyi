"""Type stubs of the decimate package (see the docstrings in __init__.py)."""

import os
from dataclasses import dataclass
from typing import Any, List, Optional, Sequence, Tuple, Union

import numpy as np

_Path = Union[str, "os.PathLike[str]"]

__version__: str

class ReadError(ValueError):
    """A file that cannot be read as a mesh."""

class Cancelled(Exception):
    """A run stopped because its Cancel was requested."""

class Cancel:
    """A stop request another thread can make while a run goes on."""
    def __init__(self) -> None: ...
    def request(self) -> None: ...
    @property
    def requested(self) -> bool: ...

class Progressive:
    """Every level of detail between a decimated mesh and its input."""
    @property
    def min_vertices(self) -> int: ...
    @property
    def max_vertices(self) -> int: ...
    def level(self, n_vertices: int) -> Tuple[np.ndarray, np.ndarray]: ...

@dataclass
class Report:
    vertices_before: int
    vertices_after: int
    triangles_before: int
    triangles_after: int
    max_error: float
    seconds: float
    fully_decimated: bool
    feature_angle: float
    warnings: List[str]

@dataclass
class SimplifyResult:
    vertices: np.ndarray
    faces: np.ndarray
    report: Report
    colors: Optional[np.ndarray] = ...
    uvs: Optional[np.ndarray] = ...
    normals: Optional[np.ndarray] = ...
    progressive: Optional[Progressive] = ...

@dataclass
class Model:
    vertices: np.ndarray
    faces: np.ndarray
    name: str = ...
    transform: np.ndarray = ...
    colors: Optional[np.ndarray] = ...
    colors_per: str = ...
    normals: Optional[np.ndarray] = ...
    normals_per: str = ...
    uvs: Optional[np.ndarray] = ...
    texture: Optional[str] = ...
    diffuse: Tuple[float, float, float] = ...
    solid: bool = ...
    origin: Tuple[float, float, float] = ...

class Scene(List[Model]):
    warnings: List[str]
    def __init__(self, models: Sequence[Model] = ..., warnings: Sequence[str] = ...) -> None: ...

@dataclass
class Metro:
    max: float
    mean: float
    rms: float
    diagonal: float
    a_to_b: dict
    b_to_a: dict

def simplify(
    vertices: Any,
    faces: Any = ...,
    *,
    ratio: Optional[float] = ...,
    keep_triangles: Optional[int] = ...,
    keep_vertices: Optional[int] = ...,
    max_error: Optional[float] = ...,
    algorithm: str = ...,
    keep_border: bool = ...,
    feature_angle: float = ...,
    colors: Any = ...,
    uvs: Any = ...,
    normals: Any = ...,
    record: bool = ...,
    weld: bool = ...,
    cancel: Optional[Cancel] = ...,
    threads: Optional[int] = ...,
) -> Any:
    """Simplify a triangle mesh (arrays -> SimplifyResult; a mesh object -> the same kind)."""

def simplify_file(
    src: _Path,
    dst: _Path,
    *,
    ratio: Optional[float] = ...,
    keep_triangles: Optional[int] = ...,
    keep_vertices: Optional[int] = ...,
    max_error: Optional[float] = ...,
    algorithm: str = ...,
    keep_border: bool = ...,
    feature_angle: float = ...,
    cancel: Optional[Cancel] = ...,
    threads: Optional[int] = ...,
) -> Report:
    """Read src, simplify it and write dst (format from the extension)."""

def read(path: _Path) -> Scene:
    """Read a mesh file into a Scene of Model."""

def write(scene: Any, path: _Path) -> None:
    """Write meshes to path (format from the extension)."""

def metro(
    a: Any, b: Any, *, samples: Optional[int] = ..., seed: int = ..., cancel: Optional[Cancel] = ...
) -> Metro:
    """The distance between two surfaces: Hausdorff max, mean and RMS."""
