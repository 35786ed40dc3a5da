#!/usr/bin/python3
"""Plot columns of a fairshape results table (runs.csv, iterations.csv, steps.csv) to a PNG.

  scripts/plot.py results/x/latest/runs.csv --x n_dofs --y solve_s --hue solver.type --logx --logy -o out.png
  scripts/plot.py results/x/latest/runs.csv --x solver.type --y solve_s --kind strip -o out.png
  scripts/plot.py results/x/latest/iterations.csv --x iteration --y residual --hue solver.type --logy -o out.png
  scripts/plot.py results/x/latest/iterations.csv --x iteration --y residual --hue solver.type --estimator median -o out.png

A numeric x draws lines or points. A line never joins runs that share an x: by default each
run (or, in runs.csv, each combination of the swept parameters that x does not follow) is its
own line, coloured by --hue and told apart by line style (the parameters that split it are
named in the legend), and a warning says which hue values hold several lines. --estimator
median|mean instead draws one line per hue value, the estimator over its runs at each x, with
the --spread band (range: min to max, sd, or none), and says so. a categorical x (solver names, modes) draws every row as a
point per category with its median (strip), the median with the min-max range (bar), or
boxes (box). A table beside its runs.csv (iterations.csv, steps.csv) is joined with it on
run_id, so --hue and --filter can name any runs.csv column (a swept parameter, solver.type).
Without --hue, a table with several runs gets one series per run, labelled by its swept
parameters rather than its hash. Known columns are labelled with their units.
Rows whose x or y cannot be plotted (empty, not a number, not positive on a log axis) are left
out and counted; when nothing is left, the plot is refused with the reason and nothing is written.
Uses Debian's python3-matplotlib and python3-seaborn (call /usr/bin/python3 if another python3 is first on PATH).
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
    "assemble_s": "assembly time (s)", "setup_s": "shared set-up (s)", "time_s": "wall time (s)",
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
    p.add_argument("--estimator", choices=["none", "median", "mean"], default="none",
                   help="numeric x: none (default) draws one line per run; median or mean draws one line per hue "
                        "value, that estimator over its runs at each x")
    p.add_argument("--spread", choices=["range", "sd", "none"], default="range",
                   help="with --estimator: the band around the line (range: min to max; sd: one standard deviation)")
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
    `run` column: the run's swept parameters, as a label; and the parameters that vary."""
    rows = read_rows(path)
    beside = os.path.join(os.path.dirname(path), "runs.csv")
    runs = read_rows(beside) if os.path.basename(path) != "runs.csv" and os.path.exists(beside) else []
    if os.path.basename(path) == "runs.csv":
        runs = rows
    if not runs:
        return rows, []
    swept = varying_parameters(runs)
    by_id = {r["run_id"]: r for r in runs}
    for r in rows:
        run = by_id.get(r.get("run_id"), {})
        for k, v in run.items():
            r.setdefault(k, v)
        r["run"] = ", ".join(f"{k}={run[k]}" for k in swept if k in run) or r.get("run_id", "")
    return rows, swept


def label_of(columns):
    return ", ".join(UNITS.get(c, c) for c in columns)


def main(argv):
    a = parse_args(argv)
    out_dir = os.path.dirname(os.path.abspath(a.output))
    if not os.path.isdir(out_dir):
        sys.exit(f"plot: the output folder {out_dir} does not exist")
    rows, swept = joined_rows(a.csv)
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
    if a.estimator != "none" and kind != "line":
        sys.exit(f"plot: --estimator {a.estimator} draws lines: it needs a numeric x and --kind line; a categorical "
                 "x already shows every run (strip), the median with the min-max range (bar) or boxes (box)")
    series = defaultdict(list)
    points = []  # (series, x, y, row) of every point drawn
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
            points.append((label, xv, yv, r))
    reasons = ", ".join(f"{n} {why}" for why, n in skipped.items())
    if not series:
        sys.exit(f"plot: nothing to plot: every one of {len(rows) * len(a.y)} points was left out ({reasons})")
    lines = None
    if not categorical:
        per_run = os.path.basename(a.csv) != "runs.csv" and "run_id" in columns
        candidates = [c for c in swept if c not in (a.x, hue)]
        lines = split_lines(points, candidates, per_run)
        say_how_runs_are_drawn(lines, hue, a, kind)
    if a.data:
        with open(a.data, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["series", a.x, "y", "line"])
            for i, (label, x, y, _) in sorted(enumerate(points), key=lambda p: (p[1][0], p[0])):
                w.writerow([label, x, y, label if lines is None or a.estimator != "none" else lines.line[i]])
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=120)
    if categorical:
        draw_categorical(ax, series, kind)
    else:
        draw_numeric(ax, points, lines, hue, kind, a)
        ax.set_xscale("log" if a.logx else "linear")
    ax.set_xlabel(a.xlabel or label_of([a.x]))
    ax.set_ylabel(a.ylabel or label_of(a.y))
    ax.set_yscale("log" if a.logy else "linear")
    ax.grid(True, which="both", alpha=0.3)
    if a.title:
        ax.set_title(a.title)
    if categorical and (len(series) > 1 or hue):
        ax.legend(fontsize=7, title=UNITS.get(hue, hue) if hue and hue != "run" else None)
    fig.tight_layout()
    tmp = a.output + ".tmp.png"
    fig.savefig(tmp)
    os.replace(tmp, a.output)  # never a truncated plot
    print(f"plot: wrote {a.output} ({len(points)} points" + (f"; left out: {reasons}" if reasons else "") + ")")
    return fig


