#!/usr/bin/env python3
"""One peer decimation for tools/bench/peers: peers-run.py TOOL IN.ply OUT.ply TRIANGLES

TOOL is meshlab (pymeshlab's quadric edge collapse), vtk (vtkQuadricDecimation), vtkpro
(vtkDecimatePro, Schroeder's vertex removal, with its defaults), meshoptimizer
(meshopt_simplify through the `meshoptimizer` Python binding), fastsimp (the
`fast-simplification` package, Fast Quadric Mesh Simplification) or open3d
(simplify_quadric_decimation). Keeps about
TRIANGLES triangles, writes OUT.ply and prints the seconds the decimation call alone took.
"""
import sys
import time


def meshlab(src, dst, triangles):
    import pymeshlab

    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(src)
    start = time.perf_counter()
    ms.meshing_decimation_quadric_edge_collapse(targetfacenum=triangles)
    seconds = time.perf_counter() - start
    ms.save_current_mesh(dst)
    return seconds


def vtk(src, dst, triangles, pro=False):
    import vtk as v

    reader = v.vtkPLYReader()
    reader.SetFileName(src)
    reader.Update()
    mesh = reader.GetOutput()
    q = v.vtkDecimatePro() if pro else v.vtkQuadricDecimation()
    q.SetInputData(mesh)
    q.SetTargetReduction(1.0 - triangles / mesh.GetNumberOfPolys())
    start = time.perf_counter()
    q.Update()
    seconds = time.perf_counter() - start
    writer = v.vtkPLYWriter()
    writer.SetFileName(dst)
    writer.SetInputData(q.GetOutput())
    writer.Write()
    return seconds


def vtkpro(src, dst, triangles):
    return vtk(src, dst, triangles, pro=True)


def meshoptimizer(src, dst, triangles):
    import numpy as np
    import pymeshlab
    import meshoptimizer as mo

    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(src)
    m = ms.current_mesh()
    positions = np.ascontiguousarray(m.vertex_matrix(), dtype=np.float32)
    indices = np.ascontiguousarray(m.face_matrix(), dtype=np.uint32).reshape(-1)
    out = np.zeros_like(indices)
    start = time.perf_counter()
    count = mo.simplify(
        out, indices, positions, target_index_count=3 * triangles, target_error=1.0
    )
    seconds = time.perf_counter() - start
    faces = out[:count].reshape(-1, 3)
    used = np.unique(faces)
    remap = np.zeros(len(positions), dtype=np.int64)
    remap[used] = np.arange(len(used))
    kept = pymeshlab.Mesh(positions[used].astype(np.float64), remap[faces].astype(np.int32))
    out_set = pymeshlab.MeshSet()
    out_set.add_mesh(kept)
    out_set.save_current_mesh(dst)
    return seconds


def _read_arrays(src):
    import numpy as np
    import pymeshlab

    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(src)
    m = ms.current_mesh()
    return np.asarray(m.vertex_matrix(), dtype=np.float64), np.asarray(m.face_matrix(), dtype=np.int64)


def _write_arrays(dst, points, faces):
    import numpy as np
    import pymeshlab

    out_set = pymeshlab.MeshSet()
    out_set.add_mesh(pymeshlab.Mesh(np.asarray(points, dtype=np.float64), np.asarray(faces, dtype=np.int32)))
    out_set.save_current_mesh(dst)


def fastsimp(src, dst, triangles):
    import fast_simplification

    points, faces = _read_arrays(src)
    start = time.perf_counter()
    out_points, out_faces = fast_simplification.simplify(
        points.astype("float32"), faces.astype("int32"), target_count=triangles
    )
    seconds = time.perf_counter() - start
    _write_arrays(dst, out_points, out_faces)
    return seconds


def open3d(src, dst, triangles):
    import open3d as o3d

    points, faces = _read_arrays(src)
    mesh = o3d.geometry.TriangleMesh(o3d.utility.Vector3dVector(points), o3d.utility.Vector3iVector(faces))
    start = time.perf_counter()
    kept = mesh.simplify_quadric_decimation(target_number_of_triangles=triangles)
    seconds = time.perf_counter() - start
    _write_arrays(dst, kept.vertices, kept.triangles)
    return seconds


if __name__ == "__main__":
    tool, src, dst, triangles = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
    print(f"{globals()[tool](src, dst, triangles):.3f}")
