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
# Exports (issue 24 part 5): per-level VTPs with the feature displacements, the limit surface,
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
# The achieved profile per feature (issue 24); a feature outside its tolerance is no convergence.
head -1 "$SCRATCH/fig11/features.csv" | grep -q "height_min_limit,.*profile_error_limit,within_tolerance" || fail "features.csv lacks the limit profile"
[ "$(tail -n +2 "$SCRATCH/fig11/features.csv" | wc -l)" -eq 3 ] || fail "expected one features.csv row per feature"
rc=0; "$FS" run $C --out "$SCRATCH/tight" --set input.levels=3 --set adaptive.enabled=false 2>/dev/null || rc=$?
[ "$rc" -eq 3 ] || fail "a feature outside its tolerance must not converge (exit $rc)"
grep -q "constraints_unmet,.*features miss their tolerance; first: feature 'ridge_a' (level 2), finest level: profile error" "$SCRATCH/tight/runs.csv" || fail "the miss is not named"
expect_error 2 "features\[0\].profile_tolerance" -- "$FS" run $C --set features.0.profile_tolerance=2 --out "$SCRATCH/x"
expect_error 2 "profile_on: unknown value 'coarse'" -- "$FS" run $C --set profile_on=coarse --out "$SCRATCH/x"
# Figure 15: the coarse edit moves the surface, the features stay on it (at 3 levels the grooves,
# drawn on the finest level with 3 edges per radius, miss 2 % by far: the tolerance is loosened).
"$FS" run configs/khodakovsky-schroder/fig15.yaml --out "$SCRATCH/fig15" --set input.levels=3 --set feature_defaults.profile_tolerance=0.5 --set feature_defaults.width_tolerance=0.5 2>/dev/null || fail "fig15 failed"
[ "$(grep -c ',converged,' "$SCRATCH/fig15/runs.csv")" -eq 2 ] || fail "fig15 runs did not finish"

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
echo "feature_run: ok"
