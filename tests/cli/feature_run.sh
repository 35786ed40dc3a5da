# Khodakovsky & Schröder feature experiments (configs/khodakovsky-schroder): outputs, the
# reference back end, a coarse edit, and bad input.
source "$(dirname "$0")/lib.sh"
C=configs/khodakovsky-schroder/fig11.yaml
# Three levels (one below the drawn level 2) are too coarse for the profile within 2 %: looser here.
"$FS" run $C --out "$SCRATCH/fig11" --set input.levels=3 --set feature_defaults.profile_tolerance=0.1 2>/dev/null || fail "fig11 failed"
for f in runs.csv final.obj run.json; do [ -s "$SCRATCH/fig11/$f" ] || fail "missing $f"; done
for c in time_s vertices_moved max_displacement triangles_adaptive; do head -1 "$SCRATCH/fig11/runs.csv" | grep -q "$c" || fail "runs.csv lacks $c"; done
[ "$(ls "$SCRATCH/fig11/vtk/"*.vtp | wc -l)" -eq 2 ] || fail "expected the result's VTK and its curves overlay"
[ -s "$SCRATCH/fig11/vtk/$(sed -n 2p "$SCRATCH/fig11/runs.csv" | cut -d, -f1)_constraints.vtp" ] || fail "no curves overlay"
grep -q "displacement_norm" "$SCRATCH/fig11/vtk/"*.vtp || fail "VTK lacks the displacement array"
[ "$(ls "$SCRATCH/fig11/curves/"*.obj | wc -l)" -eq 3 ] || fail "expected one base curve per feature"
[ -s "$SCRATCH/fig11/adaptive/"*.obj ] || fail "missing the adaptive mesh"
# Exports: per-level VTPs with the feature displacements, the limit surface,
# every curve's attachment on its drawn level and each finer one.
RUN=$(sed -n 2p "$SCRATCH/fig11/runs.csv" | cut -d, -f1)
[ "$(ls "$SCRATCH/fig11/levels/${RUN}_level"*.vtp | wc -l)" -eq 4 ] || fail "expected levels/<run>_level0..3.vtp"
grep -q "feature_displacement" "$SCRATCH/fig11/levels/${RUN}_level2.vtp" || fail "level VTP lacks feature_displacement"
grep -q "limit_normal" "$SCRATCH/fig11/limit/${RUN}.vtp" || fail "limit VTP lacks limit_normal"
grep -q "limit_position" "$SCRATCH/fig11/vtk/${RUN}.vtp" || fail "the result VTP lacks limit_position"
$PY - "$SCRATCH/fig11/attachments.csv" <<'PYEOF' || fail "attachments.csv: expected every feature on levels 2 and 3 with as many points on each"
import csv, sys, collections
rows = list(csv.DictReader(open(sys.argv[1])))
count = collections.Counter((r["feature"], r["level"]) for r in rows)
ok = len({f for f, _ in count}) == 3 and all(count[(f, "2")] == count[(f, "3")] > 0 for f, _ in count)
ok = ok and all(abs(float(r["b0"]) + float(r["b1"]) + float(r["b2"]) - 1) < 1e-9 and min(float(r["b0"]), float(r["b1"]), float(r["b2"])) >= -1e-12 for r in rows)
sys.exit(0 if ok else 1)
PYEOF
# Reference and optimized write the same surface.
"$FS" run $C --out "$SCRATCH/ref" --set input.levels=3 --set feature_defaults.profile_tolerance=0.1 --set implementation=reference --set adaptive.enabled=false 2>/dev/null \
  || fail "reference run failed"
