# Curve experiments (configs/sauvage): outputs on any curve, and bad input reported clearly.
source "$(dirname "$0")/lib.sh"
C=configs/sauvage/fig3.yaml
# Any curve through --set input.curve: a closed space curve, edited at level 1, wrinkles at 3
# (a move the lengths allow: [-0.2, 0.1, 0.3] puts the handle 14 % farther from its neighbour
# than the curve between them is long, which ends edit_undone, tested below).
"$FS" run $C --out "$SCRATCH/ring" --set input.curve=data/curves/ring128.obj --set 'sweep={}' \
  --set edits.0.level=1 --set edits.0.wrinkle_level=3 --set 'edits.0.moves=[{index: 2, by: [-0.05, 0.03, 0.1]}]' 2>/dev/null \
  || fail "ring128 run failed"
for f in runs.csv steps.csv final.obj run.json; do [ -s "$SCRATCH/ring/$f" ] || fail "missing $f"; done
head -1 "$SCRATCH/ring/runs.csv" | grep -q "length_error_max,length_error_rms,total_length_change,bending_energy,distance_to_attractor,wrinkles" \
  || fail "runs.csv lacks the issue's columns"
grep -q ",solves," <(head -1 "$SCRATCH/ring/runs.csv") || fail "no solves column"
grep -q ",converged," "$SCRATCH/ring/runs.csv" || fail "ring128 did not converge"
[ "$(grep -c '^v ' "$SCRATCH/ring/final.obj")" -eq 128 ] || fail "final.obj does not have 128 points"
[ "$(ls "$SCRATCH/ring/vtk/"*.vtp | grep -vc _constraints)" -eq 4 ] || fail "expected one VTK polyline per stage"
[ "$(ls "$SCRATCH/ring/vtk/"*_constraints.vtp | wc -l)" -eq 4 ] || fail "expected a handles overlay per stage"
# Each handle is a vertex cell: ParaView's default representation draws cells, not bare points.
$PY - "$SCRATCH/ring/vtk" <<'PYEOF'
import glob, sys
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
for f in glob.glob(f"{sys.argv[1]}/*_constraints.vtp"):
    r = vtkXMLPolyDataReader()
    r.SetFileName(f)
    r.Update()
    o = r.GetOutput()
    assert o.GetNumberOfPoints() > 0 and o.GetNumberOfVerts() == o.GetNumberOfPoints(), (f, o.GetNumberOfPoints(), o.GetNumberOfVerts())
PYEOF
[ "$(wc -l < "$SCRATCH/ring/steps.csv")" -eq 5 ] || fail "expected a header and 4 stage rows in steps.csv"
# The linearized loop and Ceres in one sweep: both converge to the same lengths.
"$FS" run $C --out "$SCRATCH/solvers" --set 'sweep={optimization.solver.type: [linearized, ceres]}' 2>/dev/null \
  || fail "solver sweep failed"
[ "$(grep -c ',converged,' "$SCRATCH/solvers/runs.csv")" -eq 2 ] || fail "a solver did not converge"

