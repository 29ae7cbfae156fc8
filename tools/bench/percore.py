#!/usr/bin/env python3
"""The per-core benchmark behind tools/bench/percore: the library call alone, one process a
call, alternating rounds.

  percore.py EXAMPLE MODEL...        MODEL: a triangle PLY; MODEL@N: it subdivided
                                           1→4 N times (edge midpoints)
  percore.py --call TOOL IN KEEP     one timed call (meshoptimizer, fast-simplification)

Each model is first copied as a binary PLY (tri_ply) under $BENCH_PERCORE_DIR, so that every
tool reads the same triangles. Each round runs every tool once, in an order rotated by one
each round; a call prints its seconds (the call alone: the mesh is read before the clock
starts), the triangles it kept, the process's peak resident memory and the CPU seconds of
the call (all threads: on a busy machine steadier than the clock). ROUNDS (5),
KEEP (percent of the triangles kept, 10), THREADS (ours, "1 2"), PEERS (the Python tools,
"meshoptimizer fast-simplification"; meshoptimizer always runs: the ratios are to it) and
BASELINE (another build of the example, e.g. an earlier commit's, run beside ours under
the name BASELINE_NAME) come from the environment. Prints one markdown table per model.
"""
import os
import resource
import statistics
import subprocess
import sys
import time

import numpy as np

from tri_ply import read_ply, write_ply


def read_any_ply(path):
    """Positions (n × 3, float32) and flat indices (uint32) of an ASCII or binary
    little-endian triangle PLY of x y z and vertex_indices."""
    with open(path, "rb") as f:
        head = f.read(512).decode("ascii", "replace")
    if "format binary_little_endian" in head:
        return read_ply(path)
    with open(path, "rb") as f:
        header = []
        while not header or header[-1] != "end_header":
            header.append(f.readline().decode("ascii").strip())
        counts = {w[1]: int(w[2]) for w in map(str.split, header) if w[0] == "element"}
        nv, nf = counts["vertex"], counts["face"]
        text = f.read().split(b"\n")
    v = np.array(b" ".join(text[:nv]).split(), dtype=np.float32).reshape(nv, -1)[:, :3]
    faces = np.array(b" ".join(text[nv:nv + nf]).split(), dtype=np.int64).reshape(nf, -1)
    if not (faces[:, 0] == 3).all():
        sys.exit(f"{path}: not all faces are triangles")
    return np.ascontiguousarray(v), faces[:, 1:4].astype(np.uint32).reshape(-1)


def subdivide(v, f):
    """Every triangle split 1→4 at its edges' midpoints, each midpoint made once."""
    f = f.reshape(-1, 3).astype(np.int64)
    n = len(v)
    ends = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    key = ends.min(1) * n + ends.max(1)
    edges, which = np.unique(key, return_inverse=True)
    lo, hi = edges // n, edges % n
    mid = ((v[lo].astype(np.float64) + v[hi]) * 0.5).astype(np.float32)
    m = which.reshape(3, -1).T + n  # the midpoints of edges 01, 12, 20
    a, b, c = f[:, 0], f[:, 1], f[:, 2]
    out = np.concatenate([
        np.stack([a, m[:, 0], m[:, 2]], 1), np.stack([m[:, 0], b, m[:, 1]], 1),
        np.stack([m[:, 2], m[:, 1], c], 1), np.stack([m[:, 0], m[:, 1], m[:, 2]], 1)])
    return np.concatenate([v, mid]), out.astype(np.uint32).reshape(-1)


def prepared(spec, folder):
    """The binary PLY the tools read for MODEL or MODEL@N, made once."""
    path, _, levels = spec.partition("@")
    levels = int(levels or 0)
    name = os.path.splitext(os.path.basename(path))[0] + (f"_sub{levels}" if levels else "")
    out = os.path.join(folder, name + ".ply")
    if not os.path.exists(out):
        v, f = read_any_ply(path)
        for _ in range(levels):
            v, f = subdivide(v, f)
        write_ply(out, v, f.reshape(-1, 3))
    return name, out


