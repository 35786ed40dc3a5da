# A saved hierarchy (.vtm from `fairshape remesh`, or a run's _levels.vtm) is a run's input:
# the remesh is paid once, its details kept; keys that contradict it, and a .vtm that is not a
# fairshape hierarchy, are refused at validation.
source "$(dirname "$0")/lib.sh"
S="$SCRATCH"
C=configs/smoke/cow_nose_pull.yaml
EDIT=(--set input.representation=catmull-clark --set 'energy=[{type: detail_preserving}]')
"$FS" remesh data/cow.off --scheme catmull-clark --base-faces 200 --levels 2 "$S/cow.vtm" > /dev/null 2>&1 || fail "remesh"
"$FS" run $C --set input.mesh="$S/cow.vtm" "${EDIT[@]}" --set input.remesh_base_faces=0 --out "$S/a" 2>/dev/null ||
  fail "a run on a saved hierarchy"
# The same edit on the remesh made inside the run: the same problem, the same answer.
"$FS" run $C --set input.mesh=data/cow.off "${EDIT[@]}" --set input.levels=2 --set input.remesh_base_faces=200 \
  --out "$S/b" 2>/dev/null || fail "a run that remeshes"
$PY - "$S/a/runs.csv" "$S/b/runs.csv" <<'PYEOF'
import csv, sys
a, b = (list(csv.DictReader(open(f)))[0] for f in sys.argv[1:])
for k in ("n_dofs", "n_fine", "n_constrained"):
    assert a[k] == b[k], (k, a[k], b[k])
for k in ("energy", "detail_change"):
    x, y = float(a[k]), float(b[k])
    assert abs(x - y) <= 1e-8 * max(1.0, abs(y)), (k, x, y)
assert float(a["detail_change"]) > 0, "the saved hierarchy's details were lost"
PYEOF
# The run's own _levels.vtm is a saved hierarchy too: it round-trips.
id=$(sed -n 2p "$S/a/runs.csv" | cut -d, -f1)
"$FS" run $C --set input.mesh="$S/a/vtk/${id}_levels.vtm" "${EDIT[@]}" --out "$S/c" 2>/dev/null || fail "a run's own hierarchy as input"
expect_error 2 "input.levels: '3', but .* is a saved hierarchy with '2'" -- \
  "$FS" run $C --set input.mesh="$S/cow.vtm" "${EDIT[@]}" --set input.levels=3 --dry-run
expect_error 2 "input.crease_method: 'chaikin', but .* is a saved hierarchy with 'uniform'" -- \
  "$FS" run $C --set input.mesh="$S/cow.vtm" "${EDIT[@]}" --set input.crease_method=chaikin --dry-run
expect_error 2 "input.representation: 'loop', but" -- \
  "$FS" run $C --set input.mesh="$S/cow.vtm" --set input.representation=loop --dry-run
expect_error 2 "remeshed already" -- \
  "$FS" run $C --set input.mesh="$S/cow.vtm" "${EDIT[@]}" --set input.remesh_base_faces=100 --dry-run
"$FS" subdivide --scheme catmull-clark --levels 1 data/cow.off "$S/plain.vtm" > /dev/null 2>&1 || fail "subdivide"
expect_error 2 "not a fairshape hierarchy (no plain.json" -- \
  "$FS" run $C --set input.mesh="$S/plain.vtm" "${EDIT[@]}" --dry-run
cp "$S/cow.vtm" "$S/other.vtm"; cp -r "$S/cow" "$S/other"
sed 's/"levels": 2/"levels": 3/' "$S/cow.json" > "$S/other.json"
expect_error 2 "holds 3 levels (0..2), but its sidecar declares 4 (0..3)" -- \
  "$FS" run $C --set input.mesh="$S/other.vtm" "${EDIT[@]}" --dry-run
echo "saved_hierarchy: ok"
