"""Shared meshes and paths for the decimate tests: an icosphere (closed, genus 0, so its
triangle count is always twice its vertex count minus four), a flat grid, and the
repository's command-line binary and assets."""

import os
import pathlib
import shutil

import numpy as np
import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


def icosphere(subdivisions: int):
    """A unit icosphere: 20 * 4**subdivisions triangles, counter-clockwise from outside."""
    t = (1.0 + 5.0 ** 0.5) / 2.0
    v = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
         [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]]
    f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
         [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
         [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]]
    verts = [np.array(p, dtype=np.float64) / np.linalg.norm(p) for p in v]
    faces = f
    for _ in range(subdivisions):
        cache = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in cache:
                p = verts[a] + verts[b]
                verts.append(p / np.linalg.norm(p))
                cache[key] = len(verts) - 1
            return cache[key]

        new = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new += [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]
        faces = new
    return np.array(verts, dtype=np.float64), np.array(faces, dtype=np.int64)


def grid(n: int):
    """A flat n x n grid of squares in z = 0, two triangles each: (n+1)**2 vertices."""
    i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1))
    v = np.stack([i.ravel(), j.ravel(), np.zeros(i.size)], axis=1).astype(np.float32)
    faces = []
    for y in range(n):
        for x in range(n):
            a = y * (n + 1) + x
            faces += [[a, a + 1, a + n + 2], [a, a + n + 2, a + n + 1]]
    return v, np.array(faces, dtype=np.int32)


@pytest.fixture(scope="session")
def cli():
    """The `decimate` binary: $DECIMATE_BIN, or a cargo build of this repository."""
    candidates = [os.environ.get("DECIMATE_BIN")]
    target = os.environ.get("CARGO_TARGET_DIR")
    for t in ([pathlib.Path(target)] if target else []) + [REPO / "target"]:
        candidates += [str(t / "release" / "decimate"), str(t / "debug" / "decimate")]
    for c in candidates:
        if c and os.access(c, os.X_OK):
            return c
    found = shutil.which("decimate")
    if found:
        return found
    if os.environ.get("CI"):
        pytest.fail("no decimate binary: build it (cargo build) or set DECIMATE_BIN")
    pytest.skip("no decimate binary: build it (cargo build) or set DECIMATE_BIN")


@pytest.fixture(scope="session")
def bunny():
    return REPO / "assets" / "bunny.ply"
