# Boier-Martin et al. §4.2, region of influence, through the command line: one nose handle
# propagated to the base or to the finest level and solved on its region; nothing outside a
# region moves (runs.csv and the VTP's influence_region array agree); a coarse level reaches
# more of the surface than a fine one; bad influence keys are refused before any run.
# Beyond the paper: rotation-aware details on a 41-degree normal edit.
source "$(dirname "$0")/lib.sh"
S="$SCRATCH"
C=configs/smoke/cow_nose_pull.yaml
FIX='{type: fixed, region: {axis: x, from: 0.0, to: 0.3}}'
# A move small against 2 rings of the raw cow's fine nose triangles (the 0.072 move this test
# used before folds 358 faces on a level-0 region of 2 rings: tests/cli/orientation.sh).
NOSE='type: position, nearest: [0.5, 0.0, 0.0], offset: [0.004, 0.006, 0.0]'
BASE=(--set input.representation=catmull-clark --set input.levels=2 --set 'energy=[{type: detail_preserving}]'
      --set 'problem={constraint_mode: kkt}')
edit() {  # out constraints
  "$FS" run $C --out "$S/$1" "${BASE[@]}" --set "constraints=[$FIX, $2]" 2>/dev/null || fail "$1: the run failed"
}
edit coarse "{$NOSE, influence_level: 0, influence_rings: 2}"
edit fine "{$NOSE, influence_level: 2, influence_rings: 2}"
$PY - "$S" <<'PYEOF'
import csv, sys
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.util.numpy_support import vtk_to_numpy
d = sys.argv[1]
rows = {}
for case in ("coarse", "fine"):
    r = list(csv.DictReader(open(f"{d}/{case}/runs.csv")))[0]
    assert r["termination"] == "converged", (case, r["termination"], r["message"])
    assert float(r["outside_region_move"]) == 0.0, (case, r["outside_region_move"])
    assert float(r["constraint_violation"]) < 1e-9, (case, r["constraint_violation"])
    assert float(r["moved_fraction"]) <= float(r["region_fraction"]), case
    assert "regions of influence: 1 pass" in r["message"], r["message"]
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(f"{d}/{case}/vtk/{r['run_id']}.vtp")
    reader.Update()
    pd = reader.GetOutput().GetPointData()
    region = vtk_to_numpy(pd.GetArray("influence_region"))
    moved = vtk_to_numpy(pd.GetArray("displacement_norm"))
    assert (moved[region == 0] == 0).all(), f"{case}: a vertex outside every region moved"
    assert abs((region > 0).mean() - float(r["region_fraction"])) < 1e-6, case
    rows[case] = r
assert float(rows["coarse"]["region_fraction"]) > 4 * float(rows["fine"]["region_fraction"]), rows
PYEOF

# Bad influence keys: exit 2 before any run, naming the key.
expect_error 2 "finer than level 0" -- "$FS" run $C --out "$S/bad1" "${BASE[@]}" \
  --set "constraints=[$FIX, {$NOSE, level: 0, influence_level: 2}]"
expect_error 2 "constraints\[0\].influence_level: a fixed constraint" -- "$FS" run $C --out "$S/bad2" "${BASE[@]}" \
  --set "constraints=[{type: fixed, region: {axis: x, from: 0.0, to: 0.3}, influence_level: 0}, {$NOSE}]"
expect_error 2 "problem.drag_steps: a drag cannot be combined with constraints\[1\]'s influence_level" -- \
  "$FS" run $C --out "$S/bad3" "${BASE[@]}" \
  --set 'problem={constraint_mode: paper, accuracy: interactive, coarse_level: 1, drag_steps: 2}' \
  --set "constraints=[$FIX, {$NOSE, influence_level: 0}]"
expect_error 2 "influence_rings" -- "$FS" run $C --out "$S/bad4" "${BASE[@]}" \
  --set "constraints=[$FIX, {$NOSE, influence_rings: -5}]"
