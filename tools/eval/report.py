"""Turns the raw numbers of tools/eval/evaluate into results/evaluation.md and results/lod-error.png.

usage: report.py RAW_DIR RESULTS_DIR "LOD MODELS" "TIMING MODELS"

Reads, per model and level, decimate's summary on standard error (vertex/triangle counts and
its own timing) and metro's JSON (Cignoni, Rocchini, Scopigno 1998 distances against the
original). Standard library only; the plot needs matplotlib and is skipped without it.
"""

import json
import os
import re
import sys

SUMMARY = re.compile(
    r"total: vertices (\d+) -> (\d+), triangles (\d+) -> (\d+); removed (\d+) vertices in "
    r"([0-9.eE+-]+) s"
)


def read(path, default=None):
    try:
        with open(path, encoding="utf-8") as f:
            return f.read()
    except OSError:
        return default


def decimate_summary(log):
    """(vertices before, after, triangles before, after, removed, seconds) or None."""
    m = SUMMARY.search(log or "")
    if not m:
        return None
    v0, v1, t0, t1, removed = (int(m.group(i)) for i in range(1, 6))
    return v0, v1, t0, t1, removed, float(m.group(6))


def run(raw, name):
    """Everything known about one decimate + metro run."""
    metro = read(os.path.join(raw, f"{name}.metro.json"))
    if metro is None:
        return None
    log = read(os.path.join(raw, f"{name}.decimate.log"), "")
    return {
        "metro": json.loads(metro),
        "summary": decimate_summary(log),
        "fully": "fully decimated" in log,
        "wall": float(read(os.path.join(raw, f"{name}.wall"), "nan")),
    }


def pct(x):
    return f"{100.0 * x:.4f}"


def sci(x):
    return f"{x:.3e}"


