"""Binary little-endian triangle PLY (float x y z, then `uchar int vertex_indices`) to and
from numpy arrays, for the benchmark scripts beside it (Python puts a script's own folder on
its import path)."""
import sys

import numpy as np


def read_ply(path):
    """The positions (n × 3) and flat triangle indices of `path`; exits naming the file when
    it is not this layout."""
    with open(path, "rb") as f:
        header = []
        while not header or header[-1] != "end_header":
            header.append(f.readline().decode("ascii").strip())
        counts = {w[1]: int(w[2]) for w in map(str.split, header) if w[0] == "element"}
        expected = ["property float x", "property float y", "property float z",
                    "property list uchar int vertex_indices"]
        props = [h for h in header if h.startswith("property")]
        if "format binary_little_endian 1.0" not in header or props != expected:
            sys.exit(f"{path}: not a binary little-endian PLY of x y z and vertex_indices")
        positions = np.fromfile(f, dtype="<f4", count=3 * counts["vertex"]).reshape(-1, 3)
        faces = np.fromfile(f, dtype=[("n", "u1"), ("i", "<u4", 3)], count=counts["face"])
    if not (faces["n"] == 3).all():
        sys.exit(f"{path}: not all faces are triangles")
    return positions, np.ascontiguousarray(faces["i"]).reshape(-1)


def write_ply(path, positions, triangles):
    """Writes `positions` (n × 3) and `triangles` (m × 3) to `path`."""
    with open(path, "wb") as f:
        f.write((f"ply\nformat binary_little_endian 1.0\nelement vertex {len(positions)}\n"
                 "property float x\nproperty float y\nproperty float z\n"
                 f"element face {len(triangles)}\nproperty list uchar int vertex_indices\n"
                 "end_header\n").encode())
        f.write(positions.astype("<f4").tobytes())
        rec = np.zeros(len(triangles), dtype=[("n", "u1"), ("i", "<i4", 3)])
        rec["n"], rec["i"] = 3, triangles
        f.write(rec.tobytes())
