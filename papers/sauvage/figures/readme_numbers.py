#!/usr/bin/python3
"""The numbers papers/sauvage/README.md quotes from its benchmarks, generated from
papers/sauvage/data/bench/*.json (Google Benchmark, medians) rather than typed (run after the
benchmarks; or alone: readme_numbers.py [--check]).

Each block sits between `<!-- numbers:NAME -->` and `<!-- /numbers:NAME -->` in the README
(scripts/readme_blocks.py); --check only reports blocks that differ from the data (exit 1).
"""
import json
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
    for r in sorted(rows, key=lambda r: (arg(r, "mode"), r["points"])):
        if r.get("error_occurred"):
            out.append(f"| {int(r['points']):,} | {MODES[arg(r, 'mode')]} | – | error: {r.get('error_message', '')} | | | | |")
            continue
        out.append(f"| {int(r['points']):,} | {MODES[arg(r, 'mode')]} | {int(r['window_points']):,} | {r['step_ms']:.2f} | "
                   f"{r['solve_ms']:.2f} | {r['check_ms']:.2f} | {100 * r['check_share']:.0f} % | {r['us_per_point']:.2f} |")
    return "\n".join(out)


def check():
    _, rows = medians("curve_benchmark.json")
    by = {arg(r, "dense"): ms(r) for r in rows if r["name"].startswith("BM_SecondOrderCheck")}
    if not by:
        raise FileNotFoundError(None, None, "BM_SecondOrderCheck in curve_benchmark.json")
    return (f"`BM_SecondOrderCheck` (129 points, the common minimum of the time-to-accuracy runs): inertia "
            f"{by['0']:.2f} ms, dense {by['1']:.1f} ms ({by['1'] / by['0']:.0f}× the inertia check).")


BLOCKS = {"drag": drag, "check": check}

if __name__ == "__main__":
    readme_blocks.main(README, BLOCKS)
