# A sweep killed at any moment and resumed produces exactly the rows of an uninterrupted one.
source "$(dirname "$0")/lib.sh"
CFG=tests/data/configs/small_sweep.yaml
"$FS" run $CFG --out "$SCRATCH/full" 2>/dev/null
[ "$(data_rows "$SCRATCH/full/runs.csv")" -eq 16 ] || fail "uninterrupted sweep"

"$FS" run $CFG --out "$SCRATCH/killed" 2>/dev/null &
pid=$!
for _ in $(seq 1 600); do
  [ -f "$SCRATCH/killed/runs.csv" ] && [ "$(data_rows "$SCRATCH/killed/runs.csv")" -ge 3 ] && break
  sleep 0.05
done
kill -9 $pid 2>/dev/null || true
wait $pid 2>/dev/null || true
done_rows=$(data_rows "$SCRATCH/killed/runs.csv")
[ "$done_rows" -lt 16 ] || fail "the sweep finished before it could be killed"
# Simulate a row cut in the middle of its write.
printf 'deadbeef,partial' >> "$SCRATCH/killed/runs.csv"
"$FS" run $CFG --out "$SCRATCH/killed" --resume 2> "$SCRATCH/resume.log"
grep -q "already done" "$SCRATCH/resume.log" || fail "resume did not skip finished runs"
rows_equal "$SCRATCH/full/runs.csv" "$SCRATCH/killed/runs.csv" || fail "resumed rows differ"

# SIGTERM to the workers, as a scheduler cancelling or requeueing a job sends it to every
# process (the workers' may come first): a stop, not crashes (no crashed row, exit 143), and a
# resume completes the sweep.
"$FS" run $CFG --out "$SCRATCH/termed" --jobs 2 2>/dev/null &
pid=$!
for _ in $(seq 1 600); do
  [ -f "$SCRATCH/termed/runs.csv" ] && [ "$(data_rows "$SCRATCH/termed/runs.csv")" -ge 3 ] && break
  sleep 0.05
done
pkill -TERM -P $pid  # the supervisor's children only: it hears of the stop from them
rc=0; wait $pid || rc=$?
[ "$(data_rows "$SCRATCH/termed/runs.csv")" -lt 16 ] || fail "the sweep finished before the SIGTERM"
[ $rc -eq 143 ] || fail "a SIGTERM to the workers: exit $rc, expected 143"
if grep -q crashed "$SCRATCH/termed/runs.csv"; then fail "a SIGTERM to the workers left a crashed row"; fi
"$FS" run $CFG --out "$SCRATCH/termed" --resume --jobs 2 2>/dev/null
rows_equal "$SCRATCH/full/runs.csv" "$SCRATCH/termed/runs.csv" || fail "rows after SIGTERM + resume"
echo "sweep_resume: ok (killed after $done_rows rows)"
