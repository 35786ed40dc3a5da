#!/usr/bin/python3
"""Plot columns of a fairshape results table (runs.csv, iterations.csv, steps.csv) to a PNG.

  scripts/plot.py results/x/latest/runs.csv --x n_dofs --y solve_s --hue solver.type --logx --logy -o out.png
  scripts/plot.py results/x/latest/runs.csv --x solver.type --y solve_s --kind strip -o out.png
  scripts/plot.py results/x/latest/iterations.csv --x iteration --y residual --hue solver.type --logy -o out.png

A numeric x draws lines or points; a categorical x (solver names, modes) draws every row as a
point per category with its median (strip), the median with the min-max range (bar), or
boxes (box). A table beside its runs.csv (iterations.csv, steps.csv) is joined with it on
run_id, so --hue and --filter can name any runs.csv column (a swept parameter, solver.type).
Without --hue, a table with several runs gets one series per run, labelled by its swept
parameters rather than its hash. Known columns are labelled with their units.
Rows whose x or y cannot be plotted (empty, not a number, not positive on a log axis) are left
out and counted; when nothing is left, the plot is refused with the reason and nothing is written.
Uses Debian's python3-matplotlib (call /usr/bin/python3 if another python3 is first on PATH).
"""
import argparse
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

UNITS = {
    "solve_s": "solve time (s)", "solve_min_s": "fastest solve (s)", "analyze_s": "analysis time (s)",
    "assemble_s": "assembly time (s)", "subdivide_s": "hierarchy build (s)", "time_s": "wall time (s)",
    "explicit_s": "explicit step time (s)", "apply_s": "feature application (s)", "seconds": "time (s)",
    "reference_solve_s": "reference solve (s)", "peak_rss_mb": "peak resident memory (MB)",
    "solve_extra_mb": "memory the solve added (MB)", "n_dofs": "unknowns", "n_fine": "finest-level vertices",
    "n_constrained": "constraint rows", "iterations": "iterations", "iteration": "iteration",
    "residual": "relative residual", "energy": "energy", "constraint_violation": "constraint residual |A dP - C|",
    "error_vs_reference": "relative error vs direct solve", "detail_change": "relative detail change",
    "length_error_max": "max relative length error", "length_error_rms": "rms relative length error",
    "bending_energy": "bending energy", "max_displacement": "max displacement (model units)",
}


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("csv", help="runs.csv, or a table beside one (iterations.csv, steps.csv)")
    p.add_argument("--x", required=True, help="column on the x axis (numeric or categorical)")
    p.add_argument("--y", required=True, action="append", help="column(s) on the y axis (repeatable)")
    p.add_argument("--hue", help="one series per value of this column (any runs.csv column)")
    p.add_argument("--filter", action="append", default=[], help="keep rows with column=value (repeatable)")
    p.add_argument("--logx", action="store_true")
    p.add_argument("--logy", action="store_true")
    p.add_argument("--kind", choices=["line", "scatter", "strip", "bar", "box"],
                   help="line or scatter for a numeric x (default line); strip, bar or box for a categorical one "
                        "(default strip)")
    p.add_argument("--xlabel", help="x-axis label (default: the column, with its unit)")
    p.add_argument("--ylabel", help="y-axis label (default: the columns, with their units)")
    p.add_argument("--title", default="")
    p.add_argument("-o", "--output", required=True, help="PNG file")
    p.add_argument("--data", help="also write the plotted points (series, x, y) to this CSV")
    return p.parse_args(argv)