W=data/curves/wave129.obj
expect_error 2 "optimization.beta: 1.5 is out of range \[0, 1\]" -- "$FS" run $C --set optimization.beta=1.5 --out "$SCRATCH/x"
expect_error 2 "edits\[0\].level: 9 is outside the hierarchy" -- "$FS" run $C --set edits.0.level=9 --out "$SCRATCH/x"
expect_error 2 "edits\[0\].wrinkle_level: 7 must lie in \[e, levels-1\]" -- "$FS" run $C --set 'sweep={}' --set edits.0.wrinkle_level=7 --out "$SCRATCH/x"
expect_error 2 "edits\[0\].moves\[0\].index: 9 is not on the level-2 polygon of 5 points" -- "$FS" run $C --set edits.0.moves.0.index=9 --out "$SCRATCH/x"
expect_error 2 "unknown value 'newtn'" -- "$FS" run $C --set optimization.solver.linearized.linearization=newtn --out "$SCRATCH/x"
expect_error 2 "include {type: segment_lengths} (every segment's length) or {type: total_length}" -- "$FS" run $C --set 'optimization.constraints=[{type: pin}]' --out "$SCRATCH/x"
# A point count that is not 2^n·k + 1: 128 open points allow no level above 0.
head -129 $W | grep -v '^l' > "$SCRATCH/open128.obj"
echo "l $(seq -s ' ' 1 128)" >> "$SCRATCH/open128.obj"
expect_error 2 "2\^L·k + 1 points" -- "$FS" run $C --set input.curve="$SCRATCH/open128.obj" --out "$SCRATCH/x"
# A repeated point: zero-length segment, refused with its index before anything runs.
awk 'NR==6{print; print; next} NR<=129{print}' $W | grep '^v' | head -129 > "$SCRATCH/repeat.obj"
echo "l $(seq -s ' ' 1 129)" >> "$SCRATCH/repeat.obj"
expect_error 2 "edits.0 on .*zero length" -- "$FS" run $C --set input.curve="$SCRATCH/repeat.obj" --set 'sweep={}' \
  --out "$SCRATCH/repeat"
[ ! -e "$SCRATCH/repeat/runs.csv" ] || fail "a run on a curve with a zero-length segment was started"
# Endpoints pinned and pulled apart beyond the curve's length: infeasible, no NaN, no loop.
# As the first edit, validation refuses it; as a later one (it starts from the curve the
# earlier edits make), the run does.
PINS='optimization.constraints=[{type: segment_lengths}, {type: pin, points: endpoints}]'
expect_error 2 "infeasible edit: points 0 and 128" -- "$FS" run configs/sauvage/fig1.yaml --set 'sweep={}' \
  --set 'edits.0.moves=[{index: -1, chord_scale: 1.5}]' --set "$PINS" --out "$SCRATCH/far"
rc=0; "$FS" run configs/sauvage/fig1.yaml --set 'sweep={}' --set "$PINS" --out "$SCRATCH/far_later" \
  --set 'edits=[{level: 0, moves: [{index: -1, chord_scale: 1.0}]}, {level: 0, moves: [{index: -1, chord_scale: 1.5}]}]' \
  2>/dev/null || rc=$?
[ "$rc" -eq 3 ] || fail "infeasible second edit: exit $rc, expected 3"
grep -q "edit 1: infeasible edit: points 0 and 128" "$SCRATCH/far_later/runs.csv" || fail "infeasible edit not reported"
! grep -qi "nan" "$SCRATCH/far_later/runs.csv" || fail "NaN written"
# A point count with no coarser level (300 points: 299 segments) is refused, naming counts that
# have levels; input.resample gives it them (it silently got 0 levels).
$PY - "$SCRATCH/c300.obj" <<'PYEOF'
import math, sys
with open(sys.argv[1], "w") as f:
    for i in range(300):
        f.write(f"v {2 * i / 299} {0.1 * math.sin(20 * i / 299)} 0\n")
    f.write("l " + " ".join(str(i + 1) for i in range(300)) + "\n")
PYEOF
C300="$SCRATCH/c300.yaml"
printf 'name: c300\ninput: {curve: %s}\nedits: [{level: 0, wrinkle_level: -1, moves: [{index: -1, chord_scale: 0.8}]}]\noptimization: {beta: 0.01, smoothness: bending, solver: {type: trust_region, max_solves: 2000}}\noutput: {vtk: none}\n' "$SCRATCH/c300.obj" > "$C300"
expect_error 2 "input.curve: .*has 300 points, which allow no coarser level .*input.resample: 289 or 305 for 4 levels" -- "$FS" run "$C300" --out "$SCRATCH/x"
"$FS" run "$C300" --set input.resample=289 --out "$SCRATCH/c300" 2>/dev/null || fail "the resampled 300-point curve failed"
$PY - "$SCRATCH/c300/runs.csv" <<'PYEOF' || fail "the resampled curve should have 289 points and converge"
import csv, sys
r = next(csv.DictReader(open(sys.argv[1])))
sys.exit(0 if r["n_points"] == "289" and r["termination"] == "converged" else 1)
PYEOF
# The trust region's large-curve keys are checked (block step, progress window).
expect_error 2 "optimization.solver.trust_region.block_size: 0 is out of range \[1, 64\]" -- "$FS" run "$C300" --set input.resample=289 \
  --set optimization.solver.trust_region.block_size=0 --out "$SCRATCH/x"
