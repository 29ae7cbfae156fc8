#!/usr/bin/env python3
"""meshoptimizer's run for tools/bench/memory: memory-meshopt.py IN.ply OUT.ply TRIANGLES

Reads a binary little-endian triangle PLY (float x y z, then `uchar int vertex_indices`:
what tools/bench/memory makes) straight into numpy arrays, keeps about TRIANGLES triangles
with meshopt_simplify (the `meshoptimizer` Python binding) and writes OUT.ply the same way,
so that the process's peak memory is the library's and the two arrays it works on, not a
mesh loader's.
"""
import sys

import meshoptimizer as mo
import numpy as np

from tri_ply import read_ply, write_ply


def main():
    src, dst, triangles = sys.argv[1], sys.argv[2], int(sys.argv[3])
    positions, indices = read_ply(src)
    out = np.zeros_like(indices)
    count = mo.simplify(out, indices, positions, target_index_count=3 * triangles,
                        target_error=1.0)
    del indices
    faces = out[:count].reshape(-1, 3)
    used, faces = np.unique(faces, return_inverse=True)
    write_ply(dst, positions[used], faces.reshape(-1, 3))


if __name__ == "__main__":
    main()
