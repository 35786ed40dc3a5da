# --jobs N and --shard i/n + merge give the rows of a serial run.
source "$(dirname "$0")/lib.sh"
CFG=tests/data/configs/small_sweep.yaml
"$FS" run $CFG --out "$SCRATCH/serial" 2>/dev/null
"$FS" run $CFG --out "$SCRATCH/jobs" --jobs 2 2>/dev/null
rows_equal "$SCRATCH/serial/runs.csv" "$SCRATCH/jobs/runs.csv" || fail "--jobs rows differ"
for i in 0 1 2; do "$FS" run $CFG --out "$SCRATCH/shard$i" --shard $i/3 2>/dev/null; done
"$FS" merge "$SCRATCH/merged.csv" "$SCRATCH"/shard{0,1,2}/runs.csv
rows_equal "$SCRATCH/serial/runs.csv" "$SCRATCH/merged.csv" || fail "merged shards differ"
[ "$(data_rows "$SCRATCH/shard0/runs.csv")" -lt 16 ] || fail "a shard ran everything"
ls "$SCRATCH"/jobs/final/*.obj | wc -l | grep -q 16 || fail "final meshes of a sweep"
# --filter keeps a subset; a --set on a sweep list replaces it.
"$FS" run $CFG --out "$SCRATCH/filtered" --filter solver.max_iterations=200 2>/dev/null
[ "$(data_rows "$SCRATCH/filtered/runs.csv")" -eq 4 ] || fail "--filter"
"$FS" run $CFG --out "$SCRATCH/replaced" --set 'sweep.solver.max_iterations=[150]' 2>/dev/null
[ "$(data_rows "$SCRATCH/replaced/runs.csv")" -eq 4 ] || fail "--set on a sweep list"
# Tables of two experiments are not joined with nothing saying which row is which: refused,
# naming the files and the differing keys (as merging their folders is). A table with no
# config.resolved.yaml beside it cannot be checked, so each row names its file instead.
expect_error 2 "replaced/runs.csv: holds another experiment than .*serial/runs.csv" -- \
  "$FS" merge "$SCRATCH/mixed.csv" "$SCRATCH/serial/runs.csv" "$SCRATCH/replaced/runs.csv"
grep -q "sweep.solver.max_iterations" "$SCRATCH/stderr.txt" || fail "the refused merge does not name the differing key"
[ ! -e "$SCRATCH/mixed.csv" ] || fail "a refused merge wrote its output"
mkdir -p "$SCRATCH/loose"
cp "$SCRATCH/serial/runs.csv" "$SCRATCH/loose/a.csv" && cp "$SCRATCH/replaced/runs.csv" "$SCRATCH/loose/b.csv"
"$FS" merge "$SCRATCH/loose.csv" "$SCRATCH/loose/a.csv" "$SCRATCH/loose/b.csv"
$PY - "$SCRATCH/loose.csv" "$SCRATCH/loose" <<'PYEOF'
import csv, os, sys
rows = list(csv.DictReader(open(sys.argv[1])))
sources = [r["source"] for r in rows]
want = {os.path.join(sys.argv[2], n): sum(1 for _ in open(os.path.join(sys.argv[2], n))) - 1 for n in ("a.csv", "b.csv")}
assert {s: sources.count(s) for s in set(sources)} == want, (set(sources), want)
PYEOF
echo "sweep_jobs_shards: ok"
