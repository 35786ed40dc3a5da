# Boier-Martin et al. §4.2 edits measured for folds on their result (design/orientation_check.h):
# a point + normal handle at a fingertip of the hand, a thin part. A region of 2 rings on the
# finest level bends over between the handle and its fixed border: reported `folded` (exit 3)
# with where, and the VTP marks the vertices; influence_rings auto grows the region until the
# result does not fold. Paper mode with the same normal constraint is measured against the
# optimum of the same problem; the KKT answer is that optimum, and no mode's energy is below it.
source "$(dirname "$0")/lib.sh"
S="$SCRATCH"
cat > "$S/tip.yaml" <<YAML
defaults: [$PWD/configs/base/output.yaml]
name: fingertip
seed: 1
input: { mesh: $PWD/data/hand.off, representation: catmull-clark, levels: 2 }
energy: [ { type: detail_preserving, alpha: 0.1, beta: 1.0 } ]
constraints:
  - { type: fixed, region: { axis: z, from: 0.0, to: 0.2 } }
  - { type: position, nearest: [0.132, -0.038, 0.5], offset: [0.087, 0.0, 0.0] }
  - { type: normal, nearest: [0.132, -0.038, 0.5], normal: [0.5, 0.0, 1.0] }
problem: { constraint_mode: kkt }
solver: { type: cholesky }
YAML
REGION=(--set constraints.1.influence_level=2 --set constraints.2.influence_level=2)
rc=0
"$FS" run "$S/tip.yaml" --out "$S/two" "${REGION[@]}" --set constraints.1.influence_rings=2 \
  --set constraints.2.influence_rings=2 > /dev/null 2> "$S/two.txt" || rc=$?
[ "$rc" -eq 3 ] || { cat "$S/two.txt" >&2; fail "a folded regional edit exits $rc, not 3"; }
"$FS" run "$S/tip.yaml" --out "$S/auto" "${REGION[@]}" 2> "$S/auto.txt" > /dev/null || { cat "$S/auto.txt" >&2; fail "auto rings"; }
"$FS" run "$S/tip.yaml" --out "$S/paper" --set problem.constraint_mode=paper > /dev/null 2> "$S/paper.txt" || true
"$FS" run "$S/tip.yaml" --out "$S/kkt" 2> "$S/kkt.txt" > /dev/null || { cat "$S/kkt.txt" >&2; fail "the single-level KKT edit"; }
"$FS" run "$S/tip.yaml" --out "$S/ladder" --set 'problem={constraint_mode: paper, accuracy: converged, coarse_level: 1}' \
  --set solver.type=multigrid_cg --set solver.tolerance=1e-12 --set solver.max_iterations=300 2> "$S/ladder.txt" > /dev/null \
  || { cat "$S/ladder.txt" >&2; fail "the converged ladder with a normal constraint"; }
# A normal ~104 degrees from the fingertip's rest normal: §4.2's tangent rows are met by its
# reverse (rows: tangent keeps that answer, `folded`); rows auto (the default) solves again with
# frame rows, which meet the target itself.
TURN=(--set 'constraints.2={type: normal, nearest: [0.132, -0.038, 0.5], normal: [0, 1, 0]}')
"$FS" run "$S/tip.yaml" --out "$S/tangent" "${TURN[@]}" --set constraints.2.rows=tangent > /dev/null 2>&1 || true
"$FS" run "$S/tip.yaml" --out "$S/frame" "${TURN[@]}" > /dev/null 2>&1 || true
$PY - "$S" <<'PYEOF'
import csv, sys
row = lambda case: list(csv.DictReader(open(f"{sys.argv[1]}/{case}/runs.csv")))[0]
tangent, frame = row("tangent"), row("frame")
assert tangent["termination"] == "folded" and float(tangent["normal_error_deg"]) > 179, tangent
assert "met by the reverse of the target" in tangent["message"], tangent["message"]
assert "solved again" not in tangent["message"], tangent["message"]
assert "so solved again with frame rows" in frame["message"], frame["message"]
assert float(frame["normal_error_deg"]) < 1e-3, frame
assert float(frame["constraint_violation"]) < 1e-6, frame
# Turning the tip that far may still fold faces around it: then it says so, never `converged`.
assert (frame["termination"] == "converged") == (int(frame["flipped_faces"]) == 0), frame
print("orientation: a reversed normal re-solved with frame rows:", frame["normal_error_deg"], "degrees,",
      frame["flipped_faces"], "faces flipped")
