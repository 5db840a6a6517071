#!/usr/bin/python3
"""Tables, plots and pictures of fse_sim runs (cloth and rigid-body scenes):
    /usr/bin/python3 sim/scene_report.py RUN_DIR... [--docs DOCS] [--readme README]

Each RUN_DIR is an fse_sim --out directory (run.json, <model>/steps.csv, <model>/frames/*.obj,
shapes.obj). Writes, into DOCS/scenes/ (default: each RUN_DIR itself):
  step_time_<scene>.png    time per step over simulated time, every model and the peer
                           (the paper's Figure 11)
  penetration_<scene>.png  deepest vertex inside the shape over time, with the tolerance
  cloth_<scene>.png        the cloth on the shape at the snapshot times (exact model)
  bodies_<scene>.png       a rigid-body scene's bodies in the bowl at the snapshot times
and, without --docs, RUN_DIR/results.md (the tables, generated here; with --docs, rewrites
the results block of DOCS/scenes.md instead), and with --readme the README's scenes block
(between `<!-- scenes:begin -->` and `<!-- scenes:end -->`; rigid-body scenes in its second
table).
Needs Debian's python3-matplotlib, and povray for the pictures (a ray tracer: a cloth that lies on
a shape hides it where it covers it).
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "scripts"))
from doc_blocks import replace_block, run_commit  # noqa: E402

GENERATOR = "sim/scene_report.py"

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The paper's Tables 5 and 6 (ms per step, its case-study machine).
PAPER = {
    3240: {"integration": 0.025, "position_constraints": 2.423, "velocity_constraints": 0.914,
           "collision_detection": 4.170, "velocity_update": 1.540, "total": 9.170},
    6460: {"integration": 0.066, "position_constraints": 5.324, "velocity_constraints": 1.544,
           "collision_detection": 7.509, "velocity_update": 1.599, "total": 16.231},
}
# The paper's Table 7 (50 rigid superellipsoids in a bowl, ms per step, its machine). Its
# "position constraints" row is the closest to our contact constraints.
PAPER_RIGID = {"integration": 0.018, "position_constraints": 0.001, "velocity_constraints": 0.119,
               "collision_detection": 5.520, "velocity_update": 3.257, "total": 8.922}
PHASES = [("integration", "time integration"), ("position_constraints", "position constraints"),
          ("contact_constraints", "contact constraints (ours)"),
          ("velocity_constraints", "velocity constraints"),
          ("collision_detection", "collision detection"), ("velocity_update", "velocity update"),
          ("total", "total")]
STYLE = {"exact": "tab:green", "paper": "tab:orange", "mesh": "tab:blue", "bullet": "tab:brown",
         "vertices": "tab:purple"}
LABEL = {"exact": "ours, Exact", "paper": "ours, paper's method", "mesh": "ours, FCL mesh",
         "bullet": "Bullet soft body", "vertices": "ours, vertices (Exact)"}
RIGID_LABEL = {"exact": "exact pairs", "vertices": "vertices, Exact solver",
               "paper": "vertices, paper's method", "mesh": "FCL mesh–mesh",
               "bullet": "Bullet rigid bodies"}
# A body counts as moving while a point of it is faster than this (m/s).
REST_SPEED = 0.1


def read_steps(path):
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def read_obj(path):
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if not parts:
                continue
            if parts[0] == "v":
                vertices.append(tuple(float(x) for x in parts[1:4]))
            elif parts[0] == "f":
                faces.append(tuple(int(x.split("/")[0]) - 1 for x in parts[1:4]))
    return vertices, faces


def fmt(x, digits=3):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return ""
    if x == 0:
        return "0"
    if abs(x) < 1e-3 or abs(x) >= 1e4:
        return f"{x:.1e}"
    return f"{x:.{digits}f}"


def plot_series(run_dir, run, column, ylabel, path, log=False, tolerance=None):
    fig, ax = plt.subplots(figsize=(8, 4.2))
    for summary in run["runs"]:
        model = summary["model"]
        steps = read_steps(os.path.join(run_dir, model, "steps.csv"))
        ax.plot([s["time"] for s in steps], [max(s[column], 1e-18) if log else s[column] for s in steps],
                color=STYLE.get(model), label=label(run, model), linewidth=0.9)
    if tolerance:
        ax.axhline(tolerance, color="black", linestyle="--", linewidth=0.8, label="collision tolerance")
    if log:
        ax.set_yscale("log")
    ax.set_xlabel("simulated time (s)")
    ax.set_ylabel(ylabel)
    ax.set_title(title(run))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def title(run):
    s = run["scene"]
    if s.get("kind") == "rigid":
        return f"{s['name']}: {s['bodies']} bodies, bowl of {s['bowl_vertices']:,} vertices"
    return f"{s['name']}: {s['vertices']} vertices"


def label(run, model):
    rigid = run["scene"].get("kind") == "rigid"
    return (RIGID_LABEL if rigid else LABEL).get(model, model)


def pov_vector(v):
    """A point in POV-Ray's frame: it is left-handed with y up, ours right-handed with z up, so
    y and z trade places (which also turns the handedness)."""
    return f"<{v[0]:.6g},{v[2]:.6g},{v[1]:.6g}>"


def pov_mesh(vertices, faces, colour):
    """A mesh2 object of triangles (faces of more than 3 vertices as fans)."""
    triangles = [(f[0], f[k], f[k + 1]) for f in faces for k in range(1, len(f) - 1)]
    return ("mesh2 {\n vertex_vectors { " + str(len(vertices)) + ",\n  "
            + ",\n  ".join(pov_vector(v) for v in vertices) + " }\n"
            + " face_indices { " + str(len(triangles)) + ",\n  "
            + ",\n  ".join(f"<{a},{b},{c}>" for a, b, c in triangles) + " }\n"
            + f" texture {{ pigment {{ rgb <{colour[0]},{colour[1]},{colour[2]}> }}"
            + " finish { ambient 0.25 diffuse 0.75 specular 0.15 roughness 0.05 } }\n}\n")


def render(meshes, centre, extent, elev, azim, path, size=(640, 480)):
    """Renders `meshes` ((vertices, faces, colour) each) with POV-Ray, a ray tracer: every pixel
    shows the surface nearest the eye, so a cloth that lies on a shape hides it wherever it
    covers it. The camera looks at `centre` from the elevation and azimuth given (degrees, as
    matplotlib's view_init), far enough to see a ball of radius `extent` whole."""
    e, a = math.radians(elev), math.radians(azim)
    direction = (math.cos(e) * math.cos(a), math.cos(e) * math.sin(a), math.sin(e))
    distance = 3.2 * extent
    eye = [centre[k] + distance * direction[k] for k in range(3)]
    light = [centre[k] + distance * (direction[k] + (0.0, 0.0, 1.2)[k]) for k in range(3)]
    scene = ("#version 3.7;\nglobal_settings { assumed_gamma 1.0 }\nbackground { rgb 1 }\n"
             f"camera {{ perspective location {pov_vector(eye)} look_at {pov_vector(centre)} "
             f"right x*{size[0]}/{size[1]} angle 40 }}\n"
             f"light_source {{ {pov_vector(light)} rgb 1.0 }}\n"
             f"light_source {{ {pov_vector(eye)} rgb 0.35 shadowless }}\n"
             + "".join(pov_mesh(v, f, c) for v, f, c in meshes))
    with tempfile.TemporaryDirectory() as tmp:
        pov = os.path.join(tmp, "scene.pov")
        with open(pov, "w") as f:
            f.write(scene)
        subprocess.run(["povray", f"+I{pov}", f"+O{path}", f"+W{size[0]}", f"+H{size[1]}",
                        "+FN", "+A0.1", "-D", "-V", "-GA"], check=True, cwd=tmp,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def offset(vertices, faces, centre, distance):
    """The cloth moved by `distance` along its vertex normals, away from `centre` (the shape's):
    drawn with the scene's contact tolerance as its thickness. Its vertices rest on the curved
    surface, so its flat triangles dip below it between them, and the shape's facets would show
    through a cloth that lies on it."""
    normals = [[0.0, 0.0, 0.0] for _ in vertices]
    for f in faces:
        for k in range(1, len(f) - 1):
            a, b, c = (vertices[i] for i in (f[0], f[k], f[k + 1]))
            u = [b[j] - a[j] for j in range(3)]
            w = [c[j] - a[j] for j in range(3)]
            n = (u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0])
            for i in (f[0], f[k], f[k + 1]):
                for j in range(3):
                    normals[i][j] += n[j]
    out = []
    for v, n in zip(vertices, normals):
        length = math.sqrt(sum(x * x for x in n)) or 1.0
        sign = 1.0 if sum(n[j] * (v[j] - centre[j]) for j in range(3)) >= 0 else -1.0
        out.append(tuple(v[j] + sign * distance * n[j] / length for j in range(3)))
    return out


def plot_frames(frames_dir, frames, path, suptitle, draw):
    """One rendered panel per snapshot file, three to a row, titled by its time; draw(file, png)
    renders a panel."""
    cols = min(3, len(frames))
    rows = math.ceil(len(frames) / cols)
    fig = plt.figure(figsize=(4.8 * cols, 3.9 * rows))
    with tempfile.TemporaryDirectory() as tmp:
        for k, name in enumerate(frames):
            png = os.path.join(tmp, f"{k}.png")
            draw(os.path.join(frames_dir, name), png)
            ax = fig.add_subplot(rows, cols, k + 1)
            ax.imshow(plt.imread(png))
            ax.set_axis_off()
            t = float(name.split("_")[1].rsplit(".", 1)[0])
            ax.set_title(f"t = {t:g} s", fontsize=10)
    fig.suptitle(suptitle)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def plot_pictures(run_dir, run, path, model="exact"):
    frames_dir = os.path.join(run_dir, model, "frames")
    if not os.path.isdir(frames_dir):
        return False
    frames = sorted(f for f in os.listdir(frames_dir) if f.startswith("cloth_"))
    if not frames:
        return False
    shape = read_obj(os.path.join(run_dir, "shapes.obj"))
    centre = [sum(v[k] for v in shape[0]) / len(shape[0]) for k in range(3)]
    tolerance = run["scene"].get("tolerance") or 0.0  # the contact tolerance (collision)

    def draw(frame, png):
        cloth_v, cloth_f = read_obj(frame)
        render([(*shape, (0.55, 0.65, 0.82)),
                (offset(cloth_v, cloth_f, centre, tolerance), cloth_f, (0.80, 0.30, 0.28))],
               (0.0, 0.0, -0.3), 7.5, 25, -60, png)

    plot_frames(frames_dir, frames, path, f"{run['scene']['name']} ({LABEL.get(model, model)})",
                draw)
    return True


def plot_bodies(run_dir, run, path, model="exact"):
    """The bodies in the bowl at the snapshot times (a section through the bowl's far half)."""
    frames_dir = os.path.join(run_dir, model, "frames")
    if not os.path.isdir(frames_dir) or not os.path.exists(os.path.join(run_dir, "bowl.obj")):
        return False
    frames = sorted(f for f in os.listdir(frames_dir) if f.startswith("bodies_"))
    if not frames:
        return False
    bowl_v, bowl_f = read_obj(os.path.join(run_dir, "bowl.obj"))
    # The far half of the bowl's faces (y > 0), so that the bodies inside are seen.
    bowl_half = [f for f in bowl_f if all(bowl_v[i][1] > 0 for i in f)]
    lo = [min(v[k] for v in bowl_v) for k in range(3)]
    hi = [max(v[k] for v in bowl_v) for k in range(3)]

    def draw(frame, png):
        body_v, body_f = read_obj(frame)
        top = max(hi[2], max(v[2] for v in body_v))
        centre = (0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + top))
        extent = 0.5 * math.dist((lo[0], lo[1], lo[2]), (hi[0], hi[1], top))
        render([(bowl_v, bowl_half, (0.78, 0.78, 0.80)), (body_v, body_f, (0.85, 0.45, 0.25))],
               centre, extent, 20, -90, png)

    plot_frames(frames_dir, frames, path, f"{run['scene']['name']} ({label(run, model)})", draw)
    return True


