#!/usr/bin/python3
"""The measured numbers papers/welch-witkin/README.md quotes in its marked blocks, generated from
papers/welch-witkin/data/ (readme_numbers.py [--check]; make_figures.sh runs it).

The block machinery (markers `<!-- numbers:NAME -->` ... `<!-- /numbers:NAME -->`, --check) is
scripts/readme_blocks.py; the number formats are papers/boier-martin/figures/readme_numbers.py's,
loaded and pointed at this paper's data.
"""
import importlib.util
import json
import os

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
_spec = importlib.util.spec_from_file_location(
    "boier_martin_readme_numbers", os.path.join(ROOT, "..", "boier-martin", "figures", "readme_numbers.py"))
shared = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(shared)
shared.DATA = os.path.join(ROOT, "data")
shared.README = os.path.join(ROOT, "README.md")
rows, table, fixed, sci, count = shared.rows, shared.table, shared.fixed, shared.sci, shared.count


def medians(name):
    """{benchmark name: its median row} of a Google Benchmark JSON run with repetitions."""
    with open(os.path.join(shared.DATA, name)) as f:
        run = json.load(f)
    out = {b["run_name"]: b for b in run["benchmarks"] if b.get("aggregate_name") == "median"}
    return run["context"], out


def drag_step():
    context, m = medians("bench/sheet_step_benchmark.json")
    cases = [("range space (factor updated)", "range_space_checks_only", None),
             ("KKT, factored every step", "kkt_refactored_checks_only", None),
             ("KKT, factorization reused", "kkt_checks_only", "kkt_refactored_checks_only"),
             ("QR-penalty, factored every step", "qr_penalty_refactored_checks_only", None),
             ("QR-penalty, factorization reused", "qr_penalty_checks_only", "qr_penalty_refactored_checks_only")]
    body = []
    for label, key, against in cases:
        b = m[f"BM_SheetDragStep/{key}"]
        ratio = f"{b['real_time'] / m[f'BM_SheetDragStep/{against}']['real_time']:.3f}×" if against else ""
        body.append([label, fixed(b["real_time"], 1), fixed(b["analyze_ms"], 2), fixed(b["solve_ms"], 2), ratio])
    return table(["drag step (32 × 32 spans, 1,225 unknowns, exact checks)", "median ms", "analyze ms", "solve ms",
                  "vs factored every step"], body) + \
        f"\n\nMedians of {m['BM_SheetDragStep/kkt_checks_only']['repetitions']} repetitions, one run, " \
        f"{context['date'][:10]}, {context['num_cpus']} cores (shared with other work: the ratios are the result)."


def memory():
    data = rows("memory_rss.csv")
    builds = list(dict.fromkeys(r["build"] for r in data))
    levels = sorted({int(r["max_level"]) for r in data})
    at = {(r["build"], int(r["max_level"])): r for r in data}
    body = []
    for level in levels:
        line = [str(level), count(next(at[(b, level)]["dofs"] for b in builds if (b, level) in at))]
        for b in builds:
            r = at.get((b, level))
            line += [count(r["peak_rss_mb"]) if r else "–", fixed(r["time_s"], 1) if r else "–"]
        if len(builds) == 2 and all((b, level) in at for b in builds):
            line.append(f"{float(at[(builds[1], level)]['peak_rss_mb']) / float(at[(builds[0], level)]['peak_rss_mb']):.2f}×")
        body.append(line)
    header = ["max_level", "unknowns"]
    for b in builds:
        header += [f"{b}: peak MB", f"{b}: s"]
    if len(builds) == 2:
        header.append("peak ratio")
    return table(header, body)


def primitives():
    labels = ["ribbon: a straight curve lifted 0.3, the slope across it kept flat",
              "a region held as it is, the curve raised 0.3 beside it", "an offset pair added"]
    body = [[r["step"], labels[int(r["step"])] if int(r["step"]) < len(labels) else "", count(r["constraint_rows"]),
             r["dropped_rows"], fixed(r["energy"], 4), sci(r["max_constraint_error"])] for r in rows("primitives_steps.csv")]
    return table(["step", "what", "rows", "dropped", "energy", "max constraint error"], body)


BLOCKS = {"ww_drag_step": drag_step, "ww_memory": memory, "ww_primitives": primitives}

if __name__ == "__main__":
    shared.readme_blocks.main(shared.README, BLOCKS)
