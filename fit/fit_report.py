#!/usr/bin/python3
"""The fitting study's table and plot, from an fse_fit study run:
    /usr/bin/python3 fit/fit_report.py RUN_DIR [--docs DOCS] [--readme README]

RUN_DIR holds study.csv (fse_fit study --out RUN_DIR). Writes RUN_DIR/study.png (or, with
--docs, DOCS/fitting/study.png) and RUN_DIR/results.md (with --docs, the results block of
DOCS/fitting.md instead); with --readme, the README's fitting block.
Needs Debian's python3-matplotlib.
"""
import argparse
import csv
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
from doc_blocks import replace_block, run_commit  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

GENERATOR = "fit/fit_report.py"
ELONGATED_OR_BLOCKY = ("blocky", "elongated", "cylinder-like", "mixed")


def read(run_dir):
    with open(os.path.join(run_dir, "study.csv")) as f:
        lines = f.readlines()
    command = lines[0].lstrip("# ").strip() if lines[0].startswith("#") else "fse_fit study"
    rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    for r in rows:
        for k in ("noise", "outliers", "parameter_error", "centre_error", "radii_error",
                  "exponent_error", "rotation_error", "rms", "shape_error", "seconds"):
            r[k] = float(r[k])
        r["iterations"] = int(r["iterations"])
    cases = {}
    for r in rows:
        cases.setdefault((r["family"], r["view"], r["noise"], r["outliers"]), {})[r["residual"]] = r
    return command, cases


def pct(x):
    return f"{100 * x:g} %"


def table(cases):
    out = ["| shape | view | noise | outliers | exact: RMS / noise | exact: shape error | "
           "radial: shape error | radial / exact | exact: parameter error | time exact / radial "
           "| iterations exact, radial |",
           "|---|---|---|---|---|---|---|---|---|---|---|"]
    for (family, view, noise, outliers), c in cases.items():
        e, r = c["exact"], c["radial"]
        rms = f"{e['rms'] / noise:.3f}" if noise > 0 else f"{e['rms']:.1e} (no noise)"
        ratio = r["shape_error"] / max(e["shape_error"], 1e-300)
        out.append(f"| {family} | {view} | {pct(noise)} | {pct(outliers)} | {rms} | "
                   f"{e['shape_error']:.2e} | {r['shape_error']:.2e} | {ratio:.1f}× | "
                   f"{e['parameter_error']:.1e} | {e['seconds'] / r['seconds']:.2f} "
                   f"({1000 * e['seconds']:.0f} / {1000 * r['seconds']:.0f} ms) | "
                   f"{e['iterations']}, {r['iterations']} |")
    return "\n".join(out)


def targets(cases):
    worst_rms = max((c["exact"]["rms"] / k[2] for k, c in cases.items() if k[2] > 0), default=0)
    noiseless = [c["exact"]["parameter_error"] for k, c in cases.items() if k[2] == 0]
    blocky = [c["radial"]["shape_error"] / max(c["exact"]["shape_error"], 1e-300)
              for k, c in cases.items() if k[0] in ELONGATED_OR_BLOCKY and k[2] > 0]
    times = [c["exact"]["seconds"] / c["radial"]["seconds"] for c in cases.values()]
    median = sorted(times)[len(times) // 2]
    lines = [
        f"- Surface RMS of the exact fit over the noise, worst noisy case: **{worst_rms:.3f}** "
        "(target ≤ 1.1).",
        f"- Without noise, the exact fit's largest parameter error: **{max(noiseless, default=0):.1e}** "
        "(target ≤ 1e-6).",
    ]
    if blocky:
        lines.append(f"- Shape error, radial over exact, on the blocky and elongated families "
                     f"with noise: smallest **{min(blocky):.1f}×**, median "
                     f"{sorted(blocky)[len(blocky) // 2]:.1f}× (target ≥ 2×).")
    lines.append(f"- Time per fit, exact over radial: median **{median:.2f}**, largest "
                 f"{max(times):.2f} (target ≤ 0.5).")
    return "\n".join(lines)


def plot(cases, path):
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.6))
    colours = {}
    palette = plt.get_cmap("tab10")
    for (family, view, noise, outliers), c in cases.items():
        colour = colours.setdefault(family, palette(len(colours)))
        marker = "o" if view == "full" else "^"
        # Cases with outliers hollow.
        style = dict(marker=marker, s=30, alpha=0.85, edgecolors=colour,
                     facecolors="none" if outliers > 0 else colour)
        e, r = c["exact"], c["radial"]
        if noise > 0:  # without noise both fit to rounding (the table)
            left.scatter(r["shape_error"], e["shape_error"], **style)
        right.scatter(1000 * r["seconds"], 1000 * e["seconds"], **style)
    for ax in (left, right):
        ax.set_xscale("log")
        ax.set_yscale("log")
        lo = min(ax.get_xlim()[0], ax.get_ylim()[0])
        hi = max(ax.get_xlim()[1], ax.get_ylim()[1])
        ax.plot([lo, hi], [lo, hi], color="grey", lw=0.8, ls="--", label="equal")
        ax.set_xlim(lo, hi)
        ax.set_ylim(lo, hi)
        ax.grid(True, which="major", alpha=0.3)
    lo, hi = left.get_xlim()
    left.plot([lo, hi], [lo / 2, hi / 2], color="grey", lw=0.8, ls=":")
    left.set_xlabel("radial fit: shape error (× size)")
    left.set_ylabel("exact fit: shape error (× size)")
    left.set_title("Shape error, noisy clouds (dotted: exact 2× smaller)", fontsize=10)
    right.set_xlabel("radial fit, forward differences: ms per fit")
    right.set_ylabel("exact fit, analytic Jacobian: ms per fit")
    right.set_title("Time per fit, every cloud (below the diagonal: exact faster)", fontsize=10)
    handles = [plt.Line2D([], [], color=c, marker="o", ls="", label=f) for f, c in colours.items()]
    handles += [plt.Line2D([], [], color="k", marker="o", ls="", label="full view"),
                plt.Line2D([], [], color="k", marker="^", ls="", label="one side"),
                plt.Line2D([], [], color="k", marker="o", ls="", markerfacecolor="none",
                           label="20 % outliers")]
    fig.legend(handles=handles, fontsize=8, loc="lower center", ncol=len(handles), frameon=False)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    fig.savefig(path, dpi=110)
    print(f"written: {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir")
    parser.add_argument("--docs")
    parser.add_argument("--readme")
    args = parser.parse_args()
    command, cases = read(args.run_dir)
    stamp = f"From `{command}` at commit {run_commit(args.run_dir)}."
    if args.docs:
        os.makedirs(os.path.join(args.docs, "fitting"), exist_ok=True)
        plot(cases, os.path.join(args.docs, "fitting", "study.png"))
        replace_block(os.path.join(args.docs, "fitting.md"), "fit-results",
                      f"{stamp}\n\n{targets(cases)}\n\n{table(cases)}", GENERATOR)
    else:
        plot(cases, os.path.join(args.run_dir, "study.png"))
        with open(os.path.join(args.run_dir, "results.md"), "w") as f:
            f.write(f"{stamp}\n\n{targets(cases)}\n\n{table(cases)}\n")
        print(f"written: {os.path.join(args.run_dir, 'results.md')}")
    if args.readme:
        replace_block(args.readme, "fitting", f"{stamp} ([docs/fitting.md](docs/fitting.md))\n\n"
                      f"{targets(cases)}\n\n![The fitting study](docs/fitting/study.png)", GENERATOR)


if __name__ == "__main__":
    main()
