#!/usr/bin/python3
"""h-independence of a solver sweep: iterations to the tolerance (and seconds) against the
number of unknowns, one line per solver, from runs.csv, with CHOLMOD's analyze+factor+solve
time beside them when the sweep has it; runs that stopped at the iteration cap are drawn hollow.

  scripts/iterations_vs_level.py RUN_DIR --solvers multigrid,multigrid_cg -o out.png
"""
import argparse
import csv
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir", help="a run folder with runs.csv")
    ap.add_argument("--solvers", default="", help="comma-separated solver.type values (default: all)")
    ap.add_argument("--title", default="iterations to tolerance against problem size")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()
    with open(os.path.join(a.run_dir, "runs.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    keep = set(a.solvers.split(",")) if a.solvers else None
    lines = defaultdict(list)
    direct = []  # CHOLMOD's time beside the iterative solvers' (it has no iterations to plot)
    for r in rows:
        if not r["iterations"] or not r["analyze_s"] or not r["solve_s"]:
            continue
        seconds = float(r["analyze_s"]) + float(r["solve_s"])
        if r["solver.type"] == "cholesky":
            direct.append((int(r["n_dofs"]), seconds))
        elif not keep or r["solver.type"] in keep:
            lines[r["solver.type"]].append((int(r["n_dofs"]), int(r["iterations"]), seconds,
                                            r["termination"] == "converged"))
    if not lines:
        raise SystemExit("iterations_vs_level: no iterative runs in " + a.run_dir)
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.5), dpi=100)
    for name, pts in sorted(lines.items()):
        pts.sort()
        n = [p[0] for p in pts]
        line, = left.plot(n, [p[1] for p in pts], "-", label=name)
        right.plot(n, [p[2] for p in pts], "-", color=line.get_color(), label=name)
        for p in pts:
            face = line.get_color() if p[3] else "none"
            left.plot(p[0], p[1], "o", color=line.get_color(), markerfacecolor=face)
            right.plot(p[0], p[2], "o", color=line.get_color(), markerfacecolor=face)
    if direct:
        direct.sort()
        right.plot([d[0] for d in direct], [d[1] for d in direct], "k:s", label="CHOLMOD (analyze+factor+solve)")
    for ax, ylabel in ((left, "iterations (hollow: hit the cap)"), (right, "seconds (analysis + solve)")):
        ax.set_xscale("log")
        ax.set_xlabel("vertices of the edit level (n_dofs)")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    right.set_yscale("log")
    fig.suptitle(a.title)
    fig.tight_layout()
    tmp = a.output + ".tmp.png"
    fig.savefig(tmp)
    os.replace(tmp, a.output)
    print("iterations_vs_level: wrote " + a.output)


if __name__ == "__main__":
    main()
