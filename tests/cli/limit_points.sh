# Constraints anywhere on the surface: a curve placed as points of the finest
# level's limit surface of a remeshed cow, a handle at (face, u, v), and bad surface points
# refused at validation.
source "$(dirname "$0")/lib.sh"
C=configs/smoke/cow_nose_pull.yaml
HIER=(--set input.representation=catmull-clark --set input.remesh_base_faces=200 --set input.levels=2
      --set 'energy=[{type: detail_preserving}]' --set problem.constraint_mode=kkt)
# A curve along the back, lifted: its points on the limit surface of level 2 (the finest).
"$FS" run $C --out "$SCRATCH/curve" "${HIER[@]}" --set 'constraints=[{type: fixed, region: {axis: x, from: 0.0, to: 0.1}},
    {type: curve, placement: limit_points, max_distance: 0.05, points: [[-0.235, 0.217, 0.0], [-0.052, 0.208, 0.0], [0.15, 0.215, 0.0]],
     translation: [0.0, 0.05, 0.0]}]' 2>/dev/null || fail "a run with a limit_points curve"
$PY - "$SCRATCH/curve" <<'PYEOF'
import csv, sys
import numpy as np
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.util.numpy_support import vtk_to_numpy
d = sys.argv[1]
r = list(csv.DictReader(open(f"{d}/runs.csv")))[0]
assert r["termination"] == "converged", r
n = int(r["curve_points"])
assert n >= 10, n  # about one sample per level-2 edge along ~0.4 of the cow (3 control points)
read = lambda name: (lambda x: (x.SetFileName(f"{d}/vtk/{name}"), x.Update(), x.GetOutput())[2])(vtkXMLPolyDataReader())
result = read(f"{r['run_id']}.vtp")
marked = vtk_to_numpy(result.GetPointData().GetArray("constrained"))
assert marked.sum() > 0, "no vertex marked"
overlay = read(f"{r['run_id']}_constraints.vtp")
assert overlay.GetNumberOfLines() == 1, "the curve is not in the overlay"
line = overlay.GetCell(overlay.GetNumberOfCells() - 1)
assert line.GetNumberOfPoints() == n, (line.GetNumberOfPoints(), n)
PYEOF
# The same curve with the default placement on the finest level, snapping only vertices within
# 0.05 of their shortest edge: no chain of them lines up along it (as on a remeshed scan's finest
# level), so it is placed on the finest level's limit surface, and the run says so.
"$FS" run $C --out "$SCRATCH/default" "${HIER[@]}" --set 'constraints=[{type: fixed, region: {axis: x, from: 0.0, to: 0.1}},
    {type: curve, level: 2, snap_ratio: 0.05, max_distance: 0.05, points: [[-0.235, 0.217, 0.0], [-0.052, 0.208, 0.0], [0.15, 0.215, 0.0]],
     translation: [0.0, 0.05, 0.0]}]' 2>/dev/null || fail "a default-placement curve on the finest level"
$PY - "$SCRATCH/default" "$SCRATCH/curve" <<'PYEOF'
import csv, sys
r = list(csv.DictReader(open(f"{sys.argv[1]}/runs.csv")))[0]
asked = list(csv.DictReader(open(f"{sys.argv[2]}/runs.csv")))[0]
assert r["termination"] == "converged", r
assert "placed at points of the finest level's limit surface (placement: limit_points)" in r["message"], r["message"]
assert float(r["constraint_violation"]) < 1e-9, r
assert r["curve_points"] == asked["curve_points"], (r["curve_points"], asked["curve_points"])  # the same placement
PYEOF
# A handle at the limit point nearest the nose, with a normal target there, exact mode (tilted
# up, [1, 0.3, 0], 2 faces beside it fold: reported folded, tests/cli/orientation.sh).
"$FS" run $C --out "$SCRATCH/at" "${HIER[@]}" --set 'constraints=[{type: fixed, region: {axis: x, from: 0.0, to: 0.3}},
    {type: position, nearest_on_limit: [0.5, 0.0, 0.0], offset: [0.0, 0.05, 0.0]},
    {type: normal, nearest_on_limit: [0.5, 0.0, 0.0], normal: [1, -0.3, 0]}]' 2>/dev/null \
  || fail "a run with a handle and a normal at a limit point"
grep -q ",converged," "$SCRATCH/at/runs.csv" || fail "the limit-point handle run did not converge"
# Bad surface points: exit 2 at validation, naming the key and the valid range.
expect_error 2 "constraints\[1\].at: on level 2: u = 1.5 is outside the quad's range \[0, 1\]" -- "$FS" run $C "${HIER[@]}" \
  --set 'constraints=[{type: fixed, region: {axis: x, from: 0.0, to: 0.3}}, {type: position, at: {face: 5, uv: [1.5, 0.5]}, offset: [0, 0.1, 0]}]' \
  --out "$SCRATCH/bad"
[ ! -e "$SCRATCH/bad/runs.csv" ] || fail "a run with a bad surface point was started"
expect_error 2 "constraints\[1\].at: on level 2: face 999999 does not exist" -- "$FS" run $C "${HIER[@]}" \
  --set 'constraints=[{type: fixed, region: {axis: x, from: 0.0, to: 0.3}}, {type: fixed, at: {face: 999999, uv: [0.5, 0.5]}}]' \
  --out "$SCRATCH/bad2"
expect_error 2 "constraints\[1\].at.uv: expected 2 parameters" -- "$FS" run $C "${HIER[@]}" \
  --set 'constraints=[{type: fixed, region: {axis: x, from: 0.0, to: 0.3}}, {type: fixed, at: {face: 1, uv: [0.5]}}]' \
  --out "$SCRATCH/bad3"
echo "limit_points: ok"
