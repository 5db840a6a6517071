#!/usr/bin/python3
"""Markdown tables of fse_bench's output, for the README: /usr/bin/python3 bench/readme_tables.py OUT

Reads OUT/results.json and OUT/scaling.csv; prints the paper's Tables 1-4 layout, the
accuracy-against-time summary per point distribution, the per-shape speed ratios and the
scaling table, as GitHub markdown.
"""
import csv
import json
import math
import os
import sys
from collections import OrderedDict, defaultdict


def num(v, fmt="{:.3g}"):
    return "-" if v is None or (isinstance(v, float) and math.isnan(v)) else fmt.format(v)


def label(r):
    return r["method"] + (" " + r["setting"] if r["setting"] else "")


def geomean(values):
    values = [v for v in values if v is not None and v > 0]
    return math.exp(sum(map(math.log, values)) / len(values)) if values else None


def paper_tables(rows):
    picks = [("Radial", None), ("Paper", 1e-3), ("Exact", 1e-9), ("Exact", 1e-12), ("FCL mesh", 272)]
    for side, title in (("paper+0.05", "Outside (+0.05), Tables 1 and 3"),
                        ("paper-0.015", "Inside (-0.015), Tables 2 and 4")):
        print(f"\n{title}; errors in mm, times in µs per query:\n")
        print("| shape (ε1; ε2) | method | avg err | σ | max err | Eq. 7 | conv % | err !conv | µs | × mesh 272 | paper: err, conv %, µs |")
        print("|---|---|---|---|---|---|---|---|---|---|---|")
        for shape in OrderedDict.fromkeys(r["shape"] for r in rows if r["side"] == side and r["a1"] == 1 and r["a3"] == 1):
            if not any(r["shape"] == shape and r.get("paper_us") for r in rows):
                continue
            for family, value in picks:
                for r in rows:
                    if r["side"] == side and r["shape"] == shape and r["method"] == family and (
                            value is None or r["setting_value"] == value):
                        paper = ""
                        if family == "Paper":
                            paper = f"{num(r['paper_avg_err_mm'])}, {num(r['paper_converged_pct'], '{:.4g}')}, {num(r['paper_us'])}"
                        elif family == "FCL mesh":
                            paper = f"mesh: {num(r['paper_us'])} µs"
                        print(f"| {shape} | {label(r)} | {num(1e3 * r['avg_err'])} | {num(1e3 * r['sigma_err'])} | "
                              f"{num(1e3 * r['max_err'])} | {num(1e3 * r['avg_error_estimate']) if r['avg_error_estimate'] is not None else '-'} | {num(r['converged_pct'], '{:.4g}')} | {num(1e3 * r['nonconv_err'])} | "
                              f"{r['us_per_query']:.2f} | {r['speedup_vs_mesh272']:.1f} | {paper} |")


def summary(rows):
    for side in OrderedDict.fromkeys(r["side"] for r in rows):
        print(f"\n`{side}`:\n")
        print("| method | avg err / size | max err / size | point err / size | conv % | failed | µs / query | × mesh 272 | bytes |")
        print("|---|---|---|---|---|---|---|---|---|")
        groups = OrderedDict()
        for r in rows:
            if r["side"] == side:
                groups.setdefault(label(r), []).append(r)
        for name, members in groups.items():
            size = [max(m["a1"], m["a2"], m["a3"]) for m in members]
            avg = sum(m["avg_err"] / s for m, s in zip(members, size)) / len(members)
            worst = max(m["max_err"] / s for m, s in zip(members, size))
            point = sum(m["avg_point_err"] / s for m, s in zip(members, size)) / len(members)
            conv = [m["converged_pct"] for m in members if m["converged_pct"] is not None]
            print(f"| {name} | {avg:.1e} | {worst:.1e} | {point:.1e} | {num(sum(conv) / len(conv), '{:.4g}') if conv else '-'} | "
                  f"{sum(m['failed'] for m in members)} | {geomean([m['us_per_query'] for m in members]):.2f} | "
                  f"{num(geomean([m['speedup_vs_mesh272'] for m in members]), '{:.2f}')} | {max(m['memory_bytes'] for m in members)} |")


