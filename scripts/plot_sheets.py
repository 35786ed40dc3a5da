#!/usr/bin/python3
"""Figures of Welch & Witkin sheet runs (configs/welch-witkin).

  plot_sheets.py steps RUN_DIR OUT.png --title TEXT [--labels L0 L1 ...]
      one rendered panel per design step (vtk/<run_id>_step<k>.vtp, coloured by displacement)
  plot_sheets.py cells RUN_DIR OUT.png --title TEXT
  plot_sheets.py runs RUN_DIR OUT.png --title TEXT --label FORMAT --profile-v V --size-v S --spans-v N --per-span K
      one rendered panel per run of a sweep (its last step), plus the height profile z(x) of
      every run along the line v = V (design units, as the config's (u, v); the sheet S long
      in v) of final/<run_id>.obj (N base spans in v, K samples per span); FORMAT is a Python
      format over the runs.csv row (dots in names -> _)
      constraint error per leaf cell after every solve of the last step (cells.csv: the first,
      unrefined solve and each refinement round), above the surface before and after refinement
  plot_sheets.py convergence RUN_DIR OUT.png --title TEXT
      a resolution study (configs/welch-witkin/resolution.yaml): energy against base spans per
      solver, and |E - E_finest| and the largest constraint error against the span size

Panels are rendered by `fairshape render` (VTK offscreen).
"""
import argparse
import csv
import glob
import math
import os
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PatchCollection  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

BIN = os.path.join(os.path.dirname(__file__), "..", "build", "bin", "fairshape")
VIEW = ["--view", "front", "--azimuth", "25", "--elevation", "40", "--width", "640", "--height", "480",
        "--array", "displacement", "--colour-label", "|displacement|"]


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def step_files(pattern):
    """The steps' sheets, not the constraint overlays beside them (fairshape render finds those)."""
    return [f for f in glob.glob(pattern) if not f.endswith("_constraints.vtp")]


def render_panels(vtps, png, labels, title=""):
    """One `fairshape render` of several sheets: one camera, one colour range, one colour bar."""
    cmd = [BIN, "render"] + vtps + [png] + VIEW + [x for label in labels for x in ("--label", label)]
    subprocess.run(cmd + (["--title", title] if title else []), check=True, stdout=subprocess.DEVNULL)


def steps_figure(run_dir, out, title, labels):
    steps = read_csv(os.path.join(run_dir, "steps.csv"))
    files = sorted(step_files(os.path.join(run_dir, "vtk", "*_step*.vtp")),
                   key=lambda p: int(p.rsplit("_step", 1)[1].split(".")[0]))
    names = []
    for k in range(len(files)):
        rows = [r for r in steps if r["step"] == str(k)]
        err = max((float(r["max_constraint_error"]) for r in rows), default=float("nan"))
        names.append(f"{labels[k] if k < len(labels) else f'step {k}'}: max constraint error {err:.1e}")
    tmp = out + ".tmp.png"
    render_panels(files, tmp, names, title)
    os.replace(tmp, out)


def cells_panel(ax, cells, label, vmin, vmax):
    rects, values, empty = [], [], []
    for c in cells:
        r = Rectangle((float(c["u0"]), float(c["v0"])), float(c["size_u"]), float(c["size_v"]))
        if float(c["error"]) > 0:
            rects.append(r)
            values.append(math.log10(float(c["error"])))
        else:
            empty.append(r)
    ax.add_collection(PatchCollection(empty, facecolor="#f2f2f2", edgecolor="#999999", linewidth=0.4))
    pc = PatchCollection(rects, cmap="viridis", edgecolor="white", linewidth=0.4)
    pc.set_array(values)
    pc.set_clim(vmin, vmax)
    ax.add_collection(pc)
    ax.set_aspect("equal")
    ax.autoscale_view()
    worst = max(float(c["error"]) for c in cells)
    ax.set_title(f"{label}: {len(rects) + len(empty)} cells\nmax error {worst:.1e}", fontsize=10)
    ax.set_xlabel("u")
    ax.set_ylabel("v")
    return pc


def cells_figure(run_dir, out, title):
    """The error map after every solve of the last step (cells.csv), then the surface before and
    after automatic refinement, rendered with one camera and one colour range."""
    cells = read_csv(os.path.join(run_dir, "cells.csv"))
    rounds = sorted({int(c["round"]) for c in cells})
    per_round = [[c for c in cells if int(c["round"]) == r and c["when"] == ("before" if r == 1 else c["when"])] for r in rounds]
    logs = [math.log10(float(c["error"])) for c in cells if float(c["error"]) > 0]
    vmin, vmax = max(min(logs), -8), max(logs)
    fig = plt.figure(figsize=(3.6 * max(len(rounds), 3), 8))
    grid = fig.add_gridspec(2, len(rounds))
    pc = None
    for k, round_cells in enumerate(per_round):
        ax = fig.add_subplot(grid[0, k])
        label = "unrefined" if k == 0 else f"round {rounds[k]}"
        pc = cells_panel(ax, round_cells, label, vmin, vmax)
    fig.colorbar(pc, ax=fig.axes, label="log10 constraint error per cell", shrink=0.45, location="right")
    steps = sorted(step_files(os.path.join(run_dir, "vtk", "*_step*.vtp")),
                   key=lambda p: int(p.rsplit("_step", 1)[1].split(".")[0]))
    last = int(steps[-1].rsplit("_step", 1)[1].split(".")[0])
    before = glob.glob(os.path.join(run_dir, "vtk", f"*_unrefined{last}.vtp"))
    files, labels = (before + steps[-1:], ["first solve (unrefined)", f"after {len(rounds) - 1} refinement rounds"]) if before else \
        (steps[-1:], ["surface"])
    ax = fig.add_subplot(grid[1, :])
    with tempfile.TemporaryDirectory() as tmp:
        render_panels(files, os.path.join(tmp, "s.png"), labels)
        ax.imshow(mpimg.imread(os.path.join(tmp, "s.png")))
    ax.axis("off")
    fig.suptitle(title)
    tmp = out + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, out)