cmp -s "$SCRATCH/fig11/final.obj" "$SCRATCH/ref/final.obj" || fail "reference and optimized final.obj differ"
# The achieved profile per feature; a feature outside its tolerance is no convergence.
head -1 "$SCRATCH/fig11/features.csv" | grep -q "height_min_limit,.*profile_error_limit,within_tolerance" || fail "features.csv lacks the limit profile"
[ "$(tail -n +2 "$SCRATCH/fig11/features.csv" | wc -l)" -eq 3 ] || fail "expected one features.csv row per feature"
rc=0; "$FS" run $C --out "$SCRATCH/tight" --set input.levels=3 --set adaptive.enabled=false --set profile_on=drawn_level 2>/dev/null || rc=$?
[ "$rc" -eq 3 ] || fail "a feature outside its tolerance must not converge (exit $rc)"
grep -q "constraints_unmet,.*features miss their tolerance; first: feature 'ridge_a' (level 2), finest level: profile error" "$SCRATCH/tight/runs.csv" || fail "the miss is not named"
# Only the surface profile_on names decides: with the profile exact at the limit (the default),
# finest control points that miss by more than 2 % are reported, not a miss; with profile_on
# finest the limit is reported and the finest level decides.
# (At 3 levels, profile_on limit: the limit within 4.2 % of h, the finest control points off by up
# to 5.8 %; profile_on finest: the finest within 4.1 %, the limit's height off by 8 %.)
"$FS" run $C --out "$SCRATCH/gated" --set input.levels=3 --set adaptive.enabled=false --set feature_defaults.profile_tolerance=0.045 2>/dev/null || fail "a feature within its tolerance at the limit must converge, whatever the finest control points show"
"$FS" run $C --out "$SCRATCH/gated_fine" --set input.levels=3 --set adaptive.enabled=false --set feature_defaults.profile_tolerance=0.045 --set profile_on=finest 2>/dev/null || fail "a feature within its tolerance on the finest level must converge, whatever the limit shows"
$PY - "$SCRATCH/gated" "$SCRATCH/gated_fine" <<'PYEOF' || fail "gated runs: expected every feature within tolerance where profile_on makes it exact, the other surface's miss reported"
import csv, sys
ok = True
for d, gate, other in zip(sys.argv[1:3], ("limit", "finest"), ("fine", "limit")):
    r = list(csv.DictReader(open(d + "/runs.csv")))[0]
    f = list(csv.DictReader(open(d + "/features.csv")))
    ok = ok and r["termination"] == "converged" and r["features_within_tolerance"] == "3"
    ok = ok and all(x["within_tolerance"] == "1" and x["gated_on"] == gate for x in f)
    ok = ok and max(max(float(x["profile_error_" + other]), float(x["height_error_" + other])) for x in f) > 0.045  # reported, not gated
sys.exit(0 if ok else 1)
PYEOF
expect_error 2 "features\[0\].profile_tolerance" -- "$FS" run $C --set features.0.profile_tolerance=2 --out "$SCRATCH/x"
expect_error 2 "profile_on: unknown value 'coarse'" -- "$FS" run $C --set profile_on=coarse --out "$SCRATCH/x"
# Features in the multiresolution editor: Figure 15's detail-preserving edit
# (ends held, middle lifted 0.2 on level 0) carries the features drawn before it; one drawn after
# it sits on the edited surface; every feature keeps its profile (loosened for 3 levels).
"$FS" run configs/khodakovsky-schroder/fig15.yaml --out "$SCRATCH/fig15e" --set input.levels=3 --set feature_defaults.profile_tolerance=0.5 --set feature_defaults.width_tolerance=0.5 2>/dev/null || fail "fig15 with the editor failed"
$PY - "$SCRATCH/fig15e" <<'PYEOF' || fail "fig15: the edit did not lift the features with the surface, or a feature was lost"
import csv, sys
d = sys.argv[1]
rows = list(csv.DictReader(open(d + "/runs.csv")))
feats = list(csv.DictReader(open(d + "/features.csv")))
ok = len(rows) == 2 and all(r["termination"] == "converged" and r["features_within_tolerance"] == "4" for r in rows)
ok = ok and all(float(r["edit_s"]) > 0 for r in rows) and len(feats) == 8
# The ridge's base curve (on its level of the edited surface) rises with the lift near the middle.
def curve(run):
    return [tuple(map(float, l.split()[1:4])) for l in open(d + "/curves/" + run + "_ridge.obj") if l.startswith("v ")]