def rest_time(steps):
    """The end of the last step in which a body point moved faster than REST_SPEED (s)."""
    moving = [s["time"] for s in steps if s["max_speed"] > REST_SPEED]
    return moving[-1] if moving else 0.0


def phase_table(run, runs, models, paper):
    """The ms-per-phase table's lines: the paper's column, then each model's; a phase no run
    has and the paper does not list is left out."""
    head = "| ms per step | paper (its machine) | " + " | ".join(label(run, m) for m in models) + " |"
    lines = [head, "|---" * (2 + len(models)) + "|"]
    for key, name in PHASES:
        cells = [fmt(runs[m]["mean_ms"].get(key)) for m in models]
        if not any(cells) and key not in paper:
            continue
        lines.append(f"| {name} | {fmt(paper.get(key))} | " + " | ".join(cells) + " |")
    return lines


def rigid_tables(run_dir, run):
    """The paper's Table 7 layout with its values beside ours, and what each model got right."""
    runs = {r["model"]: r for r in run["runs"]}
    models = [m for m in ("exact", "vertices", "paper", "mesh", "bullet") if m in runs]
    lines = phase_table(run, runs, models, PAPER_RIGID)
    tol = run["scene"]["tolerance"]
    acc = ["| measured on the exact surfaces | " + " | ".join(label(run, m) for m in models) + " |",
           "|---" * (1 + len(models)) + "|"]
    steps = {m: read_steps(os.path.join(run_dir, m, "steps.csv")) for m in models}
    acc.append("| deepest interpenetration, any step (m) | " + " | ".join(fmt(runs[m]["max_penetration"]) for m in models) + " |")
    acc.append(f"| steps with interpenetration above the tolerance ({tol:g} m) | " + " | ".join(
        f"{sum(s['max_penetration'] > tol for s in steps[m])} of {len(steps[m])}" for m in models) + " |")
    acc.append("| deepest interpenetration after 5 s (m) | " + " | ".join(
        fmt(max([s["max_penetration"] for s in steps[m] if s["time"] > 5] or [0.0])) for m in models) + " |")
    acc.append("| bodies inside the bowl at the end | " + " | ".join(
        f"{runs[m].get('bodies_inside', '?')} of {runs[m].get('bodies', '?')}" for m in models) + " |")
    acc.append(f"| at rest (every point slower than {REST_SPEED:g} m/s) from (s) | " + " | ".join(
        fmt(rest_time(steps[m]), 2) for m in models) + " |")
    acc.append("| fastest body point at the end (m/s) | " + " | ".join(fmt(runs[m]["final_max_speed"]) for m in models) + " |")
    return "\n".join(lines), "\n".join(acc), steps


