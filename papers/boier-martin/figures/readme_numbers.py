#!/usr/bin/python3
"""The numbers papers/boier-martin/README.md quotes in its figure sections, generated from
papers/boier-martin/data/ (run by make_figures.sh; or alone: readme_numbers.py [--check]).

Each block sits between `<!-- numbers:NAME -->` and `<!-- /numbers:NAME -->` in the README
and is rewritten whole from its CSVs; text outside the markers is left as it is. --check
only reports blocks that differ from the data (exit 1), for CI or a reviewer.
"""
import csv
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "scripts"))
import readme_blocks  # noqa: E402

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
DATA = os.path.join(ROOT, "data")
README = os.path.join(ROOT, "README.md")


def rows(name):
    with open(os.path.join(DATA, name)) as f:
        return list(csv.DictReader(f))


def num(x):
    try:
        return float(x)
    except (TypeError, ValueError):
        return None


def sci(x, digits=1):
    v = num(x)
    if v is None:
        return "–"
    if v == 0:
        return "0"
    return f"{v:.{digits}e}".replace("e-0", "e-").replace("e+0", "e")


def fixed(x, digits=3):
    v = num(x)
    return "–" if v is None else f"{v:.{digits}f}"


def pct(x, digits=1):
    v = num(x)
    return "–" if v is None else f"{100 * v:.{digits}f} %"


def count(x):
    v = num(x)
    return "–" if v is None else f"{int(round(v)):,}"


def table(header, body):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(r) + " |" for r in body]
    return "\n".join(lines)


def influence(row):
    """(handle, level, rings) of a Figure 1 row, from its constraints and its message."""
    c = row["constraints"]
    where = "nose" if "nearest: [0.5, 0.0, 0.0]" in c else "back"
    level = re.findall(r"influence_level: (\d+)", c)[-1]
    rings = re.search(r"level \d+: (\d+) of (\d+) vertices(?:, (\d+) rings)?", row["message"])
    given = re.findall(r"influence_rings: (\d+)", c)
    ring_text = (given[-1] if given else (rings.group(3) + " (auto)" if rings and rings.group(3) else "auto"))
    region = f"{int(rings.group(1)):,} of {int(rings.group(2)):,}" if rings else "–"
    return where, level, ring_text, region


def fig1():
    body = []
    for r in rows("fig1_runs.csv"):
        where, level, rings, region = influence(r)
        handle = "nose, (0.06, 0.1, 0)" if where == "nose" else "back, (0, 0.04, 0)"
        body.append([handle, level, rings, region, pct(r.get("region_fraction"), 2), fixed(r["detail_change"]),
                     fixed(r["spike_ratio"], 2), count(r.get("flipped_faces")), sci(r["constraint_violation"]),
                     r["termination"]])
    return table(["handle, move", "influence level", "rings", "region: level-k vertices", "region: finest vertices",
                  "detail change", "spike ratio", "flipped faces", "constraint violation", "termination"], body)


def fig2():
    names = ["thin plate (of the surface), back third held",
             "thin plate (of the surface), held but for the nose's level-1 region (4 rings)",
             "detail-preserving (of the deformation), back third held"]
    body = []
    for name, r in zip(names, rows("fig2_runs.csv")):
        body.append([name, fixed(r["detail_change"], 3), fixed(r["spike_ratio"], 2), count(r.get("flipped_faces")),
                     pct(r["region_fraction"], 1) if r.get("region_fraction") else "the level", sci(r["constraint_violation"]),
                     r["termination"]])
    return table(["energy, constraints", "detail change", "spike ratio", "flipped faces", "free to move", "constraint residual",
                  "termination"], body)


def constraint_kind(row):
    """point, normal or curve: the kind a Figure 7 run adds to its fixed region."""
    c = row["constraints"]
    if "type: curve" in c:
        where = "limit points" if "limit_points" in c else "snapped vertices"
        return "curve" + (f" ({count(row['curve_points'])} {where})" if num(row.get("curve_points")) else "")
    return "normal" if "type: normal" in c else "point"


def fig7():
    body = [[constraint_kind(r), count(r["n_constrained"]), fixed(r["detail_change"]), fixed(r["spike_ratio"]),
             count(r.get("flipped_faces")), sci(r["constraint_violation"], 0), r["termination"]]
            for r in rows("fig7_runs.csv")]
    return table(["constraints", "constrained vertices", "detail change", "spike ratio", "flipped faces",
                  "constraint residual", "termination"], body)


def fig7_vase():
    body = []
    for r in rows("fig7_vase_runs.csv"):
        e = num(r.get("energy_vs_optimum"))
        body.append([constraint_kind(r), fixed(r["spike_ratio"], 2), "–" if e is None else f"{e:.3f}",
                     count(r.get("flipped_faces")), sci(r["constraint_violation"], 0), r["termination"]])
    return table(["constraints (paper mode)", "spike ratio", "energy vs the KKT optimum", "flipped faces",
                  "constraint residual", "termination"], body)