flat, lifted = (curve(r["run_id"]) for r in rows)  # the sweep's order: lift 0, then 0.2
rise = max(b[2] - a[2] for a, b in zip(flat, lifted))
ok = ok and 0.1 < rise < 0.3  # (the walk across the edited level may cross one edge more or less)
sys.exit(0 if ok else 1)
PYEOF
# A remeshed input (a Loop hierarchy with details) carries features too; a saved one likewise.
"$FS" run $C --out "$SCRATCH/remeshed" --set input.remesh_base_faces=80 --set input.levels=3 --set feature_defaults.profile_tolerance=0.5 --set feature_defaults.width_tolerance=0.5 --set adaptive.enabled=false 2>/dev/null || fail "features on a remeshed input failed"
[ "$(tail -n +2 "$SCRATCH/remeshed/features.csv" | wc -l)" -eq 3 ] || fail "remeshed input: expected three features"
"$FS" remesh data/ks_patch.off "$SCRATCH/patch.vtm" --scheme loop --base-faces 80 --levels 3 >/dev/null 2>&1 || fail "remesh failed"
"$FS" run $C --out "$SCRATCH/saved" --set input.mesh="$SCRATCH/patch.vtm" --set input.levels=3 --set feature_defaults.profile_tolerance=0.5 --set feature_defaults.width_tolerance=0.5 --set adaptive.enabled=false 2>/dev/null || fail "features on a saved hierarchy failed"
$PY - "$SCRATCH/remeshed/final.obj" "$SCRATCH/saved/final.obj" <<'PYEOF' || fail "a saved hierarchy and the same remesh in the run give different results"
import sys
a, b = ([[float(x) for x in l.split()[1:4]] for l in open(p) if l.startswith("v ")] for p in sys.argv[1:3])
sys.exit(0 if len(a) == len(b) > 0 and max(abs(x - y) for p, q in zip(a, b) for x, y in zip(p, q)) <= 1e-12 else 1)
PYEOF
expect_error 2 "features\[0\].after_edit: there is no edit" -- "$FS" run $C --set features.0.after_edit=true --out "$SCRATCH/x"
expect_error 2 "base_edit: give the radial bump or a detail-preserving .edit., not both" -- "$FS" run configs/khodakovsky-schroder/fig15.yaml --set base_edit.enabled=true --out "$SCRATCH/x"
expect_error 2 "edit.constraints\[2\]" -- "$FS" run configs/khodakovsky-schroder/fig15.yaml --set edit.constraints.2.spam=1 --out "$SCRATCH/x"
expect_error 2 "edit.spam: unknown key" -- "$FS" run configs/khodakovsky-schroder/fig15.yaml --set edit.spam=1 --out "$SCRATCH/x"
# Design steps: a feature moved as a whole, one re-parameterized, one added and
# one removed between steps; the session ends where the same features placed at once end.
# Both configs: the patch at 3 levels, loose tolerances, no adaptive mesh; then their features.
patch_config() { printf 'defaults: [%s]\ninput: {mesh: %s, levels: 3}\nfeature_defaults: {profile_tolerance: 0.5, width_tolerance: 0.5}\nadaptive: {enabled: false}\n' "$PWD/$C" "$PWD/data/ks_patch.off"; }
{ patch_config; cat <<YAML
features:
  - { name: ridge_a, level: 2, until: 3, points: [[-0.8, -0.55, 0.0587], [-0.2, 0.1, 0.0042], [0.4, 0.25, 0.0155], [0.8, 0.7, 0.0474]] }
  - { name: ridge_b, level: 2, changes: [{step: 2, height: 0.1}], points: [[-0.75, 0.6, 0.0459], [0.0, 0.35, -0.0073], [0.7, -0.6, 0.0372]] }
  - { name: groove, level: 2, height: -0.04, radius: 0.12, moves: [{step: 1, by: [0, -0.2, 0]}], points: [[-0.6, -0.1, 0.0426], [0.1, -0.45, -0.0109], [0.75, 0.05, 0.0674]] }
  - { name: late, level: 2, step: 2, height: -0.03, radius: 0.1, points: [[-0.5, 0.8, -0.0084], [0.5, 0.8, -0.0084]] }
output: {vtk: all}
YAML
} > "$SCRATCH/steps.yaml"
{ patch_config; cat <<YAML
features:
  - { name: ridge_b, level: 2, height: 0.1, points: [[-0.75, 0.6, 0.0459], [0.0, 0.35, -0.0073], [0.7, -0.6, 0.0372]] }
  - { name: groove, level: 2, height: -0.04, radius: 0.12, points: [[-0.6, -0.3, 0.0426], [0.1, -0.65, -0.0109], [0.75, -0.15, 0.0674]] }
  - { name: late, level: 2, height: -0.03, radius: 0.1, points: [[-0.5, 0.8, -0.0084], [0.5, 0.8, -0.0084]] }
YAML
} > "$SCRATCH/at_once.yaml"
"$FS" run "$SCRATCH/steps.yaml" --out "$SCRATCH/steps" 2>/dev/null || fail "the stepped feature session failed"
"$FS" run "$SCRATCH/at_once.yaml" --out "$SCRATCH/at_once" 2>/dev/null || fail "the same features at once failed"
"$FS" run "$SCRATCH/steps.yaml" --out "$SCRATCH/steps_whole" --set step_evaluation=whole 2>/dev/null || fail "the stepped session evaluated whole failed"
[ "$(ls "$SCRATCH/steps/vtk/"*_step*.vtp | wc -l)" -eq 4 ] || fail "expected a VTK per design step"
$PY - "$SCRATCH/steps" "$SCRATCH/at_once" "$SCRATCH/steps_whole" <<'PYEOF' || fail "the session's steps are not reported, or it does not end where the same features placed at once end"
import csv, sys
steps = list(csv.DictReader(open(sys.argv[1] + "/steps.csv")))
ok = [r["step"] for r in steps] == ["0", "1", "2", "3"] and steps[1]["moved"] == "groove" and steps[2]["added"] == "late"
ok = ok and steps[2]["changed"] == "ridge_b" and steps[3]["removed"] == "ridge_a" and all(int(r["vertices_changed"]) > 0 for r in steps[1:])
ok = ok and len(list(csv.DictReader(open(sys.argv[1] + "/features.csv")))) == 3
# Region-limited steps: the first evaluates the whole hierarchy, the later ones their region
# (fewer vertices than the whole, more than the step changed on the finest level); evaluated
# whole, every step reports the whole hierarchy and the session ends on the same surface.
whole = list(csv.DictReader(open(sys.argv[3] + "/steps.csv")))
total = int(steps[0]["vertices_recomputed"])
ok = ok and steps[0]["evaluation"] == "whole" and all(r["evaluation"] == "region" for r in steps[1:])
ok = ok and all(int(r["vertices_changed"]) <= int(r["vertices_recomputed"]) < total for r in steps[1:])
ok = ok and all(r["evaluation"] == "whole" and int(r["vertices_recomputed"]) == total for r in whole)
a, b, c = ([[float(x) for x in l.split()[1:4]] for l in open(d + "/final.obj") if l.startswith("v ")] for d in sys.argv[1:4])
ok = ok and len(a) == len(b) and max(abs(x - y) for p, q in zip(a, b) for x, y in zip(p, q)) <= 1e-12
ok = ok and len(a) == len(c) and max(abs(x - y) for p, q in zip(a, c) for x, y in zip(p, q)) <= 1e-12
sys.exit(0 if ok else 1)
PYEOF
expect_error 2 "features\[0\].moves: only a feature given by world .points. is moved" -- "$FS" run configs/khodakovsky-schroder/fig17.yaml --set 'features.0.moves=[{step: 1, by: [0, 0, 0.1]}]' --out "$SCRATCH/x"
expect_error 2 "step_evaluation: unknown value 'partial' (valid: region, whole)" -- "$FS" run "$SCRATCH/steps.yaml" --set step_evaluation=partial --out "$SCRATCH/x"
expect_error 2 "step_evaluation: the features schedule no design step after the first" -- "$FS" run $C --set step_evaluation=whole --out "$SCRATCH/x"
expect_error 2 "features\[1\].until: 0 must come after step 0" -- "$FS" run $C --set features.1.until=0 --out "$SCRATCH/x"
expect_error 2 "features\[1\].changes\[0\].height" -- "$FS" run $C --set 'features.1.changes=[{step: 1, height: nan}]' --out "$SCRATCH/x"
# The radial bump of the base mesh (base_edit) still carries the features (at 3 levels the grooves,
# drawn on the finest level with 3 edges per radius, miss 2 % by far: the tolerance is loosened).
"$FS" run configs/khodakovsky-schroder/fig14.yaml --out "$SCRATCH/bump" --set input.levels=3 --set feature_defaults.profile_tolerance=0.5 --set feature_defaults.width_tolerance=0.5 --set 'base_edit={nearest: [0, 0, 0], offset: [0, 0, 0.45], radius: 0.45}' 2>/dev/null || fail "the base bump failed"
grep -q ',converged,' "$SCRATCH/bump/runs.csv" || fail "the base bump run did not finish"