def rigid_section(run_dir, run, target, rel, name):
    tol = run["scene"]["tolerance"]
    plot_series(run_dir, run, "total_ms", "ms per step", os.path.join(target, f"step_time_{name}.png"), log=True)
    plot_series(run_dir, run, "max_penetration", "deepest interpenetration (m)",
                os.path.join(target, f"penetration_{name}.png"), log=True, tolerance=tol)
    pictures = plot_bodies(run_dir, run, os.path.join(target, f"bodies_{name}.png"))
    timing, accuracy, steps = rigid_tables(run_dir, run)
    s = run["scene"]
    runs = {r["model"]: r for r in run["runs"]}
    ratios = []
    for other in ("vertices", "mesh", "bullet"):
        if "exact" in runs and other in runs:
            ms = lambda m, phase: runs[m]["mean_ms"][phase]
            ratios.append(f"exact pairs / {label(run, other)}: step {ms('exact', 'total') / ms(other, 'total'):.2f}, "
                          f"collision detection {ms('exact', 'collision_detection') / ms(other, 'collision_detection'):.2f}")
    ratio = ("Ratios in this run: " + "; ".join(ratios) + ".") if ratios else ""
    section = [f"### {name}: {s['bodies']} rigid superellipsoids, a bowl of {s['bowl_vertices']:,} vertices",
               "", f"Bodies of {s['body_mesh_vertices']} vertices (the vertex and mesh models); step {s['step']:.5g} s, "
               f"{s['substeps']} substeps, {s['duration']:g} s simulated, tolerance {tol:g} m; effects: "
               f"{', '.join(s['effects'])}.", "", timing, "", accuracy, "", ratio, "",
               f"![step time]({rel}step_time_{name}.png)", "",
               f"![interpenetration]({rel}penetration_{name}.png)", ""]
    if pictures:
        section += [f"![the bodies]({rel}bodies_{name}.png)", ""]
    row = None
    if "exact" in runs:
        ms = lambda m, phase: runs[m]["mean_ms"].get(phase) if m in runs else None
        row = (f"| {name} | {fmt(ms('exact', 'total'))} / {fmt(ms('exact', 'collision_detection'))} | "
               f"{fmt(ms('vertices', 'total'))} / {fmt(ms('vertices', 'collision_detection'))} | "
               f"{fmt(ms('paper', 'total'))} / {fmt(ms('paper', 'collision_detection'))} | "
               f"{fmt(ms('mesh', 'total'))} / {fmt(ms('mesh', 'collision_detection'))} | "
               f"{fmt(ms('bullet', 'total'))} / {fmt(ms('bullet', 'collision_detection'))} | "
               f"{fmt(PAPER_RIGID['total'])} / {fmt(PAPER_RIGID['collision_detection'])} | "
               f"{fmt(runs['exact']['max_penetration'])} / "
               f"{fmt(max([x['max_penetration'] for x in steps['exact'] if x['time'] > 5] or [0.0]))} | "
               f"{runs['exact'].get('bodies_inside')} of {runs['exact'].get('bodies')} |")
    return "\n".join(section), row


