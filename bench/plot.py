#!/usr/bin/python3
"""Plots of fse_bench's output: /usr/bin/python3 bench/plot.py OUT_DIR

Reads OUT_DIR/results.json (and OUT_DIR/scaling.csv if present) and writes
  accuracy_vs_time.png  error against time per query, log-log, every method and setting,
                        one panel per point distribution: the accuracy/time Pareto front
  mesh_resolution.png   error and time of FCL's mesh and convex polytope against vertices,
                        with our Exact solver and the paper's method as reference lines
  scaling.png           time per vertex against point-cloud size
  pairs.png             (from OUT_DIR/pairs.csv, fse_bench --pairs) the superellipsoid against
                        each FCL shape: error against time per query of ours, FCL's libccd and
                        Bullet, one panel per partner, a point per separation bucket
Needs Debian's python3-matplotlib (scripts/install-deps.sh --bench installs it).
"""
import csv
import json
import math
import os
import sys
from collections import defaultdict

import matplotlib
import matplotlib.ticker

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

FLOOR = 1e-17  # errors of exactly 0 are drawn here on the log axis
STYLE = {  # family: (colour, marker)
    "Exact": ("tab:green", "o"),
    "Paper": ("tab:orange", "s"),
    "Radial": ("tab:gray", "D"),
    "Front end": ("tab:olive", "*"),
    "FCL mesh": ("tab:blue", "^"),
    "FCL GJK convex": ("tab:purple", "v"),
    "FCL GJK ellipsoid": ("tab:red", "P"),
    "Bullet GJK": ("tab:brown", "X"),
}


def geomean(values):
    values = [v for v in values if v is not None and v > 0 and math.isfinite(v)]
    return math.exp(sum(math.log(v) for v in values) / len(values)) if values else float("nan")


def loglog(ax, xlabel, ylabel, title=None):
    """Log-log axes with labels and a light grid."""
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if title:
        ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)


def aggregate(rows):
    """(side, family, setting) -> setting value, mean relative error, geometric-mean time."""
    groups = defaultdict(list)
    for r in rows:
        groups[(r["side"], r["method"], r["setting"])].append(r)
    out = {}
    for key, members in groups.items():
        size = [max(m["a1"], m["a2"], m["a3"]) for m in members]
        err = sum(m["avg_err"] / s for m, s in zip(members, size)) / len(members)
        out[key] = (members[0]["setting_value"], max(err, FLOOR),
                    geomean([m["us_per_query"] for m in members]))
    return out


def plot_pareto(rows, sides, path):
    agg = aggregate(rows)
    cols = min(3, len(sides))
    nrows = math.ceil(len(sides) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(6 * cols, 4.8 * nrows), squeeze=False)
    for ax, side in zip(axes.flat, sides):
        for family, (colour, marker) in STYLE.items():
            pts = sorted((v[0] if v[0] is not None else 0, v[2], v[1], key[2])
                         for key, v in agg.items() if key[0] == side and key[1] == family)
            if not pts:
                continue
            xs, ys = [p[1] for p in pts], [p[2] for p in pts]
            ax.plot(xs, ys, marker=marker, color=colour, label=family, linestyle="-" if len(pts) > 1 else "")
            for x, y, setting in zip(xs, ys, [p[3] for p in pts]):
                if setting:
                    ax.annotate(setting, (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points")
        loglog(ax, "time per query [us] (geometric mean over shapes)", "average |d - d_true| / size",
               side)
    for ax in list(axes.flat)[len(sides):]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=7)
    fig.suptitle("What accuracy costs in time (lower left is better)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def plot_mesh_resolution(rows, sides, path):
    agg = aggregate(rows)
    fig, (ax_err, ax_time) = plt.subplots(1, 2, figsize=(12, 4.8))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, side in enumerate(sides):
        for family, linestyle in (("FCL mesh", "-"), ("FCL GJK convex", "--")):
            pts = sorted((v[0], v[1], v[2]) for key, v in agg.items()
                         if key[0] == side and key[1] == family)
            if pts:
                style = dict(linestyle=linestyle, marker="o", color=colours[k % len(colours)],
                             label=f"{family}, {side}")
                ax_err.plot([p[0] for p in pts], [p[1] for p in pts], **style)
                ax_time.plot([p[0] for p in pts], [p[2] for p in pts], **style)
    for family, setting, colour in (("Exact", "1e-12", "tab:green"), ("Paper", "1e-03", "tab:orange")):
        errs = [v[1] for k, v in agg.items() if k[1] == family and k[2] == setting]
        times = [v[2] for k, v in agg.items() if k[1] == family and k[2] == setting]
        if errs:
            ax_err.axhline(max(errs), color=colour, linestyle=":", label=f"{family} {setting} (worst side)")
            ax_time.axhline(geomean(times), color=colour, linestyle=":", label=f"{family} {setting}")
    for ax, ylabel in ((ax_err, "average |d - d_true| / size"), (ax_time, "time per query [us]")):
        loglog(ax, "vertices of the tessellation", ylabel)
    ax_time.legend(fontsize=6)
    fig.suptitle("FCL on a tessellation: error and time against resolution")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def plot_scaling(csv_path, path):
    """Left: the scene cloud's paths; right: single against batched queries, near and far."""
    series = defaultdict(list)
    with open(csv_path, newline="") as f:
        for r in csv.DictReader(f):
            if r["cloud"] == "scene":
                key = ("scene", f"{r['path']}, {r['threads']} thread(s)")
            elif r["scalar"] == "double":
                key = ("batch", f"{r['cloud']}: {r['path']}, {r['threads']} thread(s)")
            else:
                continue
            series[key].append((int(r["vertices"]), float(r["ns_per_vertex"])))
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.8))
    for ax, panel, title in ((axes[0], "scene", "scene cloud (1 % near the surface), double"),
                             (axes[1], "batch", "all near / all far, double")):
        ax.set_prop_cycle(color=plt.cm.tab20.colors)  # more series than the default 10 colours
        for (p, name), pts in sorted(series.items()):
            if p != panel:
                continue
            pts.sort()
            ax.plot([q[0] for q in pts], [q[1] for q in pts], marker="o", label=name,
                    linestyle="--" if "far" in name else "-")
        loglog(ax, "vertices", "time per vertex [ns]", title)
        ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