def main():
    raw, results, lod_models, timing_models = sys.argv[1:5]
    lod_models, timing_models = lod_models.split(), timing_models.split()
    machine = dict(
        line.split("\t", 1) for line in read(os.path.join(raw, "machine.tsv"), "").splitlines()
        if "\t" in line
    )
    out = ["# Evaluation: levels of detail, decimation time, metro against MeshLab", ""]
    out.append("Regenerate with `tools/eval/evaluate` (this file is written by it).")
    out.append("")
    out.append("| | |")
    out.append("|---|---|")
    for key, label in [("date", "date (UTC)"), ("cpu", "CPU"), ("nproc", "cores (nproc)"),
                       ("memory", "memory"), ("rustc", "compiler"), ("crate", "crate"),
                       ("commit", "git commit"), ("samples", "metro face samples per direction"),
                       ("runtime", "runtime of tools/eval/evaluate (s)")]:
        out.append(f"| {label} | {machine.get(key, '?')} |")
    out.append("")
    out.append(
        "Distances are measured by our `metro` between the ORIGINAL scan (A) and each level (B), "
        "in model units and as a percentage of A's bounding-box diagonal. *mean* is the "
        "area-weighted mean distance (the larger of A→B and B→A); *max* is the Hausdorff "
        "distance (the larger one-sided maximum). Decimation time is what `decimate` reports "
        "for the removal itself; wall time adds reading and writing the files."
    )
    out.append("")

    series = {}
    lod_csv = ["model,level,vertices,triangles,decimate_seconds,mean,max,mean_relative,"
               "max_relative,a_to_b_mean,b_to_a_mean,a_to_b_max,b_to_a_max,fully_decimated"]
    timing_csv = ["model,percent,vertices_before,vertices_after,triangles_after,removed,"
                  "decimate_seconds,wall_seconds,mean_relative,max_relative"]
    out.append("## Levels of detail (each level removes 50 % of the vertices of the one before)")
    out.append("")
    for model in lod_models:
        rows = []
        level = 1
        while True:
            r = run(raw, f"{model}-L{level}")
            if r is None:
                break
            rows.append((level, r))
            level += 1
        if not rows:
            out.append(f"*{model}: no levels were produced.*\n")
            continue
        first = rows[0][1]["metro"]["a"]
        diagonal = rows[0][1]["metro"]["diagonal"]
        out.append(f"### {model} ({first['vertices']} vertices, {first['triangles']} triangles, "
                   f"bounding-box diagonal {diagonal:.4g})")
        out.append("")
        out.append("| level | vertices | triangles | decimation (s) | mean | mean (% diag) "
                   "| max | max (% diag) |")
        out.append("|---:|---:|---:|---:|---:|---:|---:|---:|")
        out.append(f"| 0 | {first['vertices']} | {first['triangles']} | | 0 | 0 | 0 | 0 |")
        points = []
        for level, r in rows:
            m, s = r["metro"], r["summary"]
            verts = s[1] if s else m["b"]["vertices"]
            tris = s[3] if s else m["b"]["triangles"]
            secs = f"{s[5]:.3f}" if s else f"{r['wall']:.3f} (wall)"
            note = " (fully decimated)" if r["fully"] else ""
            sym = m["symmetric"]
            out.append(f"| {level}{note} | {verts} | {tris} | {secs} | {sci(sym['mean'])} | "
                       f"{pct(sym['mean_relative'])} | {sci(sym['max'])} | "
                       f"{pct(sym['max_relative'])} |")
            points.append((level, sym["mean_relative"], sym["max_relative"]))
            lod_csv.append(",".join(str(x) for x in (
                model, level, verts, tris, s[5] if s else "", sym["mean"], sym["max"],
                sym["mean_relative"], sym["max_relative"], m["a_to_b"]["mean"],
                m["b_to_a"]["mean"], m["a_to_b"]["max"], m["b_to_a"]["max"], int(r["fully"]))))
        series[model] = points
        out.append("")

    out.append("## Time to remove 60, 80 and 90 % of the vertices")
    out.append("")
    out.append("| model | vertices | removed | vertices left | triangles left | decimation (s) "
               "| vertices removed / s | wall (s) | mean (% diag) | max (% diag) |")
    out.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for model in timing_models:
        for percent in (60, 80, 90):
            r = run(raw, f"{model}-p{percent}")
            if r is None:
                continue
            m, s = r["metro"], r["summary"]
            if s:
                v0, v1, _, t1, removed, secs = s
                rate = f"{removed / secs:,.0f}" if secs > 0 else "-"
                secs_text = f"{secs:.3f}"
            else:
                v0, v1, t1 = m["a"]["vertices"], m["b"]["vertices"], m["b"]["triangles"]
                removed, secs_text = v0 - v1, "-"
                rate = f"{removed / r['wall']:,.0f} (wall)" if r["wall"] > 0 else "-"
            timing_csv.append(",".join(str(x) for x in (
                model, percent, v0, v1, t1, removed, s[5] if s else "", r["wall"],
                m["symmetric"]["mean_relative"], m["symmetric"]["max_relative"])))
            out.append(f"| {model} | {v0} | {percent} % ({removed}) | {v1} | {t1} | {secs_text} | "
                       f"{rate} | {r['wall']:.2f} | {pct(m['symmetric']['mean_relative'])} | "
                       f"{pct(m['symmetric']['max_relative'])} |")
    out.append("")

    meshlab = read(os.path.join(raw, "meshlab.txt"))
    if meshlab:
        out.append("## metro against MeshLab (pymeshlab `get_hausdorff_distance`)")
        out.append("")
        out.append("Output of `tools/eval/hausdorff-vs-meshlab`:")
        out.append("")
        out.append("```")
        out.append(meshlab.rstrip())
        out.append("```")
        out.append("")

    png = os.path.join(results, "lod-error.png")
    if plot(series, png, machine):
        out.append("## Plot")
        out.append("")
        out.append("![error against level](lod-error.png)")
        out.append("")
    for name, lines in (("lod.csv", lod_csv), ("timing.csv", timing_csv)):
        with open(os.path.join(results, name), "w", encoding="utf-8") as f:
            f.write("\n".join(lines) + "\n")
    with open(os.path.join(results, "evaluation.md"), "w", encoding="utf-8") as f:
        f.write("\n".join(out))
    print("\n".join(out))


def plot(series, path, machine):
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("evaluate-report: matplotlib missing, no plot", file=sys.stderr)
        return False
    if not series:
        return False
    fig, ax = plt.subplots(figsize=(8, 5), dpi=120)
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, (model, points) in enumerate(series.items()):
        c = colors[i % len(colors)]
        lv = [p[0] for p in points]
        ax.plot(lv, [100 * p[1] for p in points], "-o", color=c, label=f"{model}: mean")
        ax.plot(lv, [100 * p[2] for p in points], "--s", color=c, label=f"{model}: max (Hausdorff)")
    ax.set_yscale("log")
    ax.set_xlabel("level (each removes 50 % of the vertices of the one before)")
    ax.set_ylabel("distance to the original (% of bounding-box diagonal)")
    ax.set_title(f"Error against level of detail — decimate, measured by metro\n"
                 f"{machine.get('crate', '')} {machine.get('commit', '')}", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path)
    return True


if __name__ == "__main__":
    main()
