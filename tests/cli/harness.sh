# The experiment harness never loses, mixes or misplaces a result (issue: one experiment
# harness). Each block is one failure it used to have.
source "$(dirname "$0")/lib.sh"
CFG=tests/data/configs/harness_sweep.yaml
SMOKE=configs/smoke/cow_nose_pull.yaml

# Runs that differ only in an output-free key (description) get distinct ids and rows.
"$FS" run $CFG --out "$SCRATCH/full" 2>/dev/null
[ "$(data_rows "$SCRATCH/full/runs.csv")" -eq 6 ] || fail "six points, six rows"
[ "$(cut -d, -f1 "$SCRATCH/full/runs.csv" | sort -u | wc -l)" -eq 7 ] || fail "run ids collide"
[ "$(ls "$SCRATCH"/full/final/*.obj | wc -l)" -eq 6 ] || fail "final meshes overwrite each other"
"$FS" --version > "$SCRATCH/version.txt" || fail "--version failed"
$PY - "$SCRATCH/full" <<'PYEOF'
import csv, json, sys
d = sys.argv[1]
runs = list(csv.DictReader(open(f"{d}/runs.csv")))
its = list(csv.DictReader(open(f"{d}/iterations.csv")))
# Every table carries the run's id, its swept parameters and its solver columns.
for col in ["run_id", "solver.type", "description", "implementation"]:
    assert col in its[0], col
ids = {r["run_id"] for r in runs}
assert {r["run_id"] for r in its} == ids
# seconds never decrease within a run (observation time is left out consistently)
by = {}
for r in its:
    by.setdefault(r["run_id"], []).append(float(r["seconds"]))
for k, s in by.items():
    assert all(b >= a for a, b in zip(s, s[1:])), (k, s)
# A surface run has no steps.csv rows, so no steps.csv.
import os
assert not os.path.exists(f"{d}/steps.csv")
meta = json.load(open(f"{d}/run.json"))
assert len(meta["git_commit"]) in (40, 7) or meta["git_commit"] == "unknown"
version = open(f"{d}/../version.txt").read().split()
assert version[0] == "fairshape" and version[1] == meta["fairshape_version"], (version, meta["fairshape_version"])
assert meta["fairshape_version"].count(".") == 2, meta["fairshape_version"]
s = meta["sessions"][0]
for k in ["argv", "shard", "filter", "input_sha256", "started", "ended", "exit_status"]:
    assert k in s, k
assert any(len(h) == 64 for h in s["input_sha256"].values()), s["input_sha256"]
PYEOF

# --dry-run lists the points with their ids and runs nothing.
"$FS" run $CFG --dry-run --out "$SCRATCH/dry" > "$SCRATCH/dry.txt" 2>/dev/null
grep -q "6 of 6 point" "$SCRATCH/dry.txt" || fail "--dry-run header"
[ ! -e "$SCRATCH/dry" ] || fail "--dry-run wrote an output folder"

# A resume with another config is refused, naming the key; run.json is not rewritten.
cp "$SCRATCH/full/run.json" "$SCRATCH/run.json.before"
expect_error 2 "solver.max_iterations" -- "$FS" run $CFG --out "$SCRATCH/full" --resume --set solver.max_iterations=50
cmp -s "$SCRATCH/full/run.json" "$SCRATCH/run.json.before" || fail "a refused resume touched run.json"
# A resume of the finished sweep runs nothing and appends a session to run.json.
"$FS" run $CFG --out "$SCRATCH/full" --resume 2>/dev/null
$PY -c "import json,sys; assert len(json.load(open('$SCRATCH/full/run.json'))['sessions']) == 2"

# A --set on a swept key replaces that axis; one inside a zipped key is refused, never dropped.
"$FS" run $CFG --out "$SCRATCH/replaced" --set solver.type=sor 2>"$SCRATCH/replaced.log"
grep -q "replaces the sweep axis" "$SCRATCH/replaced.log" || fail "no note that --set replaced the axis"
[ "$(data_rows "$SCRATCH/replaced/runs.csv")" -eq 2 ] || fail "--set on a swept key"
expect_error 2 "overlaps the swept key" -- "$FS" run configs/demo.yaml --out "$SCRATCH/demo" --set energy.0.type=thinplate