PAIR_STYLE = {"ours": ("tab:green", "o"), "fcl-libccd": ("tab:purple", "v"),
              "bullet": ("tab:brown", "X")}


def plot_pairs(csv_path, path):
    """One panel per partner kind: max error × size against µs per query, per bucket."""
    rows = defaultdict(list)
    with open(csv_path, newline="") as f:
        for r in csv.DictReader(f):
            rows[r["kind"]].append(r)
    kinds = list(rows)
    cols = 4
    fig, axes = plt.subplots((len(kinds) + cols - 1) // cols, cols, figsize=(15, 3.3 * math.ceil(len(kinds) / cols)))
    for ax, kind in zip(axes.flat, kinds):
        for method, (colour, marker) in PAIR_STYLE.items():
            for separated in (True, False):
                pts = [(float(r["us_per_query"]), max(float(r["max_error"]), FLOOR))
                       for r in rows[kind] if r["method"] == method
                       and (float(r["bucket"]) > 0) == separated
                       and not math.isnan(float(r["max_error"]))]
                if pts:
                    ax.scatter([p[0] for p in pts], [p[1] for p in pts], color=colour,
                               marker=marker, facecolors=colour if separated else "none",
                               label=f"{method}, {'separated' if separated else 'overlapping'}")
        loglog(ax, "time per query [µs]", "max error × size", kind)
        lo, hi = ax.get_xlim()
        if hi / lo > 10:  # a decade's ticks are labelled
            ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        else:  # within one: four evenly spaced ticks, with the digits their spacing needs
            digits = max(2, math.ceil(math.log10(4 * hi / (hi - lo))) + 1)
            ax.xaxis.set_major_locator(matplotlib.ticker.MaxNLocator(4))
            ax.xaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter(f"%.{digits}g"))
            ax.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
        ax.legend(fontsize=6)
    for ax in list(axes.flat)[len(kinds):]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    written = []
    results = os.path.join(out, "results.json")
    if os.path.exists(results):
        with open(results) as f:
            rows = json.load(f)["rows"]
        sides = list(dict.fromkeys(r["side"] for r in rows))
        plot_pareto(rows, sides, os.path.join(out, "accuracy_vs_time.png"))
        plot_mesh_resolution(rows, sides, os.path.join(out, "mesh_resolution.png"))
        written += ["accuracy_vs_time.png", "mesh_resolution.png"]
    scaling = os.path.join(out, "scaling.csv")
    if os.path.exists(scaling):
        plot_scaling(scaling, os.path.join(out, "scaling.png"))
        written.append("scaling.png")
    pairs = os.path.join(out, "pairs.csv")
    if os.path.exists(pairs):
        plot_pairs(pairs, os.path.join(out, "pairs.png"))
        written.append("pairs.png")
    print(f"Plots written to {out}/: {', '.join(written) if written else 'nothing to plot'}")


if __name__ == "__main__":
    main()
