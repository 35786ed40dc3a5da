#!/usr/bin/python3
"""Figures of Welch & Witkin sheet runs (configs/welch-witkin).

  plot_sheets.py steps RUN_DIR OUT.png --title TEXT [--labels L0 L1 ...]
      one rendered panel per design step (vtk/<run_id>_step<k>.vtp, coloured by displacement)
  plot_sheets.py cells RUN_DIR OUT.png --title TEXT
      constraint error per leaf cell before and after automatic refinement (cells.csv), beside
      the refined surface

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
VIEW = ["--azimuth", "25", "--elevation", "40", "--width", "640", "--height", "480", "--array", "displacement_norm"]


def render(vtp, png):
    subprocess.run([BIN, "render", vtp, png] + VIEW, check=True, stdout=subprocess.DEVNULL)
    return mpimg.imread(png)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def steps_figure(run_dir, out, title, labels):
    steps = read_csv(os.path.join(run_dir, "steps.csv"))
    files = sorted(glob.glob(os.path.join(run_dir, "vtk", "*_step*.vtp")),
                   key=lambda p: int(p.rsplit("_step", 1)[1].split(".")[0]))
    fig, axes = plt.subplots(1, len(files), figsize=(4.2 * len(files), 3.8), squeeze=False)
    with tempfile.TemporaryDirectory() as tmp:
        for k, (ax, vtp) in enumerate(zip(axes[0], files)):
            ax.imshow(render(vtp, os.path.join(tmp, f"{k}.png")))
            ax.axis("off")
            rows = [r for r in steps if r["step"] == str(k)]
            err = max((float(r["max_constraint_error"]) for r in rows), default=float("nan"))
            name = labels[k] if k < len(labels) else f"step {k}"
            ax.set_title(f"{name}\nmax constraint error {err:.1e}", fontsize=10)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def cells_panel(ax, cells, when, vmin, vmax):
    rects, values, empty = [], [], []
    for c in cells:
        if c["when"] != when:
            continue
        size = float(c["size"])
        r = Rectangle((float(c["u0"]), float(c["v0"])), size, size)
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
    worst = max(float(c["error"]) for c in cells if c["when"] == when)
    ax.set_title(f"{when} refinement: {len(rects) + len(empty)} cells, max error {worst:.1e}", fontsize=10)
    ax.set_xlabel("u")
    ax.set_ylabel("v")
    return pc


def cells_figure(run_dir, out, title):
    cells = read_csv(os.path.join(run_dir, "cells.csv"))
    logs = [math.log10(float(c["error"])) for c in cells if float(c["error"]) > 0]
    vmin, vmax = max(min(logs), -8), max(logs)
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.3))
    cells_panel(axes[0], cells, "before", vmin, vmax)
    pc = cells_panel(axes[1], cells, "after", vmin, vmax)
    fig.colorbar(pc, ax=axes[1], label="log10 constraint error per cell")
    files = sorted(glob.glob(os.path.join(run_dir, "vtk", "*_step*.vtp")))
    with tempfile.TemporaryDirectory() as tmp:
        axes[2].imshow(render(files[-1], os.path.join(tmp, "s.png")))
    axes[2].axis("off")
    axes[2].set_title("refined surface", fontsize=10)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("kind", choices=["steps", "cells"])
    p.add_argument("run_dir")
    p.add_argument("out")
    p.add_argument("--title", default="")
    p.add_argument("--labels", nargs="*", default=[])
    a = p.parse_args()
    if a.kind == "steps":
        steps_figure(a.run_dir, a.out, a.title, a.labels)
    else:
        cells_figure(a.run_dir, a.out, a.title)


if __name__ == "__main__":
    main()