def dense_scan_kkt():
    body = []
    for r in rows("dense_scan_kkt_runs.csv"):
        e = num(r.get("energy_vs_optimum"))
        how = "held unknowns eliminated, range space" if "range-space" in r["message"] else \
            "equilibrated" if "equilibrated" in r["message"] else \
            "the Lagrange system" if r["problem.constraint_mode"] == "kkt" else "the paper's split (CHOLMOD)"
        body.append([r["problem.constraint_mode"], count(r["n_dofs"]), how, f"{num(r['energy']):.7g}",
                     "–" if e is None else f"{e:.6f}", sci(r["constraint_violation"], 0), fixed(r["analyze_s"], 1),
                     fixed(r["solve_s"], 2), r["termination"]])
    return table(["constraint mode", "unknowns", "solved by", "energy", "energy vs optimum", "constraint residual",
                  "analysis (s)", "solve (s)", "termination"], body)


def fig8():
    names = {("interactive", "gauss_seidel", "10"): ("interactive", "–"),
             ("improved", "gauss_seidel", "10"): ("improved (the paper's)", "10 Gauss-Seidel sweeps"),
             ("improved", "multigrid_cg", "1"): ("improved", "1 multigrid-CG iteration"),
             ("improved", "multigrid_cg", "2"): ("improved (**default**)", "2 multigrid-CG iterations"),
             ("improved", "multigrid_cg", "5"): ("improved", "5 multigrid-CG iterations"),
             ("converged", "gauss_seidel", "10"): ("converged", "multigrid-CG to 1e-10")}
    body = []
    for r in rows("fig8_runs.csv"):
        mode, relax = names.get((r["problem.accuracy"], r["problem.relaxation"], r["problem.relaxation_sweeps"]),
                                (r["problem.accuracy"], r["problem.relaxation"]))
        e = num(r.get("energy_vs_optimum"))
        body.append([mode, relax, sci(r["error_vs_reference"]), "–" if e is None else f"{e:.4g}",
                     count(r.get("flipped_faces")), r["termination"], fixed(r["solve_s"], 2), fixed(r["analyze_s"], 1)])
    return table(["mode", "relaxation per level (levels 3, 4)", "error vs converged", "energy vs optimum",
                  "flipped faces", "termination", "solve (s)", "analysis (s)"], body)


def fig8_ladder():
    path = os.path.join(DATA, "fig8_ladder_constrained.txt")
    body = []
    for line in open(path):
        m = re.match(r"level (\d+): (\d+) vertices reached by the handle's propagated rows, (\d+) by the fixed "
                     r"region's, (\d+) in all", line)
        if m:
            body.append([m.group(1), f"{int(m.group(2)):,}", f"{int(m.group(3)):,}", f"{int(m.group(4)):,}"])
    return table(["level", "vertices the handle's rows reach", "vertices the fixed region's rows reach",
                  "vertices"], body)


def fig9():
    body = []
    for r in rows("fig9_runs.csv"):
        angle = re.findall(r"angle_deg: ([-0-9.]+)", r["constraints"])[-1]
        body.append([f"{float(angle):g}°", f"{num(r['energy']):.4g}", sci(r["constraint_violation"]),
                     count(r.get("flipped_faces")), r["termination"]])
    return table(["inner rim turned", "energy", "constraint residual", "flipped faces", "termination"], body)


def fig9_vase():
    steps = rows("fig9_vase_steps.csv")
    columns = [("step", "step", str), ("solve (s)", "solve_s", lambda v: fixed(v, 4)),
               ("error vs CHOLMOD (finest level)", "error_vs_reference", lambda v: sci(v, 3)),
               ("constraint violation", "constraint_violation", sci),
               ("CHOLMOD's prefactored solve (s)", "reference_solve_s", lambda v: fixed(v, 3)),
               ("fold check (s)", "check_s", lambda v: fixed(v, 4) if v else "")]
    columns = [c for c in columns if any(r.get(c[1]) for r in steps)]  # the data's, not empty ones
    body = [[f(r[key]) for _, key, f in columns] for r in steps]
    run = rows("fig9_vase_runs.csv")[0]
    return table([c[0] for c in columns], body) + \
        f"\n\nThe run: {run['termination']}, {count(run.get('flipped_faces'))} faces flipped at its last step."


BLOCKS = {"fig1": fig1, "fig2": fig2, "fig7": fig7, "fig7_vase": fig7_vase, "dense_scan_kkt": dense_scan_kkt, "fig8": fig8, "fig8_ladder": fig8_ladder, "fig9": fig9, "fig9_vase": fig9_vase}


if __name__ == "__main__":
    readme_blocks.main(README, BLOCKS)
