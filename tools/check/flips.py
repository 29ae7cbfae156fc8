#!/usr/bin/env python3
"""Flipped triangles of a vertex-removal result (`schroeder`, whose output keeps input
positions): an output triangle is flipped when its normal is more than 90° from every
input triangle at its three corners (issue 40's bar). Reads PLY/OBJ/OFF/STL by pymeshlab
(EVAL_CACHE's venv). Usage: check-flips.py INPUT OUTPUT; exit 1 when any is flipped."""
import sys

import numpy as np
import pymeshlab


def read(path):
    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(path)
    m = ms.current_mesh()
    return m.vertex_matrix().astype(np.float64), m.face_matrix().astype(np.int64)


def unit_normals(v, f):
    n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    return n / np.maximum(np.linalg.norm(n, axis=1), 1e-300)[:, None]


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    vi, fi = read(sys.argv[1])
    vo, fo = read(sys.argv[2])
    # Every input vertex at a position counts (a scan may repeat a point in two places).
    at = {}
    for i, p in enumerate(vi):
        at.setdefault(tuple(p), []).append(i)
    missing = sum(tuple(p) not in at for p in vo)
    if missing:
        sys.exit(f"{sys.argv[2]}: {missing} vertices are not input vertices")
    incident = {}
    for t, tri in enumerate(fi):
        for x in tri:
            incident.setdefault(tuple(vi[x]), []).append(t)
    ni, no = unit_normals(vi, fi), unit_normals(vo, fo)
    flipped = 0
    for t, tri in enumerate(fo):
        keys = [tuple(vo[x]) for x in tri]
        best = max((float(no[t].dot(ni[s])) for k in keys for s in incident.get(k, [])), default=-1.0)
        if best <= 0.0:
            flipped += 1
            corners = [at[k][0] for k in keys]
            print(f"triangle {t} (input vertices {corners}): best cosine {best:.3f}")
    print(f"{sys.argv[2]}: {len(fo)} triangles, {flipped} flipped")
    sys.exit(1 if flipped else 0)


if __name__ == "__main__":
    main()
