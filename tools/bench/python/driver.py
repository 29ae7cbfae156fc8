#!/usr/bin/env python3
"""The table of tools/bench/python: driver.py MODEL RATIO ROUNDS API_TIMER TOOL...

Reads MODEL's first mesh with decimate.read, then for ROUNDS rounds (the tools' order
rotated each round) runs worker.py once per tool, and the Rust API's timer (API_TIMER, the
same decimation in Rust on the same arrays). Each result is measured against the input by
decimate.metro (mean / max distance, as a fraction of the bounding-box diagonal) and for
non-manifold edges; prints a Markdown table with the median time and the range.
"""
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
from importlib import metadata

import numpy as np

import decimate

HERE = os.path.dirname(os.path.abspath(__file__))
PACKAGES = {"decimate": "decimate", "fast-simplification": "fast-simplification",
            "pyfqmr": "pyfqmr", "open3d": "open3d", "pymeshlab": "pymeshlab",
            "meshoptimizer": "meshoptimizer", "trimesh": "trimesh"}


def nonmanifold_edges(faces):
    f = np.asarray(faces, dtype=np.int64)
    e = np.sort(np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    return int((counts > 2).sum())


def version(tool):
    try:
        return metadata.version(PACKAGES[tool])
    except Exception:
        return "?"


def main():
    model, ratio, rounds, timer, tools = sys.argv[1], float(sys.argv[2]), int(sys.argv[3]), sys.argv[4], sys.argv[5:]
    m = decimate.read(model)[0]
    v, f = m.vertices, m.faces.astype(np.int32)
    keep = round(ratio * len(f))
    work = tempfile.mkdtemp(prefix="bench-python-")
    src = os.path.join(work, "in.npz")
    np.savez(src, vertices=v, faces=f)
    times = {t: [] for t in tools + ["rust-api"]}
    peaks = {t: [] for t in tools}
    order = tools + ["rust-api"]
    for r in range(rounds):
        for tool in order[r % len(order):] + order[: r % len(order)]:
            if tool == "rust-api":
                out = subprocess.run([timer, model, str(keep)], capture_output=True, text=True, check=True)
                times[tool].append(float(out.stdout.split()[0]))
                continue
            dst = os.path.join(work, f"{tool}.npz")
            out = subprocess.run([sys.executable, os.path.join(HERE, "worker.py"), tool, src, str(ratio), dst],
                                 capture_output=True, text=True)
            if out.returncode != 0:
                print(f"{tool}: failed: {out.stderr.strip().splitlines()[-1:]}", file=sys.stderr)
                continue
            result = json.loads(out.stdout.strip().splitlines()[-1])
            times[tool].append(result["seconds"])
            peaks[tool].append(result["peak_mb"])
    print(f"{model}: {len(v)} vertices, {len(f)} triangles; keep {keep} ({ratio:g}); {rounds} rounds\n")
    print("| tool | version | triangles | time s, median (range) | peak memory growth MB | metro mean / diag | metro max / diag | non-manifold edges |")
    print("|---|---|---|---|---|---|---|---|")
    for tool in tools:
        if not times[tool]:
            continue
        r = np.load(os.path.join(work, f"{tool}.npz"))
        d = decimate.metro((v, f), (r["vertices"], r["faces"]))
        t = times[tool]
        print(f"| {tool} | {version(tool)} | {len(r['faces'])} | {statistics.median(t):.3f} ({min(t):.3f}–{max(t):.3f}) "
              f"| {statistics.median(peaks[tool]):.0f} | {d.mean / d.diagonal:.2e} | {d.max / d.diagonal:.2e} "
              f"| {nonmanifold_edges(r['faces'])} |")
    t = times["rust-api"]
    print(f"| Rust API (same arrays) | | | {statistics.median(t):.3f} ({min(t):.3f}–{max(t):.3f}) | | | | |")
    shutil.rmtree(work, ignore_errors=True)
    if times.get("decimate"):
        print(f"\ndecimate.simplify / Rust API, medians: {statistics.median(times['decimate']) / statistics.median(t):.3f}")


if __name__ == "__main__":
    main()
