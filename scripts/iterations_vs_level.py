#!/usr/bin/python3
"""h-independence of a solver sweep: iterations to the tolerance, seconds and solver memory
(runs.csv `solve_extra_mb`) against the number of unknowns, one line per solver, with CHOLMOD's
analyze+factor+solve time and memory beside them when the sweep has it; runs that did not end
`converged` (the iteration cap, a stall at the rounding floor) are drawn hollow.

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
    ap.add_argument("--machine-gb", type=float, default=0, help="draw the machine's memory (GiB) on the memory panel")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()
    with open(os.path.join(a.run_dir, "runs.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    keep = set(a.solvers.split(",")) if a.solvers else None
    lines = defaultdict(list)
    direct = []  # CHOLMOD's time and memory beside the iterative solvers' (it has no iterations to plot)
    memory = lambda r: float(r["solve_extra_mb"]) / 1024 if r.get("solve_extra_mb") else float("nan")
    for r in rows:
        if not r["iterations"] or not r["analyze_s"] or not r["solve_s"]:
            continue
        seconds = float(r["analyze_s"]) + float(r["solve_s"])
        if r["solver.type"] == "cholesky":
            direct.append((int(r["n_dofs"]), seconds, memory(r)))
        elif not keep or r["solver.type"] in keep:
            lines[r["solver.type"]].append((int(r["n_dofs"]), int(r["iterations"]), seconds,
                                            r["termination"] == "converged", memory(r)))
    if not lines:
        raise SystemExit("iterations_vs_level: no iterative runs in " + a.run_dir)
    fig, (left, right, mem) = plt.subplots(1, 3, figsize=(17, 4.5), dpi=100)
    for name, pts in sorted(lines.items()):
        pts.sort()
        n = [p[0] for p in pts]
        line, = left.plot(n, [p[1] for p in pts], "-", label=name)
        right.plot(n, [p[2] for p in pts], "-", color=line.get_color(), label=name)
        mem.plot(n, [p[4] for p in pts], "-", color=line.get_color(), label=name)
        for p in pts:
            face = line.get_color() if p[3] else "none"
            left.plot(p[0], p[1], "o", color=line.get_color(), markerfacecolor=face)
            right.plot(p[0], p[2], "o", color=line.get_color(), markerfacecolor=face)
            mem.plot(p[0], p[4], "o", color=line.get_color(), markerfacecolor=face)
    if direct:
        direct.sort()
        right.plot([d[0] for d in direct], [d[1] for d in direct], "k:s", label="CHOLMOD (analyze+factor+solve)")
        mem.plot([d[0] for d in direct], [d[2] for d in direct], "k:s", label="CHOLMOD")
    if a.machine_gb > 0:
        mem.axhline(a.machine_gb, color="r", lw=1, ls="--", label=f"this machine ({a.machine_gb:g} GiB)")
    for ax, ylabel in ((left, "iterations (hollow: not converged)"), (right, "seconds (analysis + solve)"),
                       (mem, "solver memory, GiB (solve_extra_mb)")):
        ax.set_xscale("log")
        ax.set_xlabel("vertices of the edit level (n_dofs)")
        ax.set_ylabel(ylabel)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    right.set_yscale("log")
    mem.set_yscale("log")
    fig.suptitle(a.title)
    fig.tight_layout()
    tmp = a.output + ".tmp.png"
    fig.savefig(tmp)
    os.replace(tmp, a.output)
    print("iterations_vs_level: wrote " + a.output)


if __name__ == "__main__":
    main()