expect_error 2 "feature 'ridge_a': point 0 .* the curve leaves the surface" -- \
  "$FS" run $C --set 'features.0.points=[[-0.8, -0.55, 0.9], [0.0, 0.1, 0.0]]' --out "$SCRATCH/x"
expect_error 2 "features\[1\].radius" -- "$FS" run $C --set features.1.radius=-0.1 --out "$SCRATCH/x"
expect_error 2 "features\[0\]: give exactly one of points" -- "$FS" run $C \
  --set 'features.0.surface_points=[[0, 0.2, 0.3, 0.5], [1, 0.2, 0.3, 0.5]]' --out "$SCRATCH/x"
expect_error 2 "features\[2\].level" -- "$FS" run $C --set features.2.level=9 --out "$SCRATCH/x"
expect_error 2 "feature_defaults.flatness_angle_deg" -- "$FS" run $C --set feature_defaults.flatness_angle_deg=120 --out "$SCRATCH/x"
# A radius far beyond the scale at which level 0 of the helmet is flat: refused with a clear
# message before anything runs (the coarsest features are applied at validation). Either check
# may fire first: the optimized back end evaluates the vertices in parallel.
expect_error 2 "feature 'crest': the surface turns by [0-9]* degrees within radius\|vertex [0-9]*: its one-ring folds over" -- \
  "$FS" run configs/khodakovsky-schroder/fig17.yaml --set feature_defaults.radius=0.6 --set 'features.0.level=0' \
  --out "$SCRATCH/wide"