# Given on a coarse level: refused at the edit level, with the way out named; solved on its own level.
expect_error 2 "level 0 is coarser than the edit level 2: .*give it influence_level: k with k <= 0" -- \
  "$FS" run $C --out "$S/bad5" "${BASE[@]}" --set "constraints=[$FIX, {$NOSE, level: 0}]"
[ ! -e "$S/bad1/runs.csv" ] || fail "a refused sweep wrote runs.csv"
edit given0 "{$NOSE, level: 0, influence_level: 0}"
$PY - "$S" <<'PYEOF'
import csv, sys
r = list(csv.DictReader(open(f"{sys.argv[1]}/given0/runs.csv")))[0]
assert r["termination"] == "converged" and float(r["constraint_violation"]) < 1e-9, r
assert float(r["outside_region_move"]) == 0.0, r
PYEOF

# Under §5's ladder: the bounded level-0 region solved directly, the whole-level handle on the
# interactive / improved ladder from level 1; nothing outside the regions moves, every
# constraint is met, and the error against the converged ladder is reported.
TOP='type: position, nearest: [-0.05, 0.21, 0.0], offset: [0.0, 0.04, 0.0]'
for a in interactive improved; do
  "$FS" run $C --out "$S/ladder_$a" "${BASE[@]}" \
    --set "problem={constraint_mode: paper, accuracy: $a, coarse_level: 1}" \
    --set "constraints=[$FIX, {$NOSE, influence_level: 0}, {$TOP}]" 2>/dev/null || fail "ladder_$a: the run failed"
done
$PY - "$S" <<'PYEOF'
import csv, sys
for a in ("interactive", "improved"):
    r = list(csv.DictReader(open(f"{sys.argv[1]}/ladder_{a}/runs.csv")))[0]
    assert r["termination"] in ("converged", "schedule_completed"), (a, r["termination"], r["message"])
    assert "level 0: " in r["message"] and "direct" in r["message"], r["message"]
    assert f"{a} ladder from level 1" in r["message"], r["message"]
    assert float(r["outside_region_move"]) == 0.0, r
    assert float(r["constraint_violation"]) < 1e-8, r
    assert 0 < float(r["error_vs_reference"]) < 0.5, (a, r["error_vs_reference"])
PYEOF

# Rotation-aware details: the nose's normal turned 41 degrees from its rest normal (remeshed cow,
# details; a target 115 degrees from it is met by its reverse and ends folded). Whether
# the rounds settle depends on the model (papers/boier-martin/README.md); what is tested is
# that a run says which: converged only with its last change within the tolerance, and a run
# given too few rounds ends max_iterations with the change in its message.
TURN='{type: fixed, nearest: [0.5, 0.0, 0.0]}, {type: normal, nearest: [0.5, 0.0, 0.0], normal: [0.9, -0.43, 0.0]}'
for n in 0 2 40; do
  "$FS" run $C --out "$S/turn$n" "${BASE[@]}" --set input.remesh_base_faces=200 \
    --set "problem={constraint_mode: kkt, rotation_iterations: $n}" --set "constraints=[$FIX, $TURN]" >/dev/null 2>&1 || true
done
$PY - "$S" <<'PYEOF'
import csv, re, sys
d = sys.argv[1]
linear, short, turned = (list(csv.DictReader(open(f"{d}/turn{n}/runs.csv")))[0] for n in (0, 2, 40))
assert linear["termination"] == "converged" and linear["rotation_rounds"] == "", linear
for r in (short, turned):
    change = float(re.search(r"last change ([0-9.e+-]+)", r["message"]).group(1))
    if r["termination"] == "converged":
        assert change <= 1e-4, (r["termination"], r["message"])
    else:
        assert r["termination"] == "max_iterations" and "above the tolerance" in r["message"], r
assert short["termination"] == "max_iterations", short
PYEOF
echo "region_of_influence: ok"
