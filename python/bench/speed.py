#!/usr/bin/env python3
"""The Python module's speed, against the C++ library and Open3D, in one run.

    scripts/bench.sh --python          (or: PYTHONPATH=build/python /usr/bin/python3
                                        python/bench/speed.py --baseline build/python/fse_python_baseline)

For each shape, on the same points:
  - batched queries from Python (signed_distance on an (N, 3) array) against batchDistance called
    from C++ (cpp_baseline.cpp), as a ratio of rates; rounds alternate the two;
  - a one-point call from Python against pointDistance from C++: the difference per call;
  - Open3D's RaycastingScene.compute_signed_distance on the shape's tessellation (272 and 5,000
    vertices), float32 as Open3D takes it: time per point on a cloud in and around the shape,
    and worst error on points at known distances, beside ours (the exact method and the
    paper's).
Writes RUN_DIR/python_speed.json and the figure RUN_DIR/python_speed.png; with --docs, the
results block of docs/python.md and docs/bench/python_speed.png.
"""
import argparse
import json
import os
import pathlib
import shutil
import subprocess
import sys
import time

import numpy as np

import fcl_superellipsoid as fse

ROOT = pathlib.Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
import doc_blocks  # noqa: E402

SHAPES = [
    ("rounded box", (1.0, 0.8, 0.6), (0.3, 0.3)),
    ("the paper's shape", (3.5, 3.0, 2.0), (0.4, 0.3)),
    ("pointed", (1.0, 2.0, 1.5), (1.7, 1.5)),
]


def best(reps, f):
    times = []
    for _ in range(reps):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return min(times)


def cloud(shape, n, seed):
    """Points in the shape's bounding box grown by half its size: inside, near and outside."""
    rng = np.random.default_rng(seed)
    return rng.uniform(-1, 1, size=(n, 3)) * (shape.radii + 0.5 * shape.size)