expect_error 2 "optimization.solver.trust_region.progress_decrease: 2 is out of range \[0, 1\]" -- "$FS" run "$C300" --set input.resample=289 \
  --set optimization.solver.trust_region.progress_decrease=2 --out "$SCRATCH/x"
# Issue 25 parts 3-4: the editing options are checked, and locality is reported.
expect_error 2 "editing.explicit_step: unknown value 'rope' (valid: local, sweep)" -- "$FS" run $C --set editing.explicit_step=rope --out "$SCRATCH/x"
expect_error 2 "editing.details: unknown value 'local' (valid: global, local_frames)" -- "$FS" run $C --set editing.details=local --out "$SCRATCH/x"
expect_error 2 "tangent constraints are not solved on the edit's support yet" -- "$FS" run $C --out "$SCRATCH/x" \
  --set 'optimization.constraints=[{type: segment_lengths}, {type: tangent, points: endpoints}]'
grep -q ",moved_outside_support,attractor_moved_outside_support," <(head -1 "$SCRATCH/ring/runs.csv") || fail "no moved_outside_support columns"
# Issue 25 part 6: a fixed total length instead of every segment's: the total is met, the
# segments stretch, runs.csv says both; what it cannot combine with is refused by name.
T=configs/sauvage/total_length.yaml
"$FS" run $T --out "$SCRATCH/total" --set 'sweep={}' 2>/dev/null || fail "the total-length run failed"
$PY - "$SCRATCH/total/runs.csv" <<'PYEOF' || fail "the total-length run should keep the total and stretch segments"
import csv, sys
r = next(csv.DictReader(open(sys.argv[1])))
ok = (r["termination"] == "converged" and r["length_constraint"] == "total_length" and float(r["total_length_error"]) < 1e-12
      and float(r["segment_stretch_max"]) > 1.01 and float(r["segment_stretch_min"]) < 0.99 and float(r["min_reduced_hessian_eig"]) >= 0)
sys.exit(0 if ok else 1)
PYEOF
expect_error 2 "optimization.constraints\[0\].value: -1 is not a length" -- "$FS" run $T --out "$SCRATCH/x" \
  --set 'optimization.constraints=[{type: total_length, value: -1}]'
expect_error 2 "optimization.solver.type: ceres does not take the total_length constraint .*the solvers that do: linearized, trust_region" -- \
  "$FS" run $T --out "$SCRATCH/x" --set optimization.solver.type=ceres
expect_error 2 "total_length and segment_lengths together" -- "$FS" run $T --out "$SCRATCH/x" \
  --set 'optimization.constraints=[{type: segment_lengths}, {type: total_length}]'
expect_error 2 "set editing.solve_region: curve" -- "$FS" run $T --out "$SCRATCH/x" --set editing.solve_region=support
# Planar curves stay planar, judged in their plane; the key is checked.
F1=configs/sauvage/fig1.yaml
expect_error 2 "editing.plane: unknown value 'flat' (valid: keep, free)" -- "$FS" run $F1 --set editing.plane=flat --out "$SCRATCH/x"
expect_error 2 "editing.partial_edit: unknown value 'yes' (valid: fail, accept)" -- "$FS" run $F1 --set editing.partial_edit=yes --out "$SCRATCH/x"
"$FS" run $F1 --set 'sweep={}' --set optimization.beta=0.5 --set optimization.solver.type=linearized --out "$SCRATCH/planar" 2>/dev/null \
  || fail "the paper's loop on Figure 1 at beta 0.5 should end at an in-plane minimum"