def tables(run):
    """The paper's Table 5/6 layout with its values beside ours, and the accuracy table."""
    n = run["scene"]["vertices"]
    paper = PAPER.get(n, {})
    runs = {r["model"]: r for r in run["runs"]}
    models = [m for m in ("exact", "paper", "mesh", "bullet") if m in runs]
    lines = phase_table(run, runs, models, paper)
    if "collision_detection" in runs.get("exact", {}).get("mean_ms", {}):
        ex = runs["exact"]["mean_ms"]
        lines.append(f"| collision / total | {fmt(100 * paper['collision_detection'] / paper['total'], 0) + ' %' if paper else ''} | "
                     + " | ".join((fmt(100 * runs[m]['mean_ms']['collision_detection'] / runs[m]['mean_ms']['total'], 0) + " %")
                                  if "collision_detection" in runs[m]["mean_ms"] else "" for m in models) + " |")
    acc = ["| accuracy (against the exact surface) | " + " | ".join(LABEL[m] for m in models) + " |",
           "|---" * (1 + len(models)) + "|"]
    acc.append("| deepest vertex inside, any step (m) | " + " | ".join(fmt(runs[m]["max_penetration"]) for m in models) + " |")
    acc.append("| contact vertices' distance to the surface, mean (m) | " + " | ".join(
        fmt(runs[m]["contact_error_mean"]) if m != "bullet" else "" for m in models) + " |")
    acc.append("| the same, worst (m) | " + " | ".join(
        fmt(runs[m]["contact_error_max"]) if m != "bullet" else "" for m in models) + " |")
    acc.append("| first contact (s) | " + " | ".join(
        fmt(runs[m]["first_contact_time"], 2) if m != "bullet" else "" for m in models) + " |")
    acc.append("| largest edge strain | " + " | ".join(
        fmt(runs[m]["max_edge_strain"]) if m != "bullet" else "" for m in models) + " |")
    acc.append("| fastest vertex at the end (m/s) | " + " | ".join(
        fmt(runs[m]["final_max_speed"]) if m != "bullet" else "" for m in models) + " |")
    return "\n".join(lines), "\n".join(acc)