# Names and ids that would leave results/ are refused at validation.
expect_error 2 "plain folder name" -- "$FS" run $SMOKE --set name=../escaped
expect_error 2 "plain folder name" -- "$FS" run $SMOKE --set "name=$SCRATCH/absolute"
[ ! -e escaped ] && [ ! -e "$SCRATCH/absolute" ] || fail "wrote outside results"

# A second writer on one folder is refused while the first runs.
"$FS" run $CFG --out "$SCRATCH/locked" 2>/dev/null &
first=$!
for _ in $(seq 1 200); do [ -f "$SCRATCH/locked/.lock" ] && break; sleep 0.05; done
expect_error 2 "another fairshape run is writing" -- "$FS" run $CFG --out "$SCRATCH/locked" --resume
wait $first

# kill -9 of the supervisor under --jobs 2: no process is left, and a resume gives exactly
# the rows of an uninterrupted run, in every table.
"$FS" run $CFG --out "$SCRATCH/killed" --jobs 2 2>/dev/null &
pid=$!
for _ in $(seq 1 400); do
  [ -f "$SCRATCH/killed/runs.csv" ] && [ "$(data_rows "$SCRATCH/killed/runs.csv")" -ge 2 ] && break
  sleep 0.02
done
kill -9 $pid; wait $pid 2>/dev/null || true
sleep 0.5
if pgrep -f -- "--out $SCRATCH/killed" >/dev/null; then fail "workers outlived their supervisor"; fi
"$FS" run $CFG --out "$SCRATCH/killed" --resume --jobs 2 2>/dev/null
rows_equal "$SCRATCH/full/runs.csv" "$SCRATCH/killed/runs.csv" || fail "runs.csv after kill + resume"
$PY - "$SCRATCH/full/iterations.csv" "$SCRATCH/killed/iterations.csv" <<'PYEOF'
import csv, sys
def key(p):
    return sorted((r["run_id"], int(r["iteration"]), r["residual"]) for r in csv.DictReader(open(p)))
a, b = key(sys.argv[1]), key(sys.argv[2])
assert a == b, f"iterations.csv differs after kill + resume: {len(a)} vs {len(b)} rows"
PYEOF
if find "$SCRATCH/killed" -name '*.tmp.*' | grep -q .; then fail "temporary files left behind"; fi

# A run that throws a foreign exception, or whose worker is killed by a signal, becomes a
# crashed row; the sweep finishes (exit 3), and --retry-failed runs it again.
rc=0; FAIRSHAPE_FAULT_INJECTION=length_error@1 "$FS" run $CFG --out "$SCRATCH/throw" 2>/dev/null || rc=$?
[ $rc -eq 3 ] || fail "a crashed run: exit $rc, expected 3"
[ "$(data_rows "$SCRATCH/throw/runs.csv")" -eq 6 ] || fail "the sweep did not go on after an exception"
grep -q "crashed.*length_error" "$SCRATCH/throw/runs.csv" || fail "no crashed row for std::length_error"
rc=0; FAIRSHAPE_FAULT_INJECTION=segv@2 "$FS" run $CFG --out "$SCRATCH/segv" --jobs 2 2>/dev/null || rc=$?
[ $rc -eq 3 ] || fail "a worker killed by SIGSEGV: exit $rc, expected 3"
[ "$(data_rows "$SCRATCH/segv/runs.csv")" -eq 6 ] || fail "the sweep did not go on after a signal"
grep -q "crashed.*signal 11" "$SCRATCH/segv/runs.csv" || fail "no crashed row for the signal"
"$FS" run $CFG --out "$SCRATCH/segv" --resume --retry-failed 2>/dev/null
rows_equal "$SCRATCH/full/runs.csv" "$SCRATCH/segv/runs.csv" || fail "--retry-failed did not redo the crashed run"

