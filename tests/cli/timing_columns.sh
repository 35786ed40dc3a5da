# Timing columns a benchmark can trust (configs/README.md, "Timing columns"): shared work is
# counted once and charged to no run, whatever the order or the number of workers; every run's
# time_s holds its parts; iterations.csv's seconds never decrease; energy is the result's.
source "$(dirname "$0")/lib.sh"
SMOKE=configs/smoke/cow_nose_pull.yaml
# Three solvers and two seeds on one Catmull-Clark hierarchy of the cow: one build, one
# yardstick, six runs.
SHARED=(--set input.representation=catmull-clark --set input.levels=1 --set output.iterations=true
        --set output.vtk=none --set 'sweep.solver.type=[cholesky, multigrid_cg, multigrid]' --set 'sweep.seed=[1, 2]')
for jobs in 1 2; do
  "$FS" run "$SMOKE" --out "$SCRATCH/jobs$jobs" --jobs $jobs "${SHARED[@]}" 2>"$SCRATCH/log$jobs.txt" \
    || { cat "$SCRATCH/log$jobs.txt" >&2; fail "the shared-hierarchy sweep under --jobs $jobs"; }
done
$PY - "$SCRATCH" <<'PYEOF'
import csv, sys
d = sys.argv[1]
rows = {j: list(csv.DictReader(open(f"{d}/jobs{j}/runs.csv"))) for j in (1, 2)}
setup = {j: list(csv.DictReader(open(f"{d}/jobs{j}/setup.csv"))) for j in (1, 2)}
for j in (1, 2):
    assert len(rows[j]) == 6, rows[j]
    for r in rows[j]:
        parts = sum(float(r[c]) for c in ("assemble_s", "analyze_s", "solve_s"))
        assert float(r["time_s"]) >= parts, (j, r["solver.type"], r["time_s"], parts)
        assert "subdivide_s" not in r, "the build is not a run's column"
    ids = {r["setup_ids"] for r in rows[j]}
    # every run used the one hierarchy and the one reference solution, whoever built them
    assert len(ids) == 1 and len(next(iter(ids)).split()) == 2, ids
    used = set(next(iter(ids)).split())
    built = [s["setup_id"] for s in setup[j]]
    assert set(built) == used, (built, used)
    # each piece of shared work is done once per worker process, never once per run
    for i in used:
        assert 1 <= built.count(i) <= j, (j, i, built)
    assert all(float(s["setup_s"]) > 0 for s in setup[j])
# The attribution does not depend on the scheduling: the same ids on the same runs.
by_run = lambda j: {r["run_id"]: r["setup_ids"] for r in rows[j]}
assert by_run(1) == by_run(2), (by_run(1), by_run(2))
# iterations.csv: seconds never decrease within a run; energy is the iterate's (never negative)
its = list(csv.DictReader(open(f"{d}/jobs1/iterations.csv")))
assert its, "no iterations"
last = {}
for r in its:
    s = float(r["seconds"])
    assert s >= last.get(r["run_id"], 0.0), r
    last[r["run_id"]] = s
    assert float(r["energy"]) >= 0, r
PYEOF
rows_equal "$SCRATCH/jobs1/runs.csv" "$SCRATCH/jobs2/runs.csv" || fail "--jobs 2 rows differ from --jobs 1"

# The energy of a thin plate of the surface's positions is the result's, a sum of squares (the
# free front of the cow collapses under it, folding: Figure 2's failure, expected here).
"$FS" run "$SMOKE" --out "$SCRATCH/plate" --set 'energy=[{type: surface_thin_plate}]' --set expect=folded 2>/dev/null \
  || fail "a thin-plate run"
$PY - "$SCRATCH/plate/runs.csv" <<'PYEOF'
import csv, sys
r = list(csv.DictReader(open(sys.argv[1])))[0]
assert r["termination"] == "folded", r
assert float(r["energy"]) > 0, r["energy"]
PYEOF

# repeat: 3 — every timing of the row from one execution, so the parts still add up.
"$FS" run "$SMOKE" --out "$SCRATCH/repeat" --set repeat=3 2>/dev/null || fail "repeat: 3"
$PY - "$SCRATCH/repeat/runs.csv" <<'PYEOF'
import csv, sys
r = list(csv.DictReader(open(sys.argv[1])))[0]
assert r["repeat"] == "3", r
assert float(r["time_s"]) >= float(r["assemble_s"]) + float(r["analyze_s"]) + float(r["solve_s"]), r
assert float(r["solve_min_s"]) <= float(r["solve_s"]), r
PYEOF

# The other kinds: time_s holds its parts.
check_parts() {  # runs.csv, then the part columns
  $PY - "$@" <<'PYEOF'
import csv, sys
path, parts = sys.argv[1], sys.argv[2:]
for r in csv.DictReader(open(path)):
    total = sum(float(r[c]) for c in parts if r[c])
    assert float(r["time_s"]) >= total, (path, {c: r[c] for c in parts}, r["time_s"])
PYEOF
}
"$FS" run configs/welch-witkin/fig3.yaml --smoke --out "$SCRATCH/sheet" 2>/dev/null || fail "a sheet run"
check_parts "$SCRATCH/sheet/runs.csv" analyze_s solve_s
"$FS" run configs/sauvage/fig3.yaml --smoke --out "$SCRATCH/curve" 2>/dev/null || fail "a curve run"
check_parts "$SCRATCH/curve/runs.csv" explicit_s solve_s
"$FS" run configs/khodakovsky-schroder/fig11.yaml --smoke --out "$SCRATCH/feature" 2>/dev/null || fail "a feature run"
check_parts "$SCRATCH/feature/runs.csv" edit_s apply_s
echo "timing_columns: ok"