PYEOF
# A drag (§5's ladder, 3 steps): every step before the last is checked for folds in steps.csv,
# and a step that folded is named in the run's message.
"$FS" run "$S/tip.yaml" --out "$S/drag" --set 'problem={constraint_mode: paper, accuracy: interactive, coarse_level: 1, drag_steps: 3}' \
  > /dev/null 2>&1 || true
$PY - "$S" <<'PYEOF'
import csv, sys
d = sys.argv[1]
run = list(csv.DictReader(open(f"{d}/drag/runs.csv")))[0]
steps = list(csv.DictReader(open(f"{d}/drag/steps.csv")))
assert [s["step"] for s in steps] == ["1", "2", "3"], steps
assert all(s["flipped_faces"].isdigit() for s in steps[:-1]) and steps[-1]["flipped_faces"] == "", steps
for s in steps[:-1]:
    assert (int(s["flipped_faces"]) > 0) == (f"{s['step']} (" in run["message"] and "folded on the way" in run["message"]), (s, run["message"])
print("orientation: drag steps' flipped faces", [s["flipped_faces"] for s in steps[:-1]], "last", run["flipped_faces"])
PYEOF
$PY - "$S" <<'PYEOF'
import csv, sys
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader
from vtkmodules.util.numpy_support import vtk_to_numpy
d = sys.argv[1]
row = lambda case: list(csv.DictReader(open(f"{d}/{case}/runs.csv")))[0]
two, auto, paper, kkt, ladder = (row(c) for c in ("two", "auto", "paper", "kkt", "ladder"))
# Two rings: the solver met every row, and the surface folded.
assert float(two["constraint_violation"]) < 1e-6, two
assert two["termination"] == "folded", two
assert int(two["flipped_faces"]) > 0 and "faces flipped, around (" in two["message"], two
r = vtkXMLPolyDataReader(); r.SetFileName(f"{d}/two/vtk/{two['run_id']}.vtp"); r.Update()
flipped = vtk_to_numpy(r.GetOutput().GetPointData().GetArray("flipped"))
assert flipped.sum() >= 3, flipped.sum()  # the corners of the flipped faces are marked
# Auto rings: grown until nothing folds, the normal met with its own orientation.
assert auto["termination"] == "converged", auto
assert int(auto["flipped_faces"]) == 0 and float(auto["normal_error_deg"]) < 3, auto
assert "rings (auto)" in auto["message"], auto["message"]
# Paper mode: judged against the optimum of the same problem (the KKT run's energy).
assert abs(float(kkt["energy_vs_optimum"]) - 1) < 1e-6 and float(kkt["error_vs_reference"]) < 1e-6, kkt
assert int(kkt["flipped_faces"]) == 0 and float(kkt["normal_error_deg"]) < 3, kkt
ratio = float(paper["energy_vs_optimum"])
assert abs(ratio - float(paper["energy"]) / float(kkt["energy"])) < 1e-6 * ratio, (paper, kkt)
if ratio > 1.5:
    assert "times the optimum of the same problem" in paper["message"], paper["message"]
assert paper["termination"] != "converged" or (ratio <= 1.5 and int(paper["flipped_faces"]) == 0), paper
# The ladder's converged mode with a normal constraint: measured against the same optimum, which
# no mode can beat (the paper split converges to its own answer, 0.7 % above it here:
# papers/boier-martin/README.md, "One reference per problem").
assert ladder["termination"] == "converged", ladder
for r in (paper, ladder, auto):
    assert float(r["energy_vs_optimum"] or 1) >= 1 - 1e-9, r
assert 0 < float(ladder["error_vs_reference"]) < 0.05, ladder["error_vs_reference"]
print("orientation: two rings fold", two["flipped_faces"], "faces; auto:", auto["message"].split("(")[-1].rstrip(")"),
      "; paper mode", ratio, "x the optimum; ladder error", ladder["error_vs_reference"])
PYEOF
echo "orientation: ok"