# Shards merged folder by folder give the unsharded tables, iterations.csv included.
for i in 0 1; do "$FS" run $CFG --out "$SCRATCH/shard$i" --shard $i/2 2>/dev/null; done
"$FS" merge "$SCRATCH/merged" "$SCRATCH/shard0" "$SCRATCH/shard1"
rows_equal "$SCRATCH/full/runs.csv" "$SCRATCH/merged/runs.csv" || fail "merged runs.csv"
$PY - "$SCRATCH/full/iterations.csv" "$SCRATCH/merged/iterations.csv" <<'PYEOF'
import csv, sys
def key(p):
    return sorted((r["run_id"], int(r["iteration"]), r["residual"]) for r in csv.DictReader(open(p)))
assert key(sys.argv[1]) == key(sys.argv[2]), "merged iterations.csv differs from the unsharded one"
PYEOF
expect_error 2 "holds another experiment" -- "$FS" merge "$SCRATCH/bad" "$SCRATCH/shard0" "$SCRATCH/replaced"

# Outcomes: the energy rule stopping a run is a success; an unreached tolerance is not. The nose
# moves a tenth of the smoke edit's: a few Gauss-Seidel sweeps leave the full edit's handle pulled
# out alone, folding the faces around it — a fold, which no stopping rule makes a success.
SMALL='constraints=[{type: fixed, region: {axis: x, from: 0.0, to: 0.3}}, {type: position, nearest: [0.5, 0.0, 0.0], offset: [0.015, 0.0, 0.008]}]'
expect_error 3 "folded: .* faces flipped" -- "$FS" run $SMOKE --out "$SCRATCH/folded" --set solver.type=gauss_seidel \
  --set solver.tolerance=0 --set solver.max_iterations=5
"$FS" run $SMOKE --out "$SCRATCH/stalled" --set solver.type=gauss_seidel --set solver.tolerance=0 --set "$SMALL" \
  --set solver.energy_tolerance=1.0e-3 --set solver.max_iterations=100000 2>/dev/null || fail "energy_stalled exits non-zero"
grep -q energy_stalled "$SCRATCH/stalled/runs.csv" || fail "no energy_stalled row"
expect_error 3 "max_iterations" -- "$FS" run $SMOKE --out "$SCRATCH/unreached" --set solver.type=gauss_seidel \
  --set solver.tolerance=1.0e-12 --set solver.max_iterations=5
"$FS" run $SMOKE --out "$SCRATCH/fixed" --set solver.type=gauss_seidel --set solver.tolerance=0 --set "$SMALL" \
  --set solver.max_iterations=5 2>/dev/null || fail "a fixed sweep count (the papers' rule) exits non-zero"
grep -q schedule_completed "$SCRATCH/fixed/runs.csv" || fail "no schedule_completed row"
expect_error 3 "max_iterations" -- "$FS" run configs/sauvage/fig3.yaml --out "$SCRATCH/curve" \
  --set optimization.solver.max_solves=1 --set 'sweep.edits.0.wrinkle_level=[3]'
# A key's validity does not depend on its siblings; what the run does not use is recorded as
# unused, never as used (no linear solver runs under constraint_mode kkt).
"$FS" run $SMOKE --out "$SCRATCH/unused" --set problem.constraint_mode=kkt --set solver.type=sor \
  --set solver.tolerance=1.0e-7 --set solver.multigrid.max_levels=2 2>/dev/null || fail "solver options beside kkt"
$PY - "$SCRATCH/unused/runs.csv" <<'PYEOF'
import csv, sys
r = list(csv.DictReader(open(sys.argv[1])))[0]
assert r["solver.type"] == "", r["solver.type"]
assert set(r["unused_keys"].split()) == {"solver.type", "solver.tolerance", "solver.multigrid"}, r["unused_keys"]
PYEOF
expect_error 2 "solver.tolerence: unknown key" -- "$FS" run $SMOKE --set solver.tolerence=1e-7
echo "harness: ok"
