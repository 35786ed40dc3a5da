#!/usr/bin/python3
"""Side-by-side figure of a sweep's results: one rendered panel per run of runs.csv.

  panels.py RUN_DIR OUT.png --title TEXT --label FORMAT [--rest MESH] [--render ARG ...]
  panels.py RUN_DIR OUT.png --title TEXT --ladder RUN_ID [--render ARG ...]

--ladder shows one run's accuracy ladder instead (vtk/<RUN_ID>_ladder_level<l>.vtp: each
level's deformed control mesh, coloured by the vertices the propagated constraints reach).

FORMAT is a Python format string over the runs.csv row, with dots in column names replaced
by underscores and numbers parsed, e.g. "edit level {input_edit_level}: {detail_change:.2f}".
A `{kind}` field holds the last `type:` in the swept values (the energy, or the last constraint).
Panels are rendered by `fairshape render` (VTK offscreen) from vtk/<run_id>.vtp.
"""
import argparse
import csv
import os
import re
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

BIN = os.path.join(os.path.dirname(__file__), "..", "build", "bin", "fairshape")


def fields(row):
    out = {}
    for key, value in row.items():
        try:
            value = float(value)
        except ValueError:
            pass
        out[key.replace(".", "_")] = value
    swept = list(row)[1:list(row).index("implementation")]  # run_id, the swept keys, then the rest
    types = [m for key in swept for m in re.findall(r"type: ([\w-]+)", row[key])]
    out["kind"] = types[-1] if types else ""
    return out


def render(source, png, args):
    subprocess.run([BIN, "render", source, png] + args, check=True)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run_dir")
    p.add_argument("out_png")
    p.add_argument("--title", required=True)
    p.add_argument("--label", help="panel label format (required unless --ladder)")
    p.add_argument("--ladder", metavar="RUN_ID", help="show this run's ladder levels instead of every run")
    p.add_argument("--rest", help="also show this mesh first, uncoloured")
    p.add_argument("--columns", type=int, default=0, help="panels per row (default: all in one row)")
    p.add_argument("--render", nargs=argparse.REMAINDER, default=[], help="arguments for fairshape render")
    a = p.parse_args()
    panels = ladder_panels(a) if a.ladder else run_panels(a)
    cols = a.columns or len(panels)
    rows = (len(panels) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(6.4 * cols, 5.0 * rows), dpi=100, squeeze=False)
    for ax in axes.flat:
        ax.axis("off")
    for ax, (png, label) in zip(axes.flat, panels):
        ax.imshow(mpimg.imread(png))
        ax.set_title(label, fontsize=11)
    fig.suptitle(a.title, fontsize=13)
    fig.tight_layout()
    tmp = a.out_png + ".tmp.png"
    fig.savefig(tmp)
    os.replace(tmp, a.out_png)  # never a truncated figure
    print(f"panels: wrote {a.out_png}")


def ladder_panels(a):
    vtk = os.path.join(a.run_dir, "vtk")
    files = sorted(f for f in os.listdir(vtk) if f.startswith(a.ladder + "_ladder_level") and f.endswith(".vtp"))
    if not files:
        sys.exit(f"panels: no ladder levels of run {a.ladder} in {vtk}")
    panels = []
    for f in files:
        level = f[len(a.ladder + "_ladder_level"):-len(".vtp")]
        png = os.path.join(a.run_dir, f[:-len(".vtp")] + ".png")
        render(os.path.join(vtk, f), png, ["--array", "constrained", "--edges"] + a.render)
        panels.append((png, f"level {level}: control mesh, constrained vertices in red"))
    return panels


def run_panels(a):
    if not a.label:
        sys.exit("panels: --label is required (or --ladder RUN_ID)")
    rows = list(csv.DictReader(open(os.path.join(a.run_dir, "runs.csv"))))
    failed = [r["run_id"] for r in rows if r["termination"] not in ("converged", "energy_stalled", "schedule_completed")]
    if failed:
        sys.exit(f"panels: runs {failed} did not finish; see {a.run_dir}/runs.csv")
    panels = []
    if a.rest:
        png = os.path.join(a.run_dir, "rest.png")
        render(a.rest, png, [x for x in a.render])
        panels.append((png, "before"))
    for r in rows:
        png = os.path.join(a.run_dir, f"{r['run_id']}.png")
        render(os.path.join(a.run_dir, "vtk", f"{r['run_id']}.vtp"), png, ["--array", "displacement_norm"] + a.render)
        panels.append((png, a.label.format(**fields(r))))
    return panels


if __name__ == "__main__":
    main()