def constructed(shape, n, seed):
    """Points at known distances outside: support points moved out along their normal by up to
    half the size (their nearest surface point is the support point: the shape is convex)."""
    rng = np.random.default_rng(seed)
    u = rng.normal(size=(n, 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    d = rng.uniform(0.0, 0.5, size=n) * shape.size
    return shape.support(u) + d[:, None] * u, d


def cpp_baseline(baseline, points, radii, exponents, reps, work):
    path = work / "points.bin"
    np.ascontiguousarray(points, dtype=np.float64).tofile(path)
    out = subprocess.run([baseline, str(path), *map(str, radii), *map(str, exponents), str(reps)],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def open3d_peer(shape, num_vertices, points32, reps):
    import open3d as o3d

    vertices, faces = shape.tessellate(num_vertices)
    scene = o3d.t.geometry.RaycastingScene()
    scene.add_triangles(o3d.core.Tensor(vertices.astype(np.float32)),
                        o3d.core.Tensor(faces.astype(np.uint32)))
    query = o3d.core.Tensor(points32)
    scene.compute_signed_distance(query)  # builds the scene's BVH
    seconds = best(reps, lambda: scene.compute_signed_distance(query))
    return seconds, scene.compute_signed_distance(query).numpy().astype(np.float64)


def measure(baseline, sizes, reps, rounds, work):
    rows = []
    for name, radii, exponents in SHAPES:
        shape = fse.Superellipsoid(radii, exponents)
        row = {"shape": name, "radii": radii, "exponents": exponents, "batch": []}
        for n in sizes:
            points = cloud(shape, n, seed=n)
            python_times, cpp_times, python_1, cpp_1 = [], [], [], []
            for _ in range(rounds):  # alternate, so both see the same machine
                c = cpp_baseline(baseline, points, radii, exponents, reps, work)
                cpp_times.append(c["batch"])
                cpp_1.append(c["batch_1_thread"])
                python_times.append(best(reps, lambda: shape.signed_distance(points)) / n * 1e9)
                python_1.append(best(reps, lambda: shape.signed_distance(points, threads=1)) /
                                n * 1e9)
            row["batch"].append({"n": n, "python_ns": min(python_times), "cpp_ns": min(cpp_times),
                                 "python_1_thread_ns": min(python_1), "cpp_1_thread_ns": min(cpp_1)})
        # One point per call: a Python loop over (3,) rows against a C++ loop over columns.
        points = cloud(shape, 20000, seed=7)
        rows_of = list(points)
        c = cpp_baseline(baseline, points, radii, exponents, reps, work)
        f = shape.signed_distance
        python_single = best(reps, lambda: [f(p) for p in rows_of]) / len(rows_of) * 1e9
        row["single"] = {"python_ns": python_single, "cpp_ns": c["single"]}
        rows.append(row)
    # Accuracy on constructed points (their distances known exactly), and Open3D's: after every
    # Python-against-C++ figure, so that Open3D's worker threads cannot weigh on those.
    for (name, radii, exponents), row in zip(SHAPES, rows):
        shape = fse.Superellipsoid(radii, exponents)
        timed = cloud(shape, 20000, seed=8)  # inside, near and outside: what is timed
        p, d = constructed(shape, 20000, seed=9)  # known distances: what the errors are of
        row["methods"] = []
        for method in ("exact", "paper"):
            seconds = best(reps, lambda: shape.signed_distance(timed, method=method))
            error = np.max(np.abs(shape.signed_distance(p, method=method) - d)) / shape.size
            row["methods"].append({"name": f"ours, {method}", "ns": seconds / len(timed) * 1e9,
                                   "error": float(error)})
        for num_vertices in (272, 5000):
            seconds, _ = open3d_peer(shape, num_vertices, timed.astype(np.float32), reps)
            _, o3d_distance = open3d_peer(shape, num_vertices, p.astype(np.float32), 1)
            error = np.max(np.abs(o3d_distance - d)) / shape.size
            row["methods"].append({"name": f"Open3D, {num_vertices} vertices",
                                   "ns": seconds / len(timed) * 1e9, "error": float(error)})
        print(f"measured: {name}", flush=True)
    return rows


def table(rows, commit):
    lines = ["| shape | N | Python / C++ batched rate (all threads) | (1 thread) | "
             "one-point call: Python − C++ |",
             "|---|---|---|---|---|"]
    for row in rows:
        for k, b in enumerate(row["batch"]):
            single = (f"{(row['single']['python_ns'] - row['single']['cpp_ns']) / 1000:.2f} µs "
                      f"({row['single']['python_ns'] / 1000:.2f} vs "
                      f"{row['single']['cpp_ns'] / 1000:.2f})") if k == 0 else ""
            lines.append(f"| {row['shape'] if k == 0 else ''} | {b['n']:,} | "
                         f"{b['cpp_ns'] / b['python_ns']:.1%} ({b['python_ns']:.0f} vs "
                         f"{b['cpp_ns']:.0f} ns/point) | "
                         f"{b['cpp_1_thread_ns'] / b['python_1_thread_ns']:.1%} | {single} |")
    lines += ["", "| shape | method | ns per point | worst error / size |", "|---|---|---|---|"]
    for row in rows:
        for k, m in enumerate(row["methods"]):
            lines.append(f"| {row['shape'] if k == 0 else ''} | {m['name']} | {m['ns']:.0f} | "
                         f"{m['error']:.0e} |")
    lines += ["", f"_Run at commit {commit}; {os.cpu_count()} hardware threads, SIMD "
              f"{fse.simd_instruction_set}; Open3D and ours on every thread; times per point on "
              f"20,000 points in the shape's bounding box grown by half its size (inside, near "
              f"and outside), errors on 20,000 points at known distances outside. Command: "
              f"`scripts/bench.sh --python`._"]
    return "\n".join(lines)


def plot(rows, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    markers = {"ours, exact": "o", "ours, paper": "s", "Open3D, 272 vertices": "^",
               "Open3D, 5000 vertices": "v"}
    colors = ["tab:blue", "tab:orange", "tab:green"]
    figure, ax = plt.subplots(figsize=(7, 4.5))
    for row, color in zip(rows, colors):
        for m in row["methods"]:
            ax.loglog(m["ns"], max(m["error"], 1e-17), markers[m["name"]], color=color,
                      markersize=8)
    for name, marker in markers.items():
        ax.plot([], [], marker, color="gray", label=name)
    for row, color in zip(rows, colors):
        ax.plot([], [], "-", color=color, label=row["shape"])
    ax.set_xlabel("ns per point, batched from Python (every thread)")
    ax.set_ylabel("worst |distance error| / size")
    ax.set_title("Signed distance from Python: accuracy against time")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8, loc="center right")
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", required=True, help="the fse_python_baseline program")
    parser.add_argument("--out", default="out/python", help="run directory")
    parser.add_argument("--quick", action="store_true", help="N = 1e4 only, fewer repetitions")
    parser.add_argument("--docs", help="write the results block of DOCS/python.md and its figure")
    args = parser.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    sizes, reps, rounds = ([10000], 5, 2) if args.quick else ([10000, 100000], 15, 4)
    rows = measure(args.baseline, sizes, reps, rounds, out)
    (out / "python_speed.json").write_text(json.dumps(rows, indent=1))
    text = table(rows, doc_blocks.run_commit(str(out)))
    print(text)
    plot(rows, out / "python_speed.png")
    print(f"written: {out / 'python_speed.png'}")
    if args.docs:
        docs = pathlib.Path(args.docs)
        doc_blocks.replace_block(str(docs / "python.md"), "python-speed", text,
                                 "python/bench/speed.py")
        (docs / "bench").mkdir(exist_ok=True)
        shutil.copy(out / "python_speed.png", docs / "bench" / "python_speed.png")


if __name__ == "__main__":
    main()