def ratios(run):
    runs = {r["model"]: r for r in run["runs"]}
    out = []
    if "exact" in runs and "paper" in runs:
        out.append(f"collision detection, Exact / paper's method: "
                   f"{runs['exact']['mean_ms']['collision_detection'] / runs['paper']['mean_ms']['collision_detection']:.2f}")
    if "exact" in runs and "bullet" in runs:
        out.append(f"step, Exact / Bullet: {runs['exact']['mean_ms']['total'] / runs['bullet']['mean_ms']['total']:.3f}")
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+")
    parser.add_argument("--docs")
    parser.add_argument("--readme")
    args = parser.parse_args()
    sections, headline, rigid_rows = [], [], []
    commits = {}
    for run_dir in args.runs:
        with open(os.path.join(run_dir, "run.json")) as f:
            run = json.load(f)
        name = run["scene"]["name"] or os.path.basename(os.path.normpath(run_dir))
        run["scene"]["name"] = name
        target = os.path.join(args.docs, "scenes") if args.docs else run_dir
        os.makedirs(target, exist_ok=True)
        rel = "scenes/" if args.docs else ""
        if run["scene"].get("kind") == "rigid":
            section, row = rigid_section(run_dir, run, target, rel, name)
            sections.append(section)
            if row:
                rigid_rows.append(row)
            machine = f"{run['machine']}, SIMD {run['simd']}"
            commits[name] = run_commit(run_dir)
            continue
        tol = run["scene"]["tolerance"] or None
        plot_series(run_dir, run, "total_ms", "ms per step", os.path.join(target, f"step_time_{name}.png"), log=True)
        plot_series(run_dir, run, "max_penetration", "deepest vertex inside (m)",
                    os.path.join(target, f"penetration_{name}.png"), log=True, tolerance=tol)
        pictures = plot_pictures(run_dir, run, os.path.join(target, f"cloth_{name}.png"))
        timing, accuracy = tables(run)
        s = run["scene"]
        section = [f"### {name}: {s['vertices']:,} vertices, {s['triangles']:,} triangles",
                   "", f"Step {s['step']:.5g} s, {s['substeps']} substeps, {s['duration']:g} s simulated, "
                   f"tolerance {s['tolerance']:g} m; effects: {', '.join(s['effects'])}.", "",
                   timing, "", accuracy, "", "; ".join(ratios(run)) + ".", "",
                   f"![step time]({rel}step_time_{name}.png)", "",
                   f"![penetration]({rel}penetration_{name}.png)", ""]
        if pictures:
            section += [f"![the cloth]({rel}cloth_{name}.png)", ""]
        sections.append("\n".join(section))
        runs = {r["model"]: r for r in run["runs"]}
        if "exact" in runs:
            ms = lambda m, phase: runs[m]["mean_ms"].get(phase) if m in runs else None
            pen = lambda m: fmt(runs[m]["max_penetration"]) if m in runs else ""
            paper = PAPER.get(s["vertices"], {})
            headline.append(
                f"| {name} | {fmt(ms('exact', 'total'))} / {fmt(ms('exact', 'collision_detection'))} | "
                f"{fmt(ms('paper', 'collision_detection'))} | {fmt(ms('mesh', 'collision_detection'))} | "
                f"{fmt(ms('bullet', 'total'))} | {fmt(paper.get('total'))} / {fmt(paper.get('collision_detection'))} | "
                f"{pen('exact')} / {pen('paper')} / {pen('mesh')} / {pen('bullet')} |")
        machine = f"{run['machine']}, SIMD {run['simd']}"
        commits[name] = run_commit(run_dir)
    if len(set(commits.values())) == 1:
        stamp_commit = next(iter(commits.values()))
    else:
        stamp_commit = ", ".join(f"{c} ({n})" for n, c in commits.items())
    command = "scripts/scenes.sh --full" if args.docs else "scripts/scenes.sh"
    stamp = f"_Run at commit {stamp_commit}; machine: {machine}. Command: `{command}`._"
    results = "\n".join(sections) + "\n" + stamp
    for path in [os.path.join(a, "results.md") for a in args.runs] if not args.docs else []:
        with open(path, "w") as f:
            f.write(results + "\n")
    if args.docs:
        replace_block(os.path.join(args.docs, "scenes.md"), "results", results, GENERATOR)
    if args.readme and (headline or rigid_rows):
        table = ""
        if headline:
            table += ("| ms per step; deepest vertex inside the shape | ours, Exact: step / collision | "
                      "paper's method: collision | FCL mesh: collision | Bullet: step | the paper, its machine: "
                      "step / collision | deepest inside (m): Exact / paper's / mesh / Bullet |\n"
                      "|---|---|---|---|---|---|---|\n" + "\n".join(headline) + "\n\n")
        if rigid_rows:
            table += ("| ms per step: step / collision | exact pairs | vertices, Exact | vertices, paper's "
                      "method | FCL mesh–mesh | Bullet rigid bodies | the paper, its machine | deepest "
                      "interpenetration (m), exact pairs: any step / after 5 s | inside the bowl at the end |\n"
                      "|---|---|---|---|---|---|---|---|---|\n" + "\n".join(rigid_rows) + "\n\n")
        replace_block(args.readme, "scenes", f"{table}{stamp}", GENERATOR)


if __name__ == "__main__":
    main()