"$FS" run $F1 --set 'sweep={}' --set optimization.beta=0.5 --set editing.plane=free --out "$SCRATCH/free3d" 2>/dev/null || true
$PY - "$SCRATCH/planar/runs.csv" "$SCRATCH/free3d/runs.csv" <<'PYEOF' || fail "planar run: expected plane kept, out_of_plane <= 1e-12, an in-plane verdict; plane: free judged in 3-D"
import csv, sys
r = next(csv.DictReader(open(sys.argv[1])))
f = next(csv.DictReader(open(sys.argv[2])))
ok = (r["termination"] == "converged" and r["plane"] == "kept" and float(r["out_of_plane"]) <= 1e-12
      and r["second_order_space"] == "in_plane" and float(r["min_reduced_hessian_eig"]) >= 0
      and f["plane"] == "free" and f["second_order_space"] == "3d")
sys.exit(0 if ok else 1)
PYEOF
# A drag the lengths cannot honour (the end to 1.2 times the chord: the wave is only 1.06 times
# as long) is not a success unless allowed.
OVER=(--set 'sweep={}' --set 'edits.0.moves=[{index: -1, chord_scale: 1.2}]' --set edits.0.drag_steps=5)
rc=0; "$FS" run $F1 "${OVER[@]}" --out "$SCRATCH/over" 2>/dev/null || rc=$?
[ "$rc" -eq 3 ] || fail "over-stretched drag: exit $rc, expected 3"
grep -q ",edit_undone,.*over-stretched" "$SCRATCH/over/runs.csv" || fail "over-stretched drag not reported as edit_undone"
"$FS" run $F1 "${OVER[@]}" --set editing.partial_edit=accept --out "$SCRATCH/over_ok" 2>/dev/null \
  || fail "editing.partial_edit: accept should let the over-stretched drag end converged"
grep -q ",converged,.*not honoured" "$SCRATCH/over_ok/runs.csv" || fail "an accepted partial edit should still say so"
# A folded spike (point 65 thrown beyond 66 along the level-6 chord 64-66): a 5 % compression
# with wrinkles at w = 6 leaves one midpoint the explicit step cannot place; not in silence.
$PY - "$SCRATCH/spiky.obj" <<'PYEOF'
import sys
P = [[float(x) for x in l.split()[1:4]] for l in open("data/curves/wave129.obj") if l.startswith("v ")]
p, q = P[64], P[66]
P[65] = [q[i] + 3 * (q[i] - p[i]) + (1e-3 if i == 1 else 0) for i in range(3)]
with open(sys.argv[1], "w") as f:
    for v in P:
        f.write("v %.17g %.17g %.17g\n" % tuple(v))
    f.write("l " + " ".join(str(i + 1) for i in range(len(P))) + "\n")
PYEOF
SPIKE=(--set 'sweep={}' --set input.curve="$SCRATCH/spiky.obj" --set edits.0.wrinkle_level=6 --set 'edits.0.moves=[{index: -1, chord_scale: 0.95}]')
rc=0; "$FS" run $F1 "${SPIKE[@]}" --out "$SCRATCH/spike" 2>/dev/null || rc=$?
[ "$rc" -eq 3 ] || fail "spiky explicit step: exit $rc, expected 3"
$PY - "$SCRATCH/spike/runs.csv" <<'PYEOF' || fail "the spike's unplaced midpoint should end constraints_unmet with the error it left"
import csv, sys
r = next(csv.DictReader(open(sys.argv[1])))
sys.exit(0 if r["termination"] == "constraints_unmet" and int(r["unplaceable_midpoints"]) >= 1
         and float(r["explicit_length_error"]) > 1e-3 and "explicit step left" in r["message"] else 1)
PYEOF
echo "curve_run: ok"
