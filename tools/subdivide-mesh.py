#!/usr/bin/env python3
"""A big mesh for the benchmarks: subdivide-mesh.py IN.ply OUT.ply LEVELS

Splits every triangle of IN (any PLY pymeshlab reads) 1→4 at its edge midpoints LEVELS
times and writes a binary little-endian PLY of float x y z and `uchar int vertex_indices`
(the Stanford dragon, 871,414 triangles: 13.9M at 2 levels, 55.8M at 3). Used by
tools/bench-tiles and tools/bench-memory; LEVELS 0 just converts IN to that binary form.
"""
import sys
import numpy as np
import pymeshlab

from tri_ply import write_ply

src, dst, levels = sys.argv[1], sys.argv[2], int(sys.argv[3])
ms = pymeshlab.MeshSet()
ms.load_new_mesh(src)
v = ms.current_mesh().vertex_matrix().astype(np.float32)
f = ms.current_mesh().face_matrix().astype(np.int64)
for _ in range(levels):
    # Each edge's midpoint once: edges keyed by their sorted ends.
    e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    key = np.minimum(e[:, 0], e[:, 1]) * len(v) + np.maximum(e[:, 0], e[:, 1])
    uniq, inverse = np.unique(key, return_inverse=True)
    a, b = uniq // len(v), uniq % len(v)
    mid = ((v[a].astype(np.float64) + v[b]) / 2).astype(np.float32)
    m = inverse.reshape(3, -1).T + len(v)  # midpoints of edges 01, 12, 20
    v = np.concatenate([v, mid])
    f = np.concatenate([
        np.stack([f[:, 0], m[:, 0], m[:, 2]], 1),
        np.stack([m[:, 0], f[:, 1], m[:, 1]], 1),
        np.stack([m[:, 2], m[:, 1], f[:, 2]], 1),
        m,
    ])
write_ply(dst, v, f)
