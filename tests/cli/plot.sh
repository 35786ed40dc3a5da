# scripts/plot.py: a categorical x draws every row, a table beside runs.csv is joined with it
# (hue by a swept parameter), runs are labelled by their parameters, and a plot with nothing
# to draw is refused without writing a file.
source "$(dirname "$0")/lib.sh"
S="$SCRATCH"
P=(/usr/bin/python3 scripts/plot.py)
"$FS" run configs/smoke/cow_nose_pull.yaml --out "$S/sweep" --set 'sweep.solver.type=[cholesky, conjugate_gradient, sor]' \
  --set 'sweep.solver.tolerance=[1.0e-6, 1.0e-9]' 2>/dev/null || true  # sor may stop at its cap: a row all the same
rows=$(data_rows "$S/sweep/runs.csv")
[ "$rows" -eq 6 ] || fail "the sweep wrote $rows rows, expected 6"
# The README's first plot: a categorical x with --kind scatter.
"${P[@]}" "$S/sweep/runs.csv" --x solver.type --y solve_s --hue implementation --logy --kind scatter \
  -o "$S/cat.png" --data "$S/cat.csv" > /dev/null || fail "categorical x"
[ "$(data_rows "$S/cat.csv")" -eq "$rows" ] || fail "a categorical plot drew $(data_rows "$S/cat.csv") of $rows rows"
for kind in bar box; do
  "${P[@]}" "$S/sweep/runs.csv" --x solver.type --y time_s --kind $kind -o "$S/$kind.png" > /dev/null || fail "--kind $kind"
done
# iterations.csv has no solver.tolerance column: it comes from runs.csv, by run_id.
"${P[@]}" "$S/sweep/iterations.csv" --x iteration --y residual --hue solver.tolerance --logy -o "$S/it.png" \
  --data "$S/it.csv" > /dev/null || fail "hue by a runs.csv column"
$PY - "$S/it.csv" "$S/sweep/runs.csv" <<'PYEOF'
import csv, sys
series = {r["series"] for r in csv.DictReader(open(sys.argv[1]))}
tolerances = {r["solver.tolerance"] for r in csv.DictReader(open(sys.argv[2])) if r["solver.type"] != "cholesky"}
assert series == tolerances and len(series) == 2, (series, tolerances)
PYEOF
# Without --hue, one series per run, named by what varies between runs, never by the hash.
"${P[@]}" "$S/sweep/iterations.csv" --x iteration --y residual --logy -o "$S/runs.png" --data "$S/runs.csv" > /dev/null ||
  fail "runs labelled by parameters"
$PY - "$S/runs.csv" <<'PYEOF'
import csv, sys
series = {r["series"] for r in csv.DictReader(open(sys.argv[1]))}
assert all("solver.tolerance=" in s and "solver.type=" in s for s in series), series
PYEOF
# A hue value holding several runs draws one line per run (told apart by style, with a warning
# naming the value), never one line through all of them; --estimator median draws one line per
# hue value and says what it drew. Counted on the figure itself (matplotlib's Line2D objects).
$PY - "$S/sweep" "$S/lines.png" <<'PYEOF' || fail "one line per run"
import contextlib, csv, importlib.util, io, sys
import matplotlib.pyplot as plt
spec = importlib.util.spec_from_file_location("plot", "scripts/plot.py")
plot = importlib.util.module_from_spec(spec)
spec.loader.exec_module(plot)
table, runs = sys.argv[1] + "/iterations.csv", list(csv.DictReader(open(sys.argv[1] + "/runs.csv")))
def positive(v):
    try:
        return float(v) > 0
    except ValueError:
        return False
drawn_runs = {r["run_id"] for r in csv.DictReader(open(table)) if positive(r["residual"])}
types = {r["solver.type"] for r in runs if r["run_id"] in drawn_runs}
assert len(drawn_runs) > len(types), "the sweep must put several runs under one solver.type"
def lines_of(*extra):
    plt.close("all")
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        plot.main([table, "--x", "iteration", "--y", "residual", "--hue", "solver.type", "--logy", "-o", sys.argv[2], *extra])
    return [l for l in plt.gcf().axes[0].get_lines() if len(l.get_xdata())], err.getvalue()
lines, said = lines_of()
assert len(lines) == len(drawn_runs), f"{len(lines)} lines for {len(drawn_runs)} runs"
assert "solver.type=conjugate_gradient holds 2 runs: drawn as 2 lines" in said, said
lines, said = lines_of("--estimator", "median")
assert len(lines) == len(types), f"{len(lines)} median lines for {len(types)} solver types"
assert "each line is the median over the runs of one solver.type value" in said, said
PYEOF
expect_error 1 "needs a numeric x and --kind line" -- "${P[@]}" "$S/sweep/runs.csv" --x solver.type --y solve_s \
  --estimator median -o "$S/none.png"
expect_error 1 "nothing to plot: every one of $rows points was left out ($rows y empty or not a number)" -- \
  "${P[@]}" "$S/sweep/runs.csv" --x solver.type --y message -o "$S/none.png"
expect_error 1 "no row has solver.type=lu" -- "${P[@]}" "$S/sweep/runs.csv" --x n_dofs --y solve_s \
  --filter solver.type=lu -o "$S/none.png"
expect_error 1 "no column 'nope'" -- "${P[@]}" "$S/sweep/runs.csv" --x nope --y solve_s -o "$S/none.png"
expect_error 1 "the output folder .*/nowhere does not exist" -- "${P[@]}" "$S/sweep/runs.csv" --x n_dofs --y solve_s \
  -o "$S/nowhere/x.png"
[ ! -e "$S/none.png" ] || fail "a refused plot wrote a file"
echo "plot: ok"
