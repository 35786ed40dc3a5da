#!/usr/bin/python3
"""Plots of experiments/bench/curve_benchmark's JSON (medians).

    plot_curve_bench.py BENCH.json OUT_DIR
writes OUT_DIR/scaling.png (edit time vs points, log-log, with a slope-1 guide) and
OUT_DIR/time_to_accuracy.png (every length solver at one common local minimum: time against the length
error reached).
"""
import json
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def medians(path):
    rows = json.load(open(path))["benchmarks"]
    return [r for r in rows if r.get("aggregate_name", "median") == "median" and "error_occurred" not in r]


def ms(r):
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[r["time_unit"]]
    return r["real_time"] * scale


def scaling(rows, out):
    if not any(r["name"].startswith("BM_EditScaling") for r in rows):
        return  # a JSON of other benchmarks: leave the plot as it is
    fig, ax = plt.subplots(figsize=(6, 4.2))
    for flag, label in (("optimized:1", "optimized (banded LDLᵀ, one analysis)"), ("optimized:0", "reference (SparseLU per solve)")):
        pts = sorted((r["points"], ms(r)) for r in rows if r["name"].startswith("BM_EditScaling") and flag in r["name"])
        if pts:
            ax.loglog([p for p, _ in pts], [t for _, t in pts], "o-", label=label)
    opt = sorted((r["points"], ms(r)) for r in rows if r["name"].startswith("BM_EditScaling") and "optimized:1" in r["name"])
    if opt:
        n0, t0 = opt[0]
        xs = [p for p, _ in opt]
        ax.loglog(xs, [t0 * x / n0 for x in xs], "k:", label="slope 1 (linear)")
    ax.set_xlabel("points")
    ax.set_ylabel("one edit end to end [ms] (median)")
    ax.set_title("Cost growth, 2^7+1 .. 2^20+1 points (Newton, 6 solves each)", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "scaling.png", dpi=130)


def time_to_accuracy(rows, out):
    if not any(r["name"].startswith("BM_TimeToAccuracy") for r in rows):
        return
    fig, ax = plt.subplots(figsize=(6, 4.2))
    labels = {"linearized_paper": "paper's linearization", "linearized_newton": "Newton", "ceres": "Ceres (augmented Lagrangian)",
              "trust_region": "trust region"}
    for solver, label in labels.items():
        pts = sorted((r["length_error"], ms(r)) for r in rows if r["name"].startswith(f"BM_TimeToAccuracy/{solver}/"))
        if pts:
            ax.loglog([max(e, 1e-16) for e, _ in pts], [t for _, t in pts], "o-", label=label)
    far = [r for r in rows if r["name"].startswith("BM_TimeToAccuracy") and r.get("distance_to_minimum", 0) > 1e-6]
    # What every run spends after its solve, judging the answer at second order: the default
    # (inertia) and, for comparison, the dense eigen-solve every run paid before.
    for arg, style, label in (("dense:0", ":", "of which: the second-order check (inertia, the default)"),
                              ("dense:1", "--", "the dense check (second_order: dense), not paid by default")):
        check = [ms(r) for r in rows if r["name"].startswith(f"BM_SecondOrderCheck/{arg}")]
        if check:
            ax.axhline(check[0], color="k", ls=style, lw=1, label=label)
    ax.invert_xaxis()
    ax.set_xlabel("max relative length error reached")
    ax.set_ylabel("time [ms] (median)")
    note = "every run at the common minimum" if not far else f"{len(far)} runs > 1e-6 from the common minimum (loose tolerances)"
    ax.set_title(f"Wave (129 points) compressed to 95 %, β = 0.01: time to accuracy\n({note})", fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "time_to_accuracy.png", dpi=130)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    rows = medians(sys.argv[1])
    out = pathlib.Path(sys.argv[2])
    out.mkdir(parents=True, exist_ok=True)
    scaling(rows, out)
    time_to_accuracy(rows, out)
