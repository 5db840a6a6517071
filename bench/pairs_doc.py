#!/usr/bin/python3
"""Writes the shape pairs' results from a run of `fse_bench --pairs N --out OUT`.

    /usr/bin/python3 bench/pairs_doc.py OUT [--docs DOCS] [--readme README.md]

Reads OUT/pairs.txt (the run's printed table), OUT/pairs.csv, OUT/pairs.png (bench/plot.py) and
OUT/commit (the commit the run was built at, recorded by scripts/bench.sh). Prints the results
block; with --docs rewrites the block between `<!-- results:begin -->` and `<!-- results:end -->` in
DOCS/pairs.md and copies the plot to DOCS/bench/pairs.png; with --readme rewrites the README's
block between `<!-- pairs:begin -->` and `<!-- pairs:end -->`. Every figure comes from the run.
"""
import argparse
import csv
import math
import os
import shutil
import sys
from collections import defaultdict


sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
from doc_blocks import replace_block, run_commit  # noqa: E402

GENERATOR = "bench/pairs_doc.py"

def read(path):
    with open(path) as f:
        return f.read()


def readme_table(csv_path):
    """Per partner: ours' worst error and time against libccd's and Bullet's, separated."""
    rows = defaultdict(lambda: defaultdict(list))
    with open(csv_path, newline="") as f:
        for r in csv.DictReader(f):
            rows[r["kind"]][r["method"]].append(r)

    def summary(rs, separated):
        rs = [r for r in rs if (float(r["bucket"]) > 0) == separated]
        if not rs:
            return None, None
        us = sum(float(r["us_per_query"]) for r in rs) / len(rs)
        errors = [float(r["max_error"]) for r in rs]
        return us, (None if any(math.isnan(e) for e in errors) else max(errors))

    def cell(us, err):
        if us is None:
            return "—"
        return f"{us:.1f} µs, {err:.0e}" if err is not None else f"{us:.1f} µs"

    lines = ["| the superellipsoid against | ours, separated | FCL libccd, separated | Bullet, separated | ours, overlapping | FCL libccd, overlapping |",
             "|---|---|---|---|---|---|"]
    for kind, methods in rows.items():
        ours_s = summary(methods["ours"], True)
        ours_o = summary(methods["ours"], False)
        ccd_s = summary(methods.get("fcl-libccd", []), True)
        ccd_o = summary(methods.get("fcl-libccd", []), False)
        bt_s = summary(methods.get("bullet", []), True)
        lines.append(f"| {kind} | {cell(*ours_s)} | {cell(*ccd_s)} | {cell(*bt_s)} | {cell(ours_o[0], None)} | {cell(*ccd_o)} |")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out")
    parser.add_argument("--docs")
    parser.add_argument("--readme")
    args = parser.parse_args()
    table = read(os.path.join(args.out, "pairs.txt")).strip()
    commit = run_commit(args.out)
    stamp = f"_Run at commit {commit}. Command: `scripts/bench.sh --pairs`._"
    body = f"{table}\n\n{stamp}\n\n![error against time per pair](bench/pairs.png)"
    if args.docs:
        os.makedirs(os.path.join(args.docs, "bench"), exist_ok=True)
        png = os.path.join(args.out, "pairs.png")
        if os.path.exists(png):
            shutil.copy(png, os.path.join(args.docs, "bench", "pairs.png"))
        replace_block(os.path.join(args.docs, "pairs.md"), "results", body, GENERATOR)
    else:
        print(body)
    if args.readme:
        replace_block(args.readme, "pairs",
                      f"{readme_table(os.path.join(args.out, 'pairs.csv'))}\n\n"
                      f"Time per query and worst error × size (separated: against the construction); the "
                      f"iterations per distance bucket (the superellipsoid's support evaluations) are in "
                      f"docs/pairs.md. {stamp[1:-1]}", GENERATOR)


if __name__ == "__main__":
    main()