def read_obj_vertices(path):
    with open(path) as f:
        return [tuple(map(float, line.split()[1:4])) for line in f if line.startswith("v ")]


def runs_figure(run_dir, out, title, label, profile_v, size_v, spans_v, per_span):
    runs = read_csv(os.path.join(run_dir, "runs.csv"))
    fig, axes = plt.subplots(1, 2, figsize=(4.2 * (len(runs) + 1), 3.9), squeeze=False,
                             gridspec_kw={"width_ratios": [len(runs), 1]})
    column = int(round(profile_v / size_v * spans_v * per_span))  # design units -> sample index
    names, vtps = [], []
    for r in runs:
        vtps.append(sorted(step_files(os.path.join(run_dir, "vtk", r["run_id"] + "_step*.vtp")))[-1])
        names.append(label.format(**{key.replace(".", "_"): value for key, value in r.items()}))
        V = read_obj_vertices(os.path.join(run_dir, "final", r["run_id"] + ".obj"))
        rows = spans_v * per_span + 1
        line = [V[i * rows + column] for i in range(len(V) // rows)]
        axes[0][1].plot([x for x, _, _ in line], [z for _, _, z in line], label=names[-1])
    with tempfile.TemporaryDirectory() as tmp:
        render_panels(vtps, os.path.join(tmp, "sheets.png"), names)
        axes[0][0].imshow(mpimg.imread(os.path.join(tmp, "sheets.png")))
    axes[0][0].axis("off")
    axes[0][1].set_xlabel("x")
    axes[0][1].set_ylabel("z")
    axes[0][1].set_title(f"profile along v = {profile_v:g} (design units)", fontsize=10)
    axes[0][1].legend(fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def convergence_figure(run_dir, out, title):
    rows = [r for r in csv.DictReader(open(os.path.join(run_dir, "runs.csv"))) if r["termination"] == "converged"]
    spans = lambda r: int(r["sheets.0.spans"].strip("[]").split(",")[0])  # noqa: E731
    solvers = sorted({r["solver.type"] for r in rows})
    finest = max(spans(r) for r in rows)
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for k, solver in enumerate(solvers):
        mine = sorted((r for r in rows if r["solver.type"] == solver), key=spans)
        n = [spans(r) for r in mine]
        e = [float(r["energy"]) for r in mine]
        left.plot(n, e, marker="os^"[k % 3], markersize=9 - 2 * k, label=solver)
        ref = e[n.index(finest)]
        h = [2.0 / x for x in n[:-1]]
        right.loglog(h, [max(abs(x - ref), 1e-16) for x in e[:-1]], marker="os^"[k % 3], markersize=9 - 2 * k,
                     label=f"|E - E({finest} spans)|, {solver}")
        if k == 0:
            right.loglog([2.0 / x for x in n], [float(r["max_constraint_error"]) for r in mine], "k--", marker="x",
                         label="largest constraint error")
    left.set_xscale("log", base=2)
    left.set_xlabel("base spans per direction")
    left.set_ylabel("energy (design units)")
    left.legend(fontsize=8)
    left.set_title("energy of one design at every resolution", fontsize=10)
    right.set_xlabel("span size h (design units)")
    right.legend(fontsize=7)
    right.set_title("convergence under refinement", fontsize=10)
    fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    tmp = out + ".tmp.png"
    fig.savefig(tmp, dpi=110)
    os.replace(tmp, out)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("kind", choices=["steps", "cells", "runs", "convergence"])
    p.add_argument("run_dir")
    p.add_argument("out")
    p.add_argument("--title", default="")
    p.add_argument("--labels", nargs="*", default=[])
    p.add_argument("--label", default="{run_id}")
    p.add_argument("--profile-v", type=float, default=0)
    p.add_argument("--size-v", type=float, default=1)
    p.add_argument("--spans-v", type=int, default=1)
    p.add_argument("--per-span", type=int, default=6)
    a = p.parse_args()
    if a.kind == "steps":
        steps_figure(a.run_dir, a.out, a.title, a.labels)
    elif a.kind == "cells":
        cells_figure(a.run_dir, a.out, a.title)
    elif a.kind == "convergence":
        convergence_figure(a.run_dir, a.out, a.title)
    else:
        runs_figure(a.run_dir, a.out, a.title, a.label, a.profile_v, a.size_v, a.spans_v, a.per_span)


if __name__ == "__main__":
    main()
