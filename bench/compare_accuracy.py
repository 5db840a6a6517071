#!/usr/bin/env python3
"""Whether two benchmark runs gave the same answers: every column of results.csv but the timed
ones, and the results of scaling.csv, compared as text (the CSV holds each double to 17 digits,
so equal text is equal bits). For a change that must not change behaviour
(docs/design.md → "Checking a refactoring").

    bench/compare_accuracy.py BEFORE_DIR AFTER_DIR    # directories of fse_bench --out
Exit 0 when our methods' rows agree; else each differing row and column, and exit 1. A peer's
row that differs is listed but does not fail: FCL's libccd on fcl::Ellipsoid reads memory it
did not initialise (its answers move with MALLOC_PERTURB_), so its inside rows can change with
nothing but the heap's history.
"""
import csv
import sys
from pathlib import Path

# Columns that time something (and so differ from run to run).
TIMED = {"us_per_query", "speedup_vs_mesh272", "setup_ms", "total_ms", "ns_per_vertex",
         "vs_single", "paper_us"}
# Rows of peers, not of this library (results.csv's method column).
PEERS = {"FCL mesh", "FCL GJK convex", "FCL GJK ellipsoid", "Bullet GJK"}
# The columns that name a row.
KEYS = {"results.csv": ("side", "shape", "method", "setting"),
        "scaling.csv": ("cloud", "scalar", "vertices", "path", "threads")}


def rows(path, keys):
    with open(path, newline="") as f:
        return {tuple(r[k] for k in keys): r for r in csv.DictReader(f)}


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    before, after = Path(argv[1]), Path(argv[2])
    differences = peer_differences = 0
    for name, keys in KEYS.items():
        a, b = rows(before / name, keys), rows(after / name, keys)
        if a.keys() != b.keys():
            print(f"{name}: different rows: {sorted(set(a) ^ set(b))}")
            differences += 1
            continue
        for key, row in a.items():
            peer = row.get("method") in PEERS
            for column, value in row.items():
                if column not in TIMED and b[key][column] != value:
                    print(f"{'peer ' if peer else ''}{name} {key} {column}: {value} -> "
                          f"{b[key][column]}")
                    if peer:
                        peer_differences += 1
                    else:
                        differences += 1
    if differences:
        print(f"{differences} differences in our rows")
        return 1
    print(f"identical: {', '.join(KEYS)}, every row of ours, every column but the timed ones"
          + (f" ({peer_differences} differences in peers' rows)" if peer_differences else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
