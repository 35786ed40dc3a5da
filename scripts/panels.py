#!/usr/bin/python3
"""Side-by-side figure of a sweep's results: one rendered panel per run of runs.csv.

  panels.py RUN_DIR OUT.png --title TEXT --label FORMAT [--label FORMAT ...] [--rest MESH] [--render ARG ...]
  panels.py RUN_DIR OUT.png --title TEXT --steps RUN_ID --label FORMAT [--render ARG ...]
  panels.py RUN_DIR OUT.png --title TEXT --ladder RUN_ID [--render ARG ...]

--runs picks rows of runs.csv; --inputs-from DIR draws copies of the results (DIR/<run>.vtp,
with their overlays) instead, coloured by --array; --allow-folded shows runs that ended folded
(their labels say so).

--steps shows one run's drag steps instead (vtk/<RUN_ID>_step<k>.vtp, written with
output.vtk: all; FORMAT over steps.csv's row). --ladder shows one run's accuracy ladder instead (vtk/<RUN_ID>_ladder_level<l>.vtp: each
level's deformed control mesh, coloured by the vertices the propagated constraints reach).

FORMAT is a Python format string over the runs.csv row, with dots in column names replaced
by underscores and numbers parsed, e.g. "edit level {input_edit_level}: {detail_change:.2f}".
A `{kind}` field holds the last `type:` in the swept values (the energy, or the last constraint).
The panels are one `fairshape render` (VTK offscreen) of the runs' geometry: one camera and
one colour range for all of them, a colour bar, the labels and the title.
"""
import argparse
import csv
import os
import re
import subprocess
import sys


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


def render(inputs, labels, out_png, args):
    """One `fairshape render` for the whole figure: one camera and one colour range."""
    cmd = [BIN, "render"] + inputs + [out_png] + [x for label in labels for x in ("--label", label)] + args
    subprocess.run(cmd, check=True)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run_dir")
    p.add_argument("out_png")
    p.add_argument("--title", required=True)
    p.add_argument("--label", action="append",
                   help="panel label format (required unless --ladder); given once per run, one each, in runs.csv order")
    p.add_argument("--ladder", metavar="RUN_ID", help="show this run's ladder levels instead of every run")
    p.add_argument("--steps", metavar="RUN_ID", help="show this run's drag steps instead of every run")
    p.add_argument("--rest", help="also show this mesh first, uncoloured")
    p.add_argument("--allow-unmet", action="store_true",
                   help="also show runs that finished as constraints_unmet (their misses are in the run's CSVs)")
    p.add_argument("--allow-folded", action="store_true",
                   help="also show runs that ended folded (a config's `expect: folded`); their labels must say so, "
                        "e.g. with {flipped_faces:.0f}")
    p.add_argument("--runs", help="only these runs, by their 1-based row in runs.csv: e.g. 1,2,7")
    p.add_argument("--inputs-from", metavar="DIR",
                   help="draw run R from DIR/R.vtp (a copy with more arrays or overlays, e.g. by "
                        "papers/boier-martin/figures/figure_tools.py) instead of RUN_DIR's own result")
    p.add_argument("--array", default="displacement", help="the point array that colours the panels")
    p.add_argument("--colour-label", help="the colour bar's label (default: |ARRAY|)")
    p.add_argument("--columns", type=int, default=0, help="panels per row (default: all in one row)")
    p.add_argument("--render", nargs=argparse.REMAINDER, default=[], help="arguments for fairshape render")
    a = p.parse_args()
    inputs, labels, args = ladder_panels(a) if a.ladder else step_panels(a) if a.steps else run_panels(a)
    args += ["--title", a.title] + (["--columns", str(a.columns)] if a.columns else [])
    tmp = a.out_png + ".tmp.png"
    render(inputs, labels, tmp, args + a.render)
    os.replace(tmp, a.out_png)  # never a truncated figure
    print(f"panels: wrote {a.out_png}")


def ladder_panels(a):
    vtk = os.path.join(a.run_dir, "vtk")
    files = sorted(f for f in os.listdir(vtk) if f.startswith(a.ladder + "_ladder_level") and f.endswith(".vtp"))
    if not files:
        sys.exit(f"panels: no ladder levels of run {a.ladder} in {vtk}")
    labels = [f"level {f[len(a.ladder + '_ladder_level'):-len('.vtp')]}: control mesh" for f in files]
    args = ["--array", "constrained", "--colour-label", "reached by the constraints", "--flat"]
    return [os.path.join(vtk, f) for f in files], labels, args


def step_panels(a):
    if not a.label or len(a.label) != 1:
        sys.exit("panels: --steps needs one --label format (over steps.csv's columns)")
    rows = [r for r in csv.DictReader(open(os.path.join(a.run_dir, "steps.csv"))) if r["run_id"] == a.steps]
    vtk = os.path.join(a.run_dir, "vtk")
    inputs = [os.path.join(a.inputs_from or vtk, f"{a.steps}_step{r['step']}.vtp") for r in rows]
    missing = [f for f in inputs if not os.path.exists(f)]
    if not rows or missing:
        sys.exit(f"panels: run {a.steps} has no drag steps in {a.run_dir} (output.vtk: all writes them): {missing[:1]}")
    labels = [a.label[0].format(**fields(r)) for r in rows]
    args = colouring(a)
    if a.rest:
        args += ["--rest", a.rest, "--rest-label", "before"]
    return inputs, labels, args


def colouring(a):
    args = ["--array", a.array]
    if a.colour_label:
        args += ["--colour-label", a.colour_label]
    elif "--component" not in a.render:
        args += ["--colour-label", f"|{a.array}|"]
    return args


def run_panels(a):
    if not a.label:
        sys.exit("panels: --label is required (or --ladder RUN_ID)")
    rows = list(csv.DictReader(open(os.path.join(a.run_dir, "runs.csv"))))
    if a.runs:
        rows = [rows[int(k) - 1] for k in a.runs.split(",")]
    finished = ("converged", "energy_stalled", "schedule_completed") + (("constraints_unmet",) if a.allow_unmet else ()) + \
               (("folded",) if a.allow_folded else ())
    failed = [r["run_id"] for r in rows if r["termination"] not in finished]
    if failed:
        sys.exit(f"panels: runs {failed} did not finish; see {a.run_dir}/runs.csv")
    inputs = [os.path.join(a.inputs_from, r["run_id"] + ".vtp") if a.inputs_from else f"{a.run_dir}@{r['run_id']}"
              for r in rows]
    if len(a.label) not in (1, len(rows)):
        sys.exit(f"panels: {len(a.label)} --label formats for {len(rows)} runs (give one, or one per run)")
    formats = a.label * len(rows) if len(a.label) == 1 else a.label
    labels = [f.format(**fields(r)) for f, r in zip(formats, rows)]
    args = colouring(a)
    if a.rest:
        args += ["--rest", a.rest, "--rest-label", "before"]
    return inputs, labels, args


if __name__ == "__main__":
    main()