class Lines:
    """How the points of a numeric x are split into lines: `style` the parameters that split a
    series (its runs would otherwise share an x on one line), `line` each point's line."""

    def __init__(self, style, line, per_series, points):
        self.style, self.line, self.per_series, self.points = style, line, per_series, points


def split_lines(points, candidates, per_run):
    """A parameter splits the lines when two points of one series at one x differ in it; in a
    per-run table (iterations.csv) every run is its own line whatever its parameters say."""
    style = []

    def key(p):
        return (p[0],) + tuple(p[3].get(c, "") for c in style)

    for c in candidates:
        values = defaultdict(set)
        for p in points:
            values[key(p) + (p[1],)].add(p[3].get(c, ""))
        if any(len(v) > 1 for v in values.values()):
            style.append(c)
    line = [" | ".join(map(str, key(p) + ((p[3].get("run_id", ""),) if per_run else ()))) for p in points]
    per_series = defaultdict(set)
    for p, name in zip(points, line):
        per_series[p[0]].add(name)
    return Lines(style, line, per_series, points)


def say_how_runs_are_drawn(lines, hue, a, kind):
    """A hue value holding several runs is never silent: one line each (told apart by style) is
    the default, and an estimator says what it draws. Points that one line would still join
    at one x (runs.csv rows of identical parameters) are refused unless an estimator is named."""
    crowded = {s: len(n) for s, n in lines.per_series.items() if len(n) > 1}
    if a.estimator != "none":
        spread = {"range": "its band the min-max range", "sd": "its band one standard deviation",
                  "none": "no band"}[a.spread]
        print(f"plot: each line is the {a.estimator} over the runs of one {hue or 'series'} value at each x, {spread}"
              + (f" ({', '.join(f'{s}: {n} runs' for s, n in sorted(crowded.items()))})" if crowded else ""),
              file=sys.stderr)
        return
    if kind == "line":
        seen = defaultdict(list)
        for p, name in zip(lines.points, lines.line):
            seen[(name, p[1])].append(p[3].get("run_id", "?"))
        clash = next((ids for ids in seen.values() if len(ids) > 1), None)
        if clash:
            sys.exit(f"plot: runs {', '.join(sorted(set(clash)))} would share an x on one line (nothing tells them "
                     f"apart); name --estimator median or mean to aggregate them, or --hue/--filter to separate them")
    if crowded and hue and hue != "run":
        how = f"told apart by style ({', '.join(lines.style)})" if lines.style else "one per run"
        for s, n in sorted(crowded.items()):
            print(f"plot: warning: {hue}={s} holds {n} runs: drawn as {n} lines, {how}; --estimator median "
                  f"draws one line per {hue} value", file=sys.stderr)


def draw_numeric(ax, points, lines, hue, kind, a):
    """seaborn draws the lines: units= keeps every run its own line (estimator=None), or an
    estimator with its band aggregates the runs of a hue value."""
    import pandas as pd
    import seaborn as sns

    hue_name = (UNITS.get(hue, hue) if hue and hue != "run" else "run") if hue else "series"
    style_name = ", ".join(lines.style) or None
    df = pd.DataFrame({"x": [p[1] for p in points], "y": [p[2] for p in points],
                       hue_name: [p[0] for p in points], "line": lines.line})
    if style_name:
        df[style_name] = [", ".join(p[3].get(c, "") for c in lines.style) for p in points]
    order = sorted(set(df[hue_name]))
    few = df.groupby("line").size().max() <= 60
    common = dict(data=df, x="x", y="y", hue=hue_name, hue_order=order, ax=ax, legend="auto" if len(order) > 1 or hue else False)
    if kind == "scatter":
        sns.scatterplot(style=style_name, s=14, **common)
    elif a.estimator == "none":
        sns.lineplot(style=style_name, units="line", estimator=None, marker="o" if few else None, ms=3, **common)
    else:
        band = {"range": ("pi", 100), "sd": "sd", "none": None}[a.spread]
        sns.lineplot(estimator=a.estimator, errorbar=band, marker="o" if few else None, ms=3, **common)
    if ax.get_legend():
        sns.move_legend(ax, "best", fontsize=7)


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