def as_float(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


def read_rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def varying_parameters(runs):
    """What tells the runs apart: the swept parameters (runs.csv's columns between run_id and
    implementation) and the identity columns, those whose values differ between runs."""
    cols = list(runs[0].keys())
    end = cols.index("implementation") if "implementation" in cols else 1
    candidates = list(dict.fromkeys(cols[1:end] + [c for c in ("implementation", "solver.type") if c in cols]))
    return [c for c in candidates if len({r[c] for r in runs}) > 1]


def joined_rows(path):
    """The table's rows with their run's runs.csv columns added (the table's own win), and a
    `run` column: the run's swept parameters, as a label."""
    rows = read_rows(path)
    beside = os.path.join(os.path.dirname(path), "runs.csv")
    runs = read_rows(beside) if os.path.basename(path) != "runs.csv" and os.path.exists(beside) else []
    if os.path.basename(path) == "runs.csv":
        runs = rows
    if not runs:
        return rows
    swept = varying_parameters(runs)
    by_id = {r["run_id"]: r for r in runs}
    for r in rows:
        run = by_id.get(r.get("run_id"), {})
        for k, v in run.items():
            r.setdefault(k, v)
        r["run"] = ", ".join(f"{k}={run[k]}" for k in swept if k in run) or r.get("run_id", "")
    return rows


def label_of(columns):
    return ", ".join(UNITS.get(c, c) for c in columns)


def main(argv):
    a = parse_args(argv)
    out_dir = os.path.dirname(os.path.abspath(a.output))
    if not os.path.isdir(out_dir):
        sys.exit(f"plot: the output folder {out_dir} does not exist")
    rows = joined_rows(a.csv)
    if not rows:
        sys.exit(f"plot: {a.csv} has no rows: nothing to plot")
    columns = list(rows[0].keys())
    for col in [a.x, *a.y] + ([a.hue] if a.hue else []) + [f.split("=")[0] for f in a.filter]:
        if col not in columns:
            sys.exit(f"plot: no column '{col}' in {a.csv} (columns: {', '.join(columns)})")
    for flt in a.filter:
        key, _, value = flt.partition("=")
        rows = [r for r in rows if r[key] == value]
        if not rows:
            sys.exit(f"plot: no row has {key}={value}: nothing to plot")
    hue = a.hue or ("run" if "run" in columns and len({r.get("run_id") for r in rows}) > 1 and a.x in ("iteration", "step") else None)
    categorical = any(as_float(r[a.x]) is None and r[a.x] != "" for r in rows)
    kind = a.kind or ("strip" if categorical else "line")
    if categorical and kind == "scatter":
        kind = "strip"  # points at their category
    if categorical != (kind in ("strip", "bar", "box")):
        sys.exit(f"plot: --kind {kind} needs a {'categorical' if kind in ('strip', 'bar', 'box') else 'numeric'} x; "
                 f"'{a.x}' is {'categorical' if categorical else 'numeric'}")
    series = defaultdict(list)
    skipped = defaultdict(int)
    for r in rows:
        for y in a.y:
            xv = r[a.x] if categorical else as_float(r[a.x])
            yv = as_float(r[y])
            why = ("x empty" if r[a.x] == "" else "x not a number" if xv is None else
                   "y empty or not a number" if yv is None else
                   "y not positive on a log axis" if a.logy and yv <= 0 else
                   "x not positive on a log axis" if a.logx and not categorical and xv <= 0 else None)
            if why:
                skipped[why] += 1
                continue
            label = " ".join(filter(None, [r[hue] if hue else "", y if len(a.y) > 1 else ""])) or y
            series[label].append((xv, yv))
    reasons = ", ".join(f"{n} {why}" for why, n in skipped.items())
    if not series:
        sys.exit(f"plot: nothing to plot: every one of {len(rows) * len(a.y)} points was left out ({reasons})")
    if a.data:
        with open(a.data, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["series", a.x, "y"])
            for label, pts in sorted(series.items()):
                w.writerows([label, x, y] for x, y in pts)
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=120)
    if categorical:
        draw_categorical(ax, series, kind)
    else:
        for label, pts in sorted(series.items()):
            pts.sort()
            xs, ys = zip(*pts)
            if kind == "line":
                ax.plot(xs, ys, marker="o" if len(xs) <= 60 else None, ms=3, label=label)
            else:
                ax.scatter(xs, ys, s=12, label=label)
        ax.set_xscale("log" if a.logx else "linear")
    ax.set_xlabel(a.xlabel or label_of([a.x]))
    ax.set_ylabel(a.ylabel or label_of(a.y))
    ax.set_yscale("log" if a.logy else "linear")
    ax.grid(True, which="both", alpha=0.3)
    if a.title:
        ax.set_title(a.title)
    if len(series) > 1 or hue:
        ax.legend(fontsize=7, title=UNITS.get(hue, hue) if hue and hue != "run" else None)
    fig.tight_layout()
    tmp = a.output + ".tmp.png"
    fig.savefig(tmp)
    os.replace(tmp, a.output)  # never a truncated plot
    points = sum(map(len, series.values()))
    print(f"plot: wrote {a.output} ({points} points" + (f"; left out: {reasons}" if reasons else "") + ")")


def draw_categorical(ax, series, kind):
    """Every row as a point at its category (strip), the median with the min-max range (bar),
    or boxes; series side by side within a category."""
    categories = list(dict.fromkeys(x for pts in series.values() for x, _ in pts))  # in the table's (config's) order
    names = sorted(series)
    width = 0.8 / len(names)
    for s, name in enumerate(names):
        by_cat = defaultdict(list)
        for x, y in series[name]:
            by_cat[x].append(y)
        offset = (s - (len(names) - 1) / 2) * width
        xs = [categories.index(c) + offset for c in by_cat]
        values = [sorted(v) for v in by_cat.values()]
        medians = [v[len(v) // 2] if len(v) % 2 else 0.5 * (v[len(v) // 2 - 1] + v[len(v) // 2]) for v in values]
        colour = f"C{s % 10}"
        if kind == "strip":
            for x, v in zip(xs, values):
                jitter = [x + width * 0.3 * ((k % 5) / 4 - 0.5) for k in range(len(v))]
                ax.scatter(jitter, v, s=14, color=colour, alpha=0.8, label=name if x == xs[0] else None)
            ax.scatter(xs, medians, marker="_", s=400, color="k", zorder=3)
        elif kind == "bar":
            lo = [m - v[0] for m, v in zip(medians, values)]
            hi = [v[-1] - m for m, v in zip(medians, values)]
            ax.bar(xs, medians, width=width * 0.9, color=colour, label=name, yerr=[lo, hi], capsize=3)
        else:
            ax.boxplot(values, positions=xs, widths=width * 0.8, patch_artist=True,
                       boxprops={"facecolor": colour, "alpha": 0.6}, medianprops={"color": "k"})
            ax.scatter([], [], color=colour, label=name)
    ax.set_xticks(range(len(categories)))
    shown = [c if len(c) <= 28 else c[:25] + "..." for c in categories]  # a swept list can be long
    long = max(map(len, shown)) > 8
    ax.set_xticklabels(shown, rotation=20 if long else 0, ha="right" if long else "center")


if __name__ == "__main__":
    main(sys.argv[1:])
