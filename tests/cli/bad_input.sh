source "$(dirname "$0")/lib.sh"
M=tests/data/malformed
expect_error 2 "nonmanifold_edge.off" -- "$FS" info $M/nonmanifold_edge.off
expect_error 2 "non-manifold edge" -- "$FS" info $M/nonmanifold_edge.off
expect_error 2 "truncated_vertices.off:2: the vertex count is 4" -- "$FS" info $M/truncated_vertices.off
expect_error 2 "truncated_faces.off:.*file ends after 1 of 2 faces" -- "$FS" info $M/truncated_faces.off
expect_error 2 "crease_missing_edge.obj:6: crease 0-2: the mesh has no edge between vertices 0 and 2" -- "$FS" info $M/crease_missing_edge.obj
expect_error 2 "crease/corner tags would be lost" -- "$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/x" \
  --set input.mesh=tests/data/osd-shapes/tagged/catmark_cube_creases1.obj --set input.representation=catmull-clark --set input.remesh_base_faces=6
# The crease method names its choices; a normal at a vertex on a sharp crease names each
# side's surface point instead (constraint/crease_normals.h).
CREASED=(--set input.mesh=tests/data/osd-shapes/tagged/catmark_inf_crease1.obj --set input.representation=catmull-clark --set input.levels=1)
expect_error 2 "input.crease_method: unknown value 'sharp' (valid: uniform, chaikin)" -- "$FS" run configs/smoke/cow_nose_pull.yaml \
  --out "$SCRATCH/x" "${CREASED[@]}" --set input.crease_method=sharp
expect_error 2 "vertex 13 of level 0 is on a sharp crease.*side 1 (faces 7 8 9 10): at: {face: 7, uv: \[0, 0\], level: 0}" -- \
  "$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/x" "${CREASED[@]}" --set input.edit_level=0 \
  --set 'constraints=[{type: fixed, vertices: [0], level: 0}, {type: normal, vertices: [13], level: 0, normal: [0, 0, 1]}]'
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
# Incompatible targets on one vertex, or nothing pinned under a translation-invariant energy:
# refused by validation, naming both constraints, before anything runs.
expect_error 2 "incompatible targets" -- "$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/conflict" \
  --set 'constraints=[{type: fixed, vertices: [5]}, {type: position, vertices: [5], offset: [1, 0, 0]}]'
[ ! -e "$SCRATCH/conflict/runs.csv" ] || fail "a conflicting run was started"
expect_error 2 "no constraint: the deformation is undetermined" -- "$FS" run configs/smoke/cow_nose_pull.yaml \
  --out "$SCRATCH/singular" --set 'constraints=[]' --set solver.type=gauss_seidel
# What validation cannot see without the assembled problem is the run's row, saying so.
rc=0; "$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/rows" --set problem.constraint_mode=range_space \
  --set 'constraints.0.region.to=0.8' --set 'constraints.1={type: normal, nearest: [0.5, 0.0, 0.0], normal: [1, 0, 0]}' \
  2>/dev/null || rc=$?
[ "$rc" -eq 3 ] || fail "too many rows for range_space: exit $rc, expected 3"
grep -q "invalid_input,in the assembled problem: range_space: [0-9]* constraint rows are too many" "$SCRATCH/rows/runs.csv" ||
  fail "the row does not say the assembled problem was refused"
# An existing result folder is not overwritten by accident.
"$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/done" > /dev/null 2>&1 || fail "the smoke run failed"
expect_error 2 "already holds results" -- "$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/done"
echo "bad_input: ok"
# A hierarchy over the refinement memory limit is refused naming the key that raises it.
expect_error 2 "over the limit of .*input.max_memory_gb" -- "$FS" run configs/smoke/cow_nose_pull.yaml --out "$SCRATCH/x" \
  --set input.representation=catmull-clark --set input.levels=2 --set input.max_memory_gb=0.001
