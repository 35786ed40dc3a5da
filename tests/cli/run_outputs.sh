source "$(dirname "$0")/lib.sh"
ROOT="$PWD"
# Default output folder: results/<name>/<timestamp>_<sha>/ with a `latest` link, relative to the cwd.
(cd "$SCRATCH" && "$FS" run "$ROOT/configs/smoke/cow_nose_pull.yaml" 2>/dev/null)
OUT="$SCRATCH/results/smoke_cow_nose_pull/latest"
[ -L "$OUT" ] || fail "no latest link"
for f in runs.csv run.json config.resolved.yaml final.obj; do  # a direct solve has no iterations.csv
  [ -s "$OUT/$f" ] || fail "missing $f"
done
ls "$OUT"/vtk/*.vtp >/dev/null || fail "no vtp"
$PY - "$OUT" <<'PYEOF'
import csv, json, sys
out = sys.argv[1]
meta = json.load(open(f"{out}/run.json"))
for key in ["git_commit", "git_dirty", "compiler", "compiler_flags", "libraries", "cpu_model", "config", "seed", "sessions"]:
    assert key in meta, key
for key in ["started", "ended", "argv", "input_sha256", "exit_status"]:
    assert key in meta["sessions"][0], key
for lib in ["eigen", "tbb", "suitesparse_cholmod", "ceres", "vtk", "yaml_cpp"]:
    assert meta["libraries"][lib], lib
rows = list(csv.DictReader(open(f"{out}/runs.csv")))
assert len(rows) == 1
r = rows[0]
assert r["termination"] == "converged", r
assert float(r["constraint_violation"]) < 1e-10, r
assert float(r["error_vs_reference"]) < 1e-8, r
assert float(r["peak_rss_mb"]) > 0
assert 0 <= float(r["solve_extra_mb"]) <= float(r["peak_rss_mb"]), r
PYEOF
# final.obj is the deformed cow: same size, moved.
"$FS" info "$OUT/final.obj" | grep -q "vertices             2904" || fail "final.obj"
"$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/every" --set output.vtk=all --set output.vtk_every=5 \
  --set solver.type=conjugate_gradient --set solver.max_iterations=20 2>/dev/null || true
ls "$SCRATCH"/every/vtk/*_it5.vtp >/dev/null || fail "no iteration snapshots"
ls "$SCRATCH"/every/vtk/*.pvd >/dev/null || fail "no pvd series"

# Subdivision representations: the problem lives on the finest level of the ladder.
"$FS" run configs/examples/subdivision_ladder.yaml --out "$SCRATCH/ladder" --set 'sweep.input.levels=[1, 2]' 2>/dev/null
$PY - "$SCRATCH/ladder/runs.csv" <<'PYEOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 4, rows
for r in rows:
    assert r["n_fine"] == {"1": "17414", "2": "69650"}[r["input.levels"]], r
    assert float(r["subdivide_s"]) > 0, r
PYEOF
expect_error 2 "input.levels: 2 subdivision levels need representation" -- \
  "$FS" run configs/smoke/cow_nose_pull.yaml --set input.levels=2 --out "$SCRATCH/bad"
echo "run_outputs (subdivision): ok"
