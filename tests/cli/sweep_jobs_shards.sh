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
"$FS" run $CFG --out "$SCRATCH/replaced" --set 'sweep.solver.max_iterations=[50]' 2>/dev/null
[ "$(data_rows "$SCRATCH/replaced/runs.csv")" -eq 4 ] || fail "--set on a sweep list"
echo "sweep_jobs_shards: ok"
