#!/usr/bin/python3
"""Time-to-accuracy curves of a solver sweep: error_vs_reference (per check, from
iterations.csv) against seconds, one line per run labelled by runs.csv columns.

  scripts/time_to_accuracy.py RUN_DIR --label '{solver.type}' --filter input.levels=3 -o out.png
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir", help="a run folder with runs.csv and iterations.csv")
    ap.add_argument("--label", default="{solver.type}", help="line label, runs.csv columns in braces")
    ap.add_argument("--filter", action="append", default=[], help="keep runs with column=value (repeatable)")
    ap.add_argument("--title", default="")
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()
    runs = read(os.path.join(a.run_dir, "runs.csv"))
    iterations = read(os.path.join(a.run_dir, "iterations.csv"))
    for f in a.filter:
        key, _, value = f.partition("=")
        if runs and key not in runs[0]:
            sys.exit(f"--filter: no column '{key}' in runs.csv")
        runs = [r for r in runs if r[key] == value]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for run in runs:
        pts = [(float(i["seconds"]), float(i["error_vs_reference"])) for i in iterations
               if i["run_id"] == run["run_id"] and i["error_vs_reference"] not in ("", "nan")]
        # The solve starts after the run's analysis (factorization, colouring, levels).
        t0 = float(run["analyze_s"] or 0)
        if run["solver.type"] == "cholesky" and run["solve_s"]:
            ax.axvline(t0 + float(run["solve_s"]), color="k", ls=":", lw=1, label="CHOLMOD analyze+factor+solve")
        if not pts:
            continue
        label = a.label
        for key, value in run.items():
            label = label.replace("{" + key + "}", value)
        ax.plot([t0 + t for t, _ in pts], [max(e, 1e-16) for _, e in pts], label=label)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("seconds (analysis + solve)")
    ax.set_ylabel("relative error vs CHOLMOD")
    ax.set_title(a.title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    tmp = a.output + ".tmp.png"
    fig.savefig(tmp, dpi=120)
    os.replace(tmp, a.output)


if __name__ == "__main__":
    main()
