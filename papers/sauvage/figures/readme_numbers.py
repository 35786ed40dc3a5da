#!/usr/bin/python3
"""The numbers papers/sauvage/README.md quotes from its benchmarks, generated from
papers/sauvage/data/bench/*.json (Google Benchmark, medians) rather than typed (run after the
benchmarks; or alone: readme_numbers.py [--check]).

Each block sits between `<!-- numbers:NAME -->` and `<!-- /numbers:NAME -->` in the README
(scripts/readme_blocks.py); --check only reports blocks that differ from the data (exit 1).
"""
import json
import math
import os
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
BENCH = os.path.join(ROOT, "data", "bench")
README = os.path.join(ROOT, "README.md")
sys.path.insert(0, os.path.join(ROOT, "..", "..", "scripts"))
import readme_blocks  # noqa: E402

MODES = {"0": "inertia (default)", "1": "dense", "2": "off"}


def medians(name):
    with open(os.path.join(BENCH, name)) as f:
        data = json.load(f)
    rows = [r for r in data["benchmarks"] if r.get("aggregate_name", "median") == "median"]
    return data["context"], rows


def ms(r):
    return r["real_time"] * {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[r["time_unit"]]


def arg(r, key):
    return r["run_name"].split(f"{key}:")[1].split("/")[0]


def machine(context):
    return (f"{context['num_cpus']} CPUs at {context['mhz_per_cpu']} MHz, {context['date'][:10]}, "
            f"{context.get('library_build_type', '?')} Google Benchmark library")


def drag():
    context, rows = medians("curve_drag_benchmark.json")
    out = [f"`data/bench/curve_drag_benchmark.json` ({machine(context)}; medians of "
           f"{rows[0].get('repetitions', '?')} repetitions):", "",
           "| points | check | largest window | step [ms] | solve [ms] | check [ms] | check / step | µs per point |",
           "|---|---|---|---|---|---|---|---|"]
    seen = set()
    for r in sorted(rows, key=lambda r: (arg(r, "mode"), int(arg(r, "log2_segments")))):
        if r["run_name"] in seen:  # a failed benchmark has no aggregates: one row per repetition
            continue
        seen.add(r["run_name"])
        points = 2 ** int(arg(r, "log2_segments")) + 1
        if r.get("error_occurred"):
            out.append(f"| {points:,} | {MODES[arg(r, 'mode')]} | – | not converged: {r.get('error_message', '')} | | | | |")
            continue
        out.append(f"| {points:,} | {MODES[arg(r, 'mode')]} | {int(r['window_points']):,} | {r['step_ms']:.2f} | "
                   f"{r['solve_ms']:.2f} | {r['check_ms']:.2f} | {100 * r['check_share']:.0f} % | {r['us_per_point']:.2f} |")
    # The goal: a drag step ≤ 16 ms up to 4k points, never slower per point at a smaller size.
    out.append("")
    for mode, label in MODES.items():
        ok = sorted((2 ** int(arg(r, "log2_segments")) + 1, r) for r in rows
                    if arg(r, "mode") == mode and not r.get("error_occurred") and "step_ms" in r)
        if not ok:
            continue
        small = [(p, r) for p, r in ok if p <= 4097]
        worst = max(r["step_ms"] for _, r in small)
        per_point = [r["us_per_point"] for _, r in ok]
        monotone = all(a <= b * 1.05 for a, b in zip(per_point, per_point[1:]))
        out.append(f"- {label}: slowest step up to 4,097 points {worst:.1f} ms "
                   f"({'within' if worst <= 16 else 'over'} the 16 ms goal); per point "
                   f"{'never slower at a smaller size (5 % noise allowed)' if monotone else 'slower at some smaller size'}.")
    return "\n".join(out)


def check():
    _, rows = medians("time_to_accuracy.json")
    by = {arg(r, "dense"): ms(r) for r in rows if r["name"].startswith("BM_SecondOrderCheck") and "dense:" in r["run_name"]}
    if not by:
        raise FileNotFoundError(None, None, "BM_SecondOrderCheck in time_to_accuracy.json")
    return (f"`BM_SecondOrderCheck` (129 points, the common minimum of the time-to-accuracy runs): inertia "
            f"{by['0']:.2f} ms, dense {by['1']:.1f} ms ({by['1'] / by['0']:.0f}× the inertia check).")


def edit129():
    context, rows = medians("curve_benchmark.json")
    t = {(arg(r, "optimized"), arg(r, "newton")): r for r in rows if r["name"].startswith("BM_Edit129")}
    cell = lambda o, n: f"{ms(t[(o, n)]):.2f} ms ({int(t[(o, n)]['solves'])} solves)"
    return "\n".join([f"`data/bench/curve_benchmark.json` ({machine(context)}; medians of {rows[0].get('repetitions', '?')}):", "",
                      "| | paper linearization | Newton |", "|---|---|---|",
                      f"| reference (block KKT, SparseLU each solve) | {cell('0', '0')} | {cell('0', '1')} |",
                      f"| optimized (banded LDLᵀ, one analysis) | {cell('1', '0')} | {cell('1', '1')} |"])


def scaling():
    _, rows = medians("curve_benchmark.json")
    pts = lambda flag: sorted((r["points"], ms(r)) for r in rows if r["name"].startswith("BM_EditScaling") and f"optimized:{flag}" in r["name"])
    opt, ref = pts(1), pts(0)
    n = len(opt)
    lx = [math.log(p) for p, _ in opt]
    ly = [math.log(t) for _, t in opt]
    mx, my = sum(lx) / n, sum(ly) / n
    slope = sum((x - mx) * (y - my) for x, y in zip(lx, ly)) / sum((x - mx) ** 2 for x in lx)
    r14 = dict(ref).get(16385)
    o14 = dict(opt).get(16385)
    line = (f"Optimized: {opt[0][1]:.2f} ms at {int(opt[0][0]):,} points → {opt[-1][1] / 1e3:.2f} s at {int(opt[-1][0]):,} "
            f"points, a log-log slope of **{slope:.2f}** (least squares over {n} sizes).")
    if r14 and o14:
        line += f" Reference (SparseLU) {r14 / o14:.1f}× slower at 16,385 points ({r14:.0f} vs {o14:.1f} ms)."
    return line


def time_to_accuracy():
    context, rows = medians("time_to_accuracy.json")
    labels = [("linearized_paper", "paper's loop"), ("linearized_newton", "Newton"), ("trust_region", "trust region"), ("ceres", "Ceres")]
    out = [f"`data/bench/time_to_accuracy.json` ({machine(context)}; medians of {rows[0].get('repetitions', '?')}); "
           "each cell: time, solves, largest distance to the common minimum:", "",
           "| length tolerance | " + " | ".join(l for _, l in labels) + " |", "|---" * (len(labels) + 1) + "|"]
    for tol in ("4", "8", "12"):
        cells = []
        for key, _ in labels:
            r = next((r for r in rows if r["run_name"] == f"BM_TimeToAccuracy/{key}/{tol}"), None)
            cells.append("–" if r is None or r.get("error_occurred") else
                         f"{ms(r):.1f} ms, {int(r['solves'])}, {r['distance_to_minimum']:.1e}")
        out.append(f"| 1e-{tol} | " + " | ".join(cells) + " |")
    return "\n".join(out)


BLOCKS = {"drag": drag, "check": check, "edit129": edit129, "scaling": scaling, "time_to_accuracy": time_to_accuracy}

if __name__ == "__main__":
    readme_blocks.main(README, BLOCKS)
