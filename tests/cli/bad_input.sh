source "$(dirname "$0")/lib.sh"
M=tests/data/malformed
expect_error 2 "nonmanifold_edge.off" -- "$FS" info $M/nonmanifold_edge.off
expect_error 2 "non-manifold edge" -- "$FS" info $M/nonmanifold_edge.off
expect_error 2 "truncated_vertices.off:2: the vertex count is 4" -- "$FS" info $M/truncated_vertices.off
expect_error 2 "truncated_faces.off:.*file ends after 1 of 2 faces" -- "$FS" info $M/truncated_faces.off
expect_error 2 "only .* bytes follow" -- "$FS" info $M/absurd_count.off
expect_error 2 "valid: .obj, .off, .ply, .vtp" -- "$FS" convert data/cow.off "$SCRATCH/cow.stl"
[ ! -e "$SCRATCH/cow.stl" ] || fail "a refused conversion left a file"
expect_error 2 "config file not found" -- "$FS" run nowhere.yaml
expect_error 2 "colour: unknown key" -- "$FS" run configs/smoke/cow_nose_pull.yaml --set colour=red --out "$SCRATCH/x"
expect_error 2 "unknown value 'multigrd'" -- "$FS" run configs/smoke/cow_nose_pull.yaml --set solver.type=multigrd --out "$SCRATCH/x"
expect_error 2 "solver.sor.omega" -- "$FS" run configs/smoke/cow_nose_pull.yaml --set solver.sor.omega=2.5 --out "$SCRATCH/x"
expect_error 2 "multigrid_cg needs a symmetric cycle" -- "$FS" run configs/smoke/cow_nose_pull.yaml --set solver.type=multigrid_cg --set solver.multigrid.pre_smooth=1 --out "$SCRATCH/x"
expect_error 2 "problem.drag_steps: a drag needs problem.accuracy" -- "$FS" run configs/smoke/cow_nose_pull.yaml --set problem.drag_steps=4 --out "$SCRATCH/x"
expect_error 2 "problem.coarse_level: 3 is above the edit level" -- "$FS" run configs/smoke/cow_nose_pull.yaml --set problem.accuracy=interactive --set problem.coarse_level=3 --out "$SCRATCH/x"
expect_error 2 "interactive needs problem.constraint_mode paper" -- "$FS" run configs/smoke/cow_nose_pull.yaml --set problem.accuracy=interactive --set problem.constraint_mode=kkt --out "$SCRATCH/x"
expect_error 2 "problem.accuracy: unknown value 'fast' (valid: single-level, interactive" -- "$FS" run configs/smoke/cow_nose_pull.yaml --set problem.accuracy=fast --out "$SCRATCH/x"
expect_error 2 "expected key.path=value" -- "$FS" run configs/smoke/cow_nose_pull.yaml --set oops
expect_error 2 "--resume needs --out" -- "$FS" run configs/smoke/cow_nose_pull.yaml --resume
expect_error 2 "expected i/n" -- "$FS" run configs/smoke/cow_nose_pull.yaml --shard 3 --out "$SCRATCH/x"
# All problems of a sweep are listed at once, before any run.
expect_error 2 "2 problem(s), nothing was run" -- "$FS" run configs/smoke/cow_nose_pull.yaml \
  --set 'sweep.solver.type=[cholesky, nope]' --set 'sweep.input.mesh=[data/cow.off, data/none.off]' --out "$SCRATCH/y"
[ ! -e "$SCRATCH/y/runs.csv" ] || fail "an invalid sweep wrote results"
# Incompatible targets on one vertex: the run fails with a message, the sweep records it.
rc=0; "$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/conflict" \
  --set 'constraints=[{type: fixed, vertices: [5]}, {type: position, vertices: [5], offset: [1, 0, 0]}]' 2>/dev/null || rc=$?
[ "$rc" -eq 3 ] || fail "conflicting targets: exit $rc, expected 3"
grep -q "invalid_input" "$SCRATCH/conflict/runs.csv" || fail "no invalid_input row"
grep -q "incompatible targets" "$SCRATCH/conflict/runs.csv" || fail "no message"
# Nothing pinned under a translation-invariant energy: singular, reported, never NaN.
rc=0; "$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/singular" --set 'constraints=[]' --set solver.type=gauss_seidel \
  2>/dev/null || rc=$?
[ "$rc" -eq 3 ] || fail "singular system: exit $rc, expected 3"
grep -q "invalid_input" "$SCRATCH/singular/runs.csv" || fail "singular system not reported"
grep -q "no constraint: the deformation is undetermined" "$SCRATCH/singular/runs.csv" || fail "singular system: no message"
! grep -qi "nan" "$SCRATCH/singular/runs.csv" || fail "NaN written"
# An existing result folder is not overwritten by accident.
expect_error 2 "already holds results" -- "$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/conflict"
echo "bad_input: ok"
