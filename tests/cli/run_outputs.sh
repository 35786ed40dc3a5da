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
# The options the run used, defaults included: keys the config leaves out are there with their
# defaults, keys it sets with its values.
used = meta["sessions"][0]["effective_options"]
common = used["common"]
assert used["by_run"] == {}, used["by_run"]  # one run: everything is common
assert common["solver.type"] == "cholesky", common.get("solver.type")
assert common["energy[0].type"] == "umbrella_thin_plate" and common["energy[1].weight"] == 0.01, common
assert "solver.tolerance" not in meta["config"].get("solver", {}) and "solver.tolerance" in common, common
assert "output.vtk" in common and "problem.formulation" in common, sorted(common)
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

# --in-process: the same rows as a worker's run (nothing but the process differs), and
# by_run lists the swept key per run while common holds the rest.
"$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/inproc" --in-process \
  --set 'sweep.solver.type=[cholesky, conjugate_gradient]' --set solver.tolerance=1e-10 2>/dev/null || fail "--in-process run"
"$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/worker" \
  --set 'sweep.solver.type=[cholesky, conjugate_gradient]' --set solver.tolerance=1e-10 2>/dev/null || fail "worker run"
rows_equal "$SCRATCH/inproc/runs.csv" "$SCRATCH/worker/runs.csv" || fail "--in-process rows differ from the worker's"
$PY - "$SCRATCH/inproc/run.json" <<'PYEOF'
import json, sys
used = json.load(open(sys.argv[1]))["sessions"][0]["effective_options"]
assert sorted(r["solver.type"] for r in used["by_run"].values()) == ["cholesky", "conjugate_gradient"], used["by_run"]
assert "solver.type" not in used["common"] and used["common"]["solver.tolerance"] == 1e-10, used["common"]
PYEOF
expect_error 2 "needs --jobs 1" -- "$FS" run configs/smoke/cow_nose_pull.yaml --in-process --jobs 2 --out "$SCRATCH/bad2"

# Subdivision representations: the problem lives on the finest level of the ladder.
"$FS" run configs/examples/subdivision_ladder.yaml --out "$SCRATCH/ladder" --set 'sweep.input.levels=[1, 2]' 2>/dev/null
$PY - "$SCRATCH/ladder/runs.csv" <<'PYEOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert len(rows) == 4, rows
for r in rows:
    assert r["n_fine"] == {"1": "17414", "2": "69650"}[r["input.levels"]], r
# Each level's hierarchy, per back end, is shared work built once: setup.csv has its row.
setup = list(csv.DictReader(open(sys.argv[1].replace("runs.csv", "setup.csv"))))
assert len(setup) == 4 and all(float(s["setup_s"]) > 0 for s in setup), setup
assert {r["setup_ids"] for r in rows} == {s["setup_id"] for s in setup}
PYEOF
expect_error 2 "input.levels: 2 subdivision levels need representation" -- \
  "$FS" run configs/smoke/cow_nose_pull.yaml --set input.levels=2 --out "$SCRATCH/bad"
# A curve constraint snapped on a level coarser than the finest: runs.csv counts its points and
# the result's `constrained` array marks them (a vertex keeps its id on finer levels).
"$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/curve" --set input.representation=catmull-clark \
  --set input.levels=2 --set input.edit_level=1 --set 'energy=[{type: detail_preserving}]' --set 'constraints=[{type: fixed, region: {axis: x, from: 0.0, to: 0.1}},
    {type: curve, level: 1, max_distance: 0.05, snap_ratio: 0.5, points: [[-0.235, 0.217, 0.0], [-0.052, 0.208, 0.0], [0.15, 0.215, 0.0]],
     translation: [0.0, 0.05, 0.0]}]' 2>/dev/null || fail "a run with a coarse-level curve constraint"
/usr/bin/python3 - "$SCRATCH/curve" <<'PYEOF'
import csv, sys
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.util.numpy_support import vtk_to_numpy
d = sys.argv[1]
r = list(csv.DictReader(open(f"{d}/runs.csv")))[0]
assert int(r["curve_points"]) >= 3, r["curve_points"]
read = lambda name: (lambda x: (x.SetFileName(f"{d}/vtk/{name}"), x.Update(), x.GetOutput())[2])(vtkXMLPolyDataReader())
marked = vtk_to_numpy(read(f"{r['run_id']}.vtp").GetPointData().GetArray("constrained"))
overlay = read(f"{r['run_id']}_constraints.vtp")
import numpy as np
distinct = len(np.unique(np.round(vtk_to_numpy(overlay.GetPoints().GetData()), 12), axis=0))
assert int(marked.sum()) == distinct, (marked.sum(), distinct)  # every constrained vertex, the curve's included
assert overlay.GetNumberOfLines() == 1, "the curve's chain is not in the overlay"
# ParaView draws cells, not bare points: each constraint point (kind >= 0) is a vertex cell.
kind = vtk_to_numpy(overlay.GetPointData().GetArray("kind"))
assert overlay.GetNumberOfVerts() == int((kind >= 0).sum()) > 0, (overlay.GetNumberOfVerts(), int((kind >= 0).sum()))
PYEOF
echo "run_outputs (subdivision): ok"
