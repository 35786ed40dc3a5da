#!/usr/bin/python3
"""Where a Krylov solver's iterations go, level by level: iterations to reach each relative
residual (left) and the error against the run's reference (CHOLMOD) per iteration (right), from
the iterations.csv and runs.csv of one or more run folders (sweeps over input.levels).

Flat lines on the left up to some tolerance and growth below it, with the right panel's error
flat from the same iteration on, say that the preconditioner is h-independent and that the
remaining iterations are spent under the rounding floor of the system, not on a weak level pair.

  scripts/iterations_to_tolerances.py DIR [DIR ...] --solver multigrid_cg -o out.png
"""
import argparse
import csv
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TOLERANCES = (1e-4, 1e-6, 1e-8, 1e-9, 1e-10)


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dirs", nargs="+", help="run folders with runs.csv and iterations.csv")
    ap.add_argument("--solver", default="multigrid_cg", help="the solver.type to plot")
    ap.add_argument("--title", default="")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()
    histories = {}  # n_dofs -> (level, [(iteration, residual, error)])
    for d in a.run_dirs:
        runs = {r["run_id"]: r for r in read(os.path.join(d, "runs.csv")) if r["solver.type"] == a.solver}
        steps = defaultdict(list)
        for r in read(os.path.join(d, "iterations.csv")):
            if r["run_id"] in runs:
                error = float(r["error_vs_reference"]) if r.get("error_vs_reference") else float("nan")
                steps[r["run_id"]].append((int(r["iteration"]), float(r["residual"]), error))
        for run_id, s in steps.items():
            histories[int(runs[run_id]["n_dofs"])] = (runs[run_id]["input.levels"], sorted(s))
    if not histories:
        raise SystemExit(f"iterations_to_tolerances: no {a.solver} iterations in {', '.join(a.run_dirs)}")
    sizes = sorted(histories)
    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 4.8), dpi=100)
    for tol in TOLERANCES:
        pts = []
        for n in sizes:
            reached = [i for i, res, _ in histories[n][1] if res <= tol]
            if reached:
                pts.append((n, reached[0]))
        if pts:
            left.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label=f"relative residual {tol:g}")
    left.set_xscale("log")
    left.set_xlabel("vertices of the edit level (n_dofs)")
    left.set_ylabel("iterations to reach it")
    left.grid(True, which="both", alpha=0.3)
    left.legend(fontsize=8)
    for n in sizes:
        level, s = histories[n]
        right.plot([i for i, _, _ in s], [e for _, _, e in s], "-", label=f"level {level} ({n:,} vertices)")
    right.set_yscale("log")
    right.set_xlabel("iteration")
    right.set_ylabel("relative error against CHOLMOD's solution")
    right.grid(True, which="both", alpha=0.3)
    right.legend(fontsize=8)
    fig.suptitle(a.title or f"{a.solver}: iterations to each residual, and where the error floors")
    fig.tight_layout()
    tmp = a.output + ".tmp.png"
    fig.savefig(tmp)
    os.replace(tmp, a.output)
    print("iterations_to_tolerances: wrote " + a.output)


if __name__ == "__main__":
    main()
