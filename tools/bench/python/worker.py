#!/usr/bin/env python3
"""One timed call for tools/bench/python: worker.py TOOL IN.npz RATIO OUT.npz

Loads the mesh's arrays (IN.npz: vertices float32 (n, 3), faces int32 (m, 3)), builds the
tool's own mesh object, then times the decimation call alone (keeping RATIO of the
triangles) and the growth of the process's peak resident memory over it, saves the result's
arrays to OUT.npz and prints `{"seconds": ..., "peak_mb": ...}` as JSON. A fresh process per
call: the peak memory is a high-water mark that never goes down.
"""
import json
import resource
import sys
import time

import numpy as np


def peak_mb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0


def prepare(tool, v, f, keep):
    """The tool's call, closed over its own input objects (built here, outside the timing)."""
    if tool == "decimate":
        import decimate
        return lambda: (lambda r: (r.vertices, r.faces))(decimate.simplify(v, f, keep_triangles=keep))
    if tool == "fast-simplification":
        import fast_simplification
        reduction = 1.0 - keep / len(f)
        return lambda: fast_simplification.simplify(v, f, target_reduction=reduction)
    if tool == "pyfqmr":
        import pyfqmr

        def run():
            s = pyfqmr.Simplify()
            s.setMesh(v, f)
            s.simplify_mesh(target_count=keep, aggressiveness=7, preserve_border=True, verbose=0)
            out_v, out_f, _ = s.getMesh()
            return out_v, out_f
        return run
    if tool == "open3d":
        import open3d as o3d
        mesh = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(v.astype(np.float64)),
                                         o3d.utility.Vector3iVector(f))

        def run():
            out = mesh.simplify_quadric_decimation(target_number_of_triangles=keep)
            return np.asarray(out.vertices), np.asarray(out.triangles)
        return run
    if tool == "pymeshlab":
        import pymeshlab
        ms = pymeshlab.MeshSet()
        ms.add_mesh(pymeshlab.Mesh(v.astype(np.float64), f))

        def run():
            ms.meshing_decimation_quadric_edge_collapse(targetfacenum=keep)
            m = ms.current_mesh()
            return m.vertex_matrix(), m.face_matrix()
        return run
    if tool == "meshoptimizer":
        import meshoptimizer as mo
        indices = f.astype(np.uint32).ravel()

        def run():
            out = np.zeros_like(indices)
            count = mo.simplify(out, indices, v, target_index_count=3 * keep, target_error=1.0)
            used, faces = np.unique(out[:count], return_inverse=True)
            return v[used], faces.reshape(-1, 3)
        return run
    if tool == "trimesh":
        import trimesh
        mesh = trimesh.Trimesh(v, f, process=False)

        def run():
            out = mesh.simplify_quadric_decimation(face_count=keep)
            return np.asarray(out.vertices), np.asarray(out.faces)
        return run
    raise SystemExit(f"unknown tool {tool}")


def main():
    tool, src, ratio, dst = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
    data = np.load(src)
    v, f = data["vertices"], data["faces"]
    keep = round(ratio * len(f))
    call = prepare(tool, v, f, keep)
    before = peak_mb()
    start = time.perf_counter()
    out_v, out_f = call()
    seconds = time.perf_counter() - start
    grown = peak_mb() - before
    np.savez(dst, vertices=np.asarray(out_v, dtype=np.float64), faces=np.asarray(out_f, dtype=np.int64))
    print(json.dumps({"seconds": seconds, "peak_mb": grown}))


if __name__ == "__main__":
    main()