def call(tool, src, keep):
    """One timed call of a peer: seconds, triangles kept, peak KiB."""
    v, f = read_ply(src)
    target = round(len(f) // 3 * keep / 100)
    if tool == "meshoptimizer":
        import meshoptimizer as mo
        out = np.zeros_like(f)
        cpu, start = time.process_time(), time.perf_counter()
        count = mo.simplify(out, f, v, target_index_count=3 * target, target_error=1.0)
        seconds, kept = time.perf_counter() - start, count // 3
    else:
        import fast_simplification
        pts, tri = v.astype(np.float64), f.reshape(-1, 3).astype(np.int32)
        cpu, start = time.process_time(), time.perf_counter()
        _, faces = fast_simplification.simplify(pts, tri, target_count=target)
        seconds, kept = time.perf_counter() - start, len(faces)
    cpu = time.process_time() - cpu
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    print(f"{seconds:.4f} {kept} {peak} {cpu:.4f}")


def run_once(command, env):
    done = subprocess.run(command, env=env, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)} failed: {done.stderr.strip()}")
    seconds, kept, peak, cpu = done.stdout.split()
    return float(seconds), int(kept), int(peak), float(cpu)


def bench(example, name, src, keep, rounds, threads):
    here = os.path.abspath(__file__)
    quiet = dict(os.environ, OMP_NUM_THREADS="1")
    peers = os.environ.get("PEERS", "meshoptimizer fast-simplification").split()
    peers = ["meshoptimizer"] + [p for p in peers if p != "meshoptimizer"]
    tools = [(p, 1, [sys.executable, here, "--call", p, src, str(keep)], quiet) for p in peers]
    # BASELINE: another build of the example (an earlier commit's), run beside ours.
    builds = [("qem", example)]
    if os.environ.get("BASELINE"):
        builds.append(("qem " + os.environ.get("BASELINE_NAME", "baseline"),
                       os.environ["BASELINE"]))
    for n in threads:
        env = dict(os.environ, RAYON_NUM_THREADS=str(n))
        for label, binary in builds:
            tools.append((label, n, [binary, src, str(keep), str(n)], env))
    results = {i: [] for i in range(len(tools))}
    for r in range(rounds):
        order = list(range(len(tools)))
        order = order[r % len(order):] + order[:r % len(order)]
        for i in order:
            results[i].append(run_once(tools[i][2], tools[i][3]))
    def median(i, k):
        return statistics.median(run[k] for run in results[i])
    base, base_cpu = median(0, 0), median(0, 3)
    print(f"\n{name}, {keep} % of the triangles kept, {rounds} rounds\n")
    print("| tool | threads | median s | × meshoptimizer | median CPU s | CPU × meshoptimizer "
          "| triangles out | peak RSS MiB |")
    print("|---|---|---|---|---|---|---|---|")
    for i, (tool, n, _, _) in enumerate(tools):
        med, cpu = median(i, 0), median(i, 3)
        kept = results[i][0][1]
        peak = max(run[2] for run in results[i]) / 1024
        print(f"| {tool} | {n} | {med:.3f} | {med / base:.2f} | {cpu:.3f} | "
              f"{cpu / base_cpu:.2f} | {kept} | {peak:.0f} |")
    sys.stdout.flush()


def main():
    if len(sys.argv) == 5 and sys.argv[1] == "--call":
        call(sys.argv[2], sys.argv[3], float(sys.argv[4]))
        return
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    example, models = sys.argv[1], sys.argv[2:]
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    folder = os.environ.get("BENCH_PERCORE_DIR", os.path.join(root, ".cache", "bench-percore"))
    os.makedirs(folder, exist_ok=True)
    rounds = int(os.environ.get("ROUNDS", "5"))
    keep = float(os.environ.get("KEEP", "10"))
    threads = [int(t) for t in os.environ.get("THREADS", "1 2").split()]
    for spec in models:
        name, src = prepared(spec, folder)
        bench(example, name, src, keep, rounds, threads)


if __name__ == "__main__":
    main()