def ratios(rows):
    sides = list(OrderedDict.fromkeys(r["side"] for r in rows))
    shapes = list(OrderedDict.fromkeys(r["shape"] for r in rows))
    def find(shape, side, family, value):
        for r in rows:
            if r["shape"] == shape and r["side"] == side and r["method"] == family and r["setting_value"] == value:
                return r
    for title, fn in (
            ("Speedup of Exact (1e-12) over FCL's 272-vertex mesh", lambda sh, si: find(sh, si, "Exact", 1e-12)["speedup_vs_mesh272"]),
            ("Time of Exact at 1e-9 / Paper at 1e-3", lambda sh, si: find(sh, si, "Exact", 1e-9)["us_per_query"] / find(sh, si, "Paper", 1e-3)["us_per_query"])):
        print(f"\n{title}:\n")
        print("| shape | " + " | ".join(sides) + " |")
        print("|---" * (len(sides) + 1) + "|")
        for shape in shapes:
            print(f"| {shape} | " + " | ".join(f"{fn(shape, side):.2f}" for side in sides) + " |")


def scaling(path):
    print("\n| cloud | scalar | vertices | path | threads | BVH ms | query ms | ns / vertex | result "
          "| × single | SIMD |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            ratio = float(r["vs_single"])
            share = float(r["simd_share"])
            print(f"| {r['cloud']} | {r['scalar']} | {r['vertices']} | {r['path']} | {r['threads']} | "
                  f"{float(r['setup_ms']):.1f} | {float(r['total_ms']):.2f} | {float(r['ns_per_vertex']):.0f} | "
                  f"{float(r['result']):.6g} | {f'{ratio:.2f}' if ratio > 0 else ''} | "
                  f"{f'{100 * share:.1f} %' if share >= 0 else ''} |")


def batch_summary(path):
    """Per-vertex cost of single queries and the batched query (SIMD, 1 and all threads) on the
    near and far clouds, by size, with the speed-up over single queries from the same run."""
    cost = defaultdict(dict)
    sizes = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            if r["cloud"] not in ("near", "far"):
                continue
            n = int(r["vertices"])
            if n not in sizes:
                sizes.append(n)
            key = (r["cloud"], r["scalar"], r["path"], int(r["threads"]))
            cost[key][n] = float(r["ns_per_vertex"])
    print("\n| cloud | scalar | path | " + " | ".join(f"{n:,} v" for n in sizes) + " |")
    print("|---" * (3 + len(sizes)) + "|")
    for cloud in ("near", "far"):
        for scalar in ("double", "float"):
            single = cost[(cloud, scalar, "single queries (sum)", 1)]
            print(f"| {cloud} | {scalar} | single queries | "
                  + " | ".join(f"{single[n]:.0f} ns" for n in sizes) + " |")
            for threads in (1, 2):
                row = cost.get((cloud, scalar, "batch distance (sum)", threads), {})
                cells = [f"{row[n]:.0f} ns ({single[n] / row[n]:.1f}×)" if n in row else "—"
                         for n in sizes]
                print(f"| {cloud} | {scalar} | batch, SIMD, {threads} thread{'s' if threads > 1 else ''} | "
                      + " | ".join(cells) + " |")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    results = os.path.join(out, "results.json")
    if os.path.exists(results):
        with open(results) as f:
            doc = json.load(f)
        print(f"Machine: {doc['meta']['machine']}; {doc['meta']['points']} points, "
              f"{doc['meta']['reference_points']} reference points, {doc['meta']['repetitions']} repetitions")
        rows = doc["rows"]
        paper_tables(rows)
        summary(rows)
        ratios(rows)
    if os.path.exists(os.path.join(out, "scaling.csv")):
        scaling(os.path.join(out, "scaling.csv"))
        batch_summary(os.path.join(out, "scaling.csv"))


if __name__ == "__main__":
    main()
