#!/usr/bin/python3
"""Plot columns of a fairshape runs.csv (or iterations.csv) to a PNG.

  scripts/plot.py results/x/latest/runs.csv --x n_dofs --y solve_s --hue solver.type --logx --logy -o out.png

Rows whose x or y is empty or not a number (failed runs) are left out and counted.
Uses Debian's python3-matplotlib (call /usr/bin/python3 if another python3 is first on PATH).
"""
import argparse
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("csv", help="runs.csv or iterations.csv")
    p.add_argument("--x", required=True, help="column on the x axis")
    p.add_argument("--y", required=True, action="append", help="column(s) on the y axis (repeatable)")
    p.add_argument("--hue", help="one line per value of this column")
    p.add_argument("--filter", action="append", default=[], help="keep rows with column=value (repeatable)")
    p.add_argument("--logx", action="store_true")
    p.add_argument("--logy", action="store_true")
    p.add_argument("--kind", choices=["line", "scatter"], default="line")
    p.add_argument("--title", default="")
    p.add_argument("-o", "--output", required=True, help="PNG file")
    return p.parse_args(argv)


def as_float(text):
    try:
        return float(text)
    except ValueError:
        return None


def main(argv):
    a = parse_args(argv)
    with open(a.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"plot: {a.csv} has no rows")
    columns = rows[0].keys()
    for col in [a.x, *a.y] + ([a.hue] if a.hue else []) + [f.split("=")[0] for f in a.filter]:
        if col not in columns:
            sys.exit(f"plot: no column '{col}' in {a.csv} (columns: {', '.join(columns)})")
    for flt in a.filter:
        key, _, value = flt.partition("=")
        rows = [r for r in rows if r[key] == value]
    series = defaultdict(list)
    skipped = 0
    for r in rows:
        for y in a.y:
            xv, yv = as_float(r[a.x]), as_float(r[y])
            if xv is None or yv is None or (a.logy and yv <= 0) or (a.logx and xv <= 0):
                skipped += 1
                continue
            label = " ".join(filter(None, [r[a.hue] if a.hue else "", y if len(a.y) > 1 else ""])) or y
            series[label].append((xv, yv))
    fig, ax = plt.subplots(figsize=(7, 4.5), dpi=120)
    for label, pts in sorted(series.items()):
        pts.sort()
        xs, ys = zip(*pts)
        if a.kind == "line":
            ax.plot(xs, ys, marker="o", ms=3, label=label)
        else:
            ax.scatter(xs, ys, s=12, label=label)
    ax.set_xlabel(a.x)
    ax.set_ylabel(", ".join(a.y))
    ax.set_xscale("log" if a.logx else "linear")
    ax.set_yscale("log" if a.logy else "linear")
    ax.grid(True, which="both", alpha=0.3)
    if a.title:
        ax.set_title(a.title)
    if len(series) > 1 or a.hue:
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.output)
    print(f"plot: wrote {a.output} ({sum(map(len, series.values()))} points, {skipped} skipped)")


if __name__ == "__main__":
    main(sys.argv[1:])