[ ! -e "$SCRATCH/wide/runs.csv" ] || fail "a run with too wide a feature was started"
# Truly adaptive evaluation: a sparse run never builds the uniform hierarchy
# (fewer faces computed than the uniform levels have, fewer finest vertices than the uniform
# finest level), writes the adaptive mesh as final.obj, and measures each feature as the uniform
# run does: the same placement (faces, barycentric coordinates), the same vertices (a sparse
# vertex is the uniform one, sparse_loop.h) and the same measurement on the support, so
# features.csv's finest-level and limit columns agree to rounding (1e-9; the values are O(0.1)
# or less): the limit points of the finest sparse vertices whose one-ring is present
# (feature/sparse_measure.h; the unit test compares them to 1e-10 unrounded).
# The features are drawn on level 2, so levels 2 makes them finest-level features.
S="--set input.levels=2 --set profile_on=drawn_level --set output.vtk=none --set feature_defaults.profile_tolerance=0.5 --set feature_defaults.width_tolerance=0.5"
"$FS" run $C --out "$SCRATCH/sparse" $S --set adaptive.evaluation=sparse 2>/dev/null || fail "sparse run failed"
"$FS" run $C --out "$SCRATCH/sparse_u" $S 2>/dev/null || fail "uniform run for the sparse comparison failed"
# compare_sparse SPARSE UNIFORM: the sparse run computed less than the uniform levels and wrote
# the adaptive mesh; features.csv, worst_profile_error_limit, max_displacement and the attachments
# (faces and points) equal the uniform run's.
compare_sparse() {
$PY - "$1" "$2" <<'PYEOF'
import csv, math, sys
s, u = sys.argv[1], sys.argv[2]
r = list(csv.DictReader(open(s + "/runs.csv")))[0]
ru = list(csv.DictReader(open(u + "/runs.csv")))[0]
uniform_faces = sum(int(ru["triangles_uniform"]) // 4 ** k for k in range(int(r["levels"]) + 1))
ok = r["adaptive_evaluation"] == "sparse" and 0 < int(r["adaptive_faces_computed"]) < uniform_faces
ok = ok and int(r["n_fine"]) < int(ru["n_fine"]) and float(r["peak_rss_mb"]) > 0
ok = ok and sum(1 for l in open(s + "/final.obj") if l.startswith("f ")) == int(r["triangles_adaptive"]) > 0
fs = {x["feature"]: x for x in csv.DictReader(open(s + "/features.csv"))}
fu = {x["feature"]: x for x in csv.DictReader(open(u + "/features.csv"))}
cols = [c + s for s in ("_fine", "_limit") for c in ("height_min", "height_max", "width_left", "width_right", "height_error", "width_error", "profile_error")]
ok = ok and len(fs) > 0 and fs.keys() == fu.keys()
for f in fs:
    for c in cols:
        a, b = float(fs[f][c]), float(fu[f][c])
        if not (abs(a - b) <= 1e-9 or (math.isnan(a) and math.isnan(b))): print(f, c, a, b); ok = False
    ok = ok and math.isfinite(float(fs[f]["profile_error_limit"])) and fs[f]["within_tolerance"] == fu[f]["within_tolerance"]
    ok = ok and fs[f]["level"] == fu[f]["level"]
ok = ok and r["worst_profile_error_limit"] != "" and abs(float(r["worst_profile_error_limit"]) - float(ru["worst_profile_error_limit"])) <= 1e-9
ok = ok and abs(float(r["max_displacement"]) - float(ru["max_displacement"])) <= 1e-9
sa = [x for x in csv.DictReader(open(s + "/attachments.csv"))]
ua = [x for x in csv.DictReader(open(u + "/attachments.csv"))]
key = lambda x: (x["feature"], x["level"], x["point"], x["face"])
ok = ok and sorted(map(key, sa)) == sorted(map(key, ua))
where = {key(x): x for x in ua}
for x in sa:
    y = where.get(key(x))
    if y is None or max(abs(float(x[c]) - float(y[c])) for c in ("x", "y", "z")) > 1e-9: print("attachment", key(x)); ok = False; break
sys.exit(0 if ok else 1)
PYEOF
}
compare_sparse "$SCRATCH/sparse" "$SCRATCH/sparse_u" || fail "sparse run (finest-level features): expected the uniform run's features.csv and attachments, no uniform level built, final.obj = the adaptive mesh"
# Features drawn below the finest level (level 2 of 3), the profile exact at the limit (the
# default) and on the finest level: the region they change is computed down to the finest level,
# and the measures are the uniform run's.
S3="--set input.levels=3 --set output.vtk=none --set feature_defaults.profile_tolerance=0.5 --set feature_defaults.width_tolerance=0.5"
for target in limit finest; do
  "$FS" run $C --out "$SCRATCH/sparse3_$target" $S3 --set profile_on=$target --set adaptive.evaluation=sparse 2>/dev/null || fail "sparse run ($target) failed"
  "$FS" run $C --out "$SCRATCH/sparse3_u_$target" $S3 --set profile_on=$target 2>/dev/null || fail "uniform run ($target) failed"
  compare_sparse "$SCRATCH/sparse3_$target" "$SCRATCH/sparse3_u_$target" || fail "sparse run (features on level 2 of 3, profile_on $target): expected the uniform run's features.csv and attachments"
done
# Placement tools on a level small enough to be computed whole (Figure 17: six curves placed by
# sections, geodesics and a file on level 1 of the helmet, at its 3 levels: at 2 its radii are
# narrower than two finest edges and refused): the uniform run's features.
F17="configs/khodakovsky-schroder/fig17.yaml --set input.levels=3 --set output.vtk=none --set feature_defaults.profile_tolerance=0.9 --set feature_defaults.width_tolerance=0.9"
"$FS" run $F17 --out "$SCRATCH/sparse17" --set adaptive.evaluation=sparse 2>/dev/null || fail "sparse run with placement tools failed"
"$FS" run $F17 --out "$SCRATCH/sparse17_u" 2>/dev/null || fail "uniform Figure 17 run failed"
compare_sparse "$SCRATCH/sparse17" "$SCRATCH/sparse17_u" || fail "sparse run with placement tools: expected the uniform run's features.csv and attachments"
# A feature taller than the surface's local scale is a miss in a sparse run as in a uniform one:
# the scale is measured on what the sparse run computes (the drawn level's patch, the base mesh).
for ev in sparse uniform; do
  rc=0; "$FS" run $C --out "$SCRATCH/tall_$ev" --set input.levels=3 --set output.vtk=none --set feature_defaults.height=5 --set feature_defaults.profile_tolerance=0.2 --set feature_defaults.width_tolerance=0.5 --set adaptive.evaluation=$ev 2>/dev/null || rc=$?
  [ "$rc" -eq 3 ] || fail "a feature taller than the local scale ($ev) must not succeed (exit $rc)"
  $PY - "$SCRATCH/tall_$ev" <<'PYEOF' || fail "a feature taller than the local scale ($ev): expected within_tolerance 0 naming the scale"
import csv, sys
r = list(csv.DictReader(open(sys.argv[1] + "/runs.csv")))[0]
f = list(csv.DictReader(open(sys.argv[1] + "/features.csv")))
# Five times the scale also turns faces over: a fold outranks the misses, which its message keeps.
folded = r["termination"] == "folded" and int(r["flipped_faces"]) > 0 and "features miss their tolerance" in r["message"]
ok = (r["termination"] == "constraints_unmet" or folded) and r["features_within_tolerance"] == "0" and "not checked" not in r["message"]
# The two ridges take the default height 5 (the groove keeps its own, -0.04, and misses where they cross it).
tall = [x for x in f if x["feature"] in ("ridge_a", "ridge_b")]
ok = ok and len(f) == 3 and len(tall) == 2 and all(x["within_tolerance"] == "0" and "exceeds the local scale of the surface" in x["miss"] for x in tall)
sys.exit(0 if ok else 1)
PYEOF
done
# The sparse run's computed faces hold every face the features move: the same folds as the uniform run's.
$PY - "$SCRATCH/tall_sparse/runs.csv" "$SCRATCH/tall_uniform/runs.csv" <<'PYEOF' || fail "a feature taller than the local scale: the sparse and uniform runs count different folds"
import csv, sys
flips = [list(csv.DictReader(open(p)))[0]["flipped_faces"] for p in sys.argv[1:]]
sys.exit(0 if flips[0] == flips[1] else 1)
PYEOF
# The same on a model the method was not tuned on: a groove of 0.2 cut into the knot's tube (its
# radius of curvature 0.055 there), drawn on level 1 of 3 — converged, within tolerance, before.
cat > "$SCRATCH/knot_tall.yaml" <<YAML
name: knot_tall
input: { mesh: $PWD/data/knot.off, levels: 3 }
feature_defaults: { radius: 0.04, height: -0.2, quadratic: false, profile_tolerance: 0.9, width_tolerance: 0.9, max_turn_deg: 179 }
features:
  - { name: cut, level: 1, max_distance: 0.1, points: [[-0.178207, 0.0240985, 0.113362], [-0.16583, 0.0293945, 0.129887]] }
output: { vtk: none }
adaptive: { evaluation: sparse }
YAML
rc=0; "$FS" run "$SCRATCH/knot_tall.yaml" --out "$SCRATCH/knot_tall" 2>/dev/null || rc=$?
[ "$rc" -eq 3 ] || fail "a groove deeper than the knot's tube (sparse) must not succeed (exit $rc)"
grep -q "0,height |h| 0.2 exceeds the local scale of the surface 0.05.* (curvature)" "$SCRATCH/knot_tall/features.csv" || fail "the knot's groove: expected the local-scale miss in features.csv"
# A feature narrower than two edges of its finest level is refused at load, naming the key,
# its radius, the finest edge and what to change (the patch's level-3 edges are about 0.024).
for ev in uniform sparse; do
  expect_error 2 "features\[2\].radius: feature 'groove' is narrower than 2 edges of its finest level: its radius 0.03 against finest edges of about 0.02.* under the curve (level 3).*give a radius of at least 0.0.* or input.levels: 4" -- \
    "$FS" run $C --set input.levels=3 --set output.vtk=none --set features.2.radius=0.03 --set adaptive.evaluation=$ev --out "$SCRATCH/x"
done
expect_error 2 "features\[0\].radius: feature 'ridge_a' is narrower than 2 edges of its finest level: its right side's radius (radius / left_right_ratio) 0.036" -- \
  "$FS" run $C --set input.levels=3 --set features.0.left_right_ratio=5 --out "$SCRATCH/x"
# What needs the whole hierarchy is refused with sparse, naming the key and the valid choices.
expect_error 2 "output.vtk: with adaptive.evaluation: sparse no VTK is written" -- "$FS" run $C --set input.levels=2 --set profile_on=drawn_level --set adaptive.evaluation=sparse --out "$SCRATCH/x"
expect_error 2 "features\[0\].section: the tool needs its whole level; level 1 has 4000 faces > adaptive.placement_max_faces 1000 with adaptive.evaluation: sparse (draw the curve on a coarser level, raise adaptive.placement_max_faces" -- "$FS" run $F17 --set adaptive.evaluation=sparse --set adaptive.placement_max_faces=1000 --out "$SCRATCH/x"
expect_error 2 "adaptive.placement_max_faces: only with adaptive.evaluation: sparse" -- "$FS" run $F17 --set adaptive.placement_max_faces=1000 --out "$SCRATCH/x"
expect_error 2 "features\[1\]: design steps (step, until, moves, changes)" -- "$FS" run $C $S --set adaptive.evaluation=sparse --set features.1.step=1 --out "$SCRATCH/x"
expect_error 2 "adaptive.evaluation: unknown value 'dense' (valid: uniform, sparse)" -- "$FS" run $C --set adaptive.evaluation=dense --out "$SCRATCH/x"
expect_error 2 "adaptive.surface_angle_deg: only with adaptive.evaluation: sparse" -- "$FS" run $C --set adaptive.surface_angle_deg=3 --out "$SCRATCH/x"
# The surface edit under the features is checked as a surface edit's result: a handle pulled
# sideways through a 1-ring region folds the patch, and the run ends `folded` (exit 3) saying
# it was the edit, before any feature is drawn on the folded surface.
rc=0
"$FS" run configs/khodakovsky-schroder/fig15.yaml --smoke --out "$SCRATCH/edit_folds" --set 'edit.constraints.2.offset=[0.6, 0, 0]' \
  --set edit.constraints.2.influence_rings=1 > /dev/null 2>&1 || rc=$?
[ "$rc" -eq 3 ] || fail "a folding edit under the features exits $rc, not 3"
$PY - "$SCRATCH/edit_folds/runs.csv" <<'PYEOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert rows and all(r["termination"] == "folded" and r["message"].startswith("the edit: ") and "faces flipped" in r["message"]
                    for r in rows), [(r["termination"], r["message"][:120]) for r in rows]
PYEOF
echo "feature_run: ok"
