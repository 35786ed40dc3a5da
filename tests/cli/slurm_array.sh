# `fairshape submit --slurm --now` on a real Slurm: a single-node cluster on localhost started
# for this test only (slurmctld + slurmd from Debian's slurm-wlm, munge with a key made here;
# everything in $SCRATCH), a 4-task array plus its dependent merge job, and a task requeued
# mid-run. The merged tables must equal a serial run's. Where the daemons cannot start, the
# test is skipped (exit 77, ctest's SKIP_RETURN_CODE), saying why; it never passes silently.
source "$(dirname "$0")/lib.sh"
SKIP=77
skip() { echo "SKIP: slurm_array: $*"; exit $SKIP; }
[ "$(id -u)" -eq 0 ] || skip "starting slurmctld and slurmd as SlurmUser=root needs root"
for tool in slurmctld slurmd sbatch squeue scontrol sinfo scancel; do
  command -v $tool >/dev/null || skip "$tool not installed (Debian: slurm-wlm; scripts/install-deps.sh)"
done
CFG=tests/data/configs/small_sweep.yaml
S=$(cd "$SCRATCH" && pwd)
mkdir -p "$S/state" "$S/spool" "$S/log"
export SLURM_CONF="$S/slurm.conf"

stop_cluster() {
  scancel --quiet --user=root 2>/dev/null || true  # only this cluster's jobs: SLURM_CONF is ours
  for pidfile in "$S/slurmd.pid" "$S/slurmctld.pid" "$S/munge/munged.pid"; do
    [ -s "$pidfile" ] || continue
    pid=$(cat "$pidfile")
    kill "$pid" 2>/dev/null || continue
    for _ in $(seq 1 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
}
trap stop_cluster EXIT

# munge with a key of its own, its socket in a folder everyone may enter (munged checks that);
# auth/none where munge is missing or refuses to start.
AUTH="AuthType=auth/none
CredType=cred/none"
if command -v munged >/dev/null && command -v mungekey >/dev/null; then
  mkdir -p "$S/munge" "$S/munge-socket" && chmod 700 "$S/munge" && chmod 755 "$S/munge-socket"
  if mungekey -c -k "$S/munge/munge.key" 2>"$S/log/mungekey.log" &&
     munged --key-file="$S/munge/munge.key" --socket="$S/munge-socket/socket" --pid-file="$S/munge/munged.pid" \
            --log-file="$S/log/munged.log" --seed-file="$S/munge/seed" 2>>"$S/log/munged.log"; then
    AUTH="AuthType=auth/munge
AuthInfo=socket=$S/munge-socket/socket
CredType=cred/munge"
  else
    echo "slurm_array: munged did not start ($(tail -n 1 "$S/log/munged.log")); using auth/none" >&2
  fi
fi
PORT=$(( 20000 + RANDOM % 20000 ))  # two ports of our own, so a system Slurm is never talked to
cat > "$SLURM_CONF" <<EOF
ClusterName=fairshape-test
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
SlurmUser=root
SlurmdUser=root
$AUTH
StateSaveLocation=$S/state
SlurmdSpoolDir=$S/spool
SlurmctldPidFile=$S/slurmctld.pid
SlurmdPidFile=$S/slurmd.pid
SlurmctldLogFile=$S/log/slurmctld.log
SlurmdLogFile=$S/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
MinJobAge=600
NodeName=localhost NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -i >"$S/log/slurmctld.start" 2>&1 || skip "slurmctld did not start: $(tail -n 3 "$S/log/slurmctld.start" "$S/log/slurmctld.log" 2>/dev/null | tr '\n' ' ')"
slurmd -N localhost >"$S/log/slurmd.start" 2>&1 || skip "slurmd did not start: $(tail -n 3 "$S/log/slurmd.start" "$S/log/slurmd.log" 2>/dev/null | tr '\n' ' ')"
for _ in $(seq 1 60); do
  [ "$(sinfo -h -o %T 2>/dev/null)" = idle ] && break
  sleep 0.5
done
[ "$(sinfo -h -o %T 2>/dev/null)" = idle ] ||
  skip "the node never became idle: $(tail -n 3 "$S/log/slurmctld.log" "$S/log/slurmd.log" 2>/dev/null | tr '\n' ' ')"

# job_state ID: the state slurmctld holds for a job (kept MinJobAge seconds after it ended).
job_state() { scontrol show job "$1" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | sort -u | tr '\n' ' '; }
# wait_for_merge DIR MERGE_ID: until the merge job ended (bounded), then it must have succeeded.
wait_for_merge() {
  for _ in $(seq 1 180); do
    case "$(job_state "$2")" in *PENDING*|*RUNNING*|*CONFIGURING*|*COMPLETING*|"") sleep 0.5 ;; *) break ;; esac
  done
  [ "$(job_state "$2")" = "COMPLETED " ] || {
    cat "$1"/slurm/logs/*.log >&2 || true
    fail "merge job $2: $(job_state "$2") (expected COMPLETED)"
  }
}
submit() {  # submit OUT ARGS...: prints the array and merge ids
  "$FS" submit $CFG --slurm --now --out "$@" > "$S/submit.out" || { cat "$S/submit.out" >&2; fail "submit --now"; }
  sed -n 's/^array job: //p' "$S/submit.out"
  sed -n 's/^merge job: //p' "$S/submit.out"
}

# 1. A 4-task array of the 16-point sweep and its merge job: the serial run's tables.
"$FS" run $CFG --out "$S/serial" 2>/dev/null
ids=$(submit "$S/array" --array-size 4 --time 5:00)
read -r ARRAY MERGE <<< "$(echo $ids)"
[ -n "$ARRAY" ] && [ -n "$MERGE" ] || fail "submit --now printed no job ids: $(cat "$S/submit.out")"
grep -q "^#SBATCH --array=0-3$" "$S/array/slurm/array.sbatch" || fail "the array script's --array"
wait_for_merge "$S/array" "$MERGE"
[ "$(job_state "$ARRAY")" = "COMPLETED " ] || fail "array job $ARRAY: $(job_state "$ARRAY")"
for i in 0 1 2 3; do [ "$(data_rows "$S/array/shards/$i/runs.csv")" -eq 4 ] || fail "shard $i ran $(data_rows "$S/array/shards/$i/runs.csv") runs, expected 4"; done
rows_equal "$S/serial/runs.csv" "$S/array/runs.csv" || fail "merged runs.csv differs from the serial run"
cmp -s "$S/serial/config.resolved.yaml" "$S/array/config.resolved.yaml" || fail "merged config.resolved.yaml"
grep -q '"shards"' "$S/array/run.json" || fail "merged run.json lists no shards"

# 2. A task requeued in the middle of its shard resumes it: runs it finished stay, the run it
# was in runs again, and the merged tables are still the serial run's.
SWEEP='sweep.solver.max_iterations=[6000, 6001, 6002]'
"$FS" run $CFG --out "$S/serial_long" --set "$SWEEP" 2>/dev/null
ids=$(submit "$S/requeue" --array-size 4 --set "$SWEEP")
read -r ARRAY MERGE <<< "$(echo $ids)"
[ -n "$MERGE" ] || fail "submit --now printed no job ids: $(cat "$S/submit.out")"
shard1="$S/requeue/shards/1/runs.csv"
for _ in $(seq 1 600); do
  [ -f "$shard1" ] && [ "$(data_rows "$shard1")" -ge 1 ] && break
  sleep 0.1
done
[ "$(data_rows "$shard1")" -lt 3 ] || fail "shard 1 finished before it could be requeued"
scontrol requeue "${ARRAY}_1" || fail "scontrol requeue ${ARRAY}_1"
# A requeued job waits for a begin time Slurm sets about two minutes ahead once the task has
# ended: release it as soon as it is pending again.
for _ in $(seq 1 300); do [ "$(job_state "${ARRAY}_1")" = "PENDING " ] && break; sleep 0.1; done
[ "$(job_state "${ARRAY}_1")" = "PENDING " ] || fail "task 1 is $(job_state "${ARRAY}_1") after its requeue, not PENDING"
scontrol update jobid="${ARRAY}_1" StartTime=now || fail "scontrol update StartTime=now"
wait_for_merge "$S/requeue" "$MERGE"
log1="$S/requeue/slurm/logs/shard-1.log"
grep -q "attempt 2" "$log1" || { cat "$log1" >&2; fail "task 1 was not started again after its requeue"; }
grep -q "already done" "$log1" || { cat "$log1" >&2; fail "the requeued task did not resume its shard"; }
rows_equal "$S/serial_long/runs.csv" "$S/requeue/runs.csv" || fail "merged runs.csv after a requeue differs"
if grep -q crashed "$S/requeue/runs.csv"; then fail "the requeue left a crashed row"; fi
requeue_note="array $ARRAY requeued mid-shard, $(grep -c attempt "$log1") attempts of task 1"

# 3. A site's sbatch options (--sbatch-arg) reach both jobs, and its set-up lines (--setup) run
# in every task and in the merge before their command, as Slurm runs them.
ids=$(submit "$S/site" --array-size 2 --sbatch-arg=--account=fairshape-test --sbatch-arg=--comment=site-options \
  --setup 'echo "site setup ran in job $SLURM_JOB_ID"' --setup 'export FAIRSHAPE_SITE_MARK=1')
read -r ARRAY MERGE <<< "$(echo $ids)"
[ -n "$MERGE" ] || fail "submit --now printed no job ids: $(cat "$S/submit.out")"
wait_for_merge "$S/site" "$MERGE"
for id in "$ARRAY" "$MERGE"; do
  scontrol show job "$id" | grep -q "Account=fairshape-test" || fail "job $id: --sbatch-arg=--account did not reach it"
  scontrol show job "$id" | grep -q "Comment=site-options" || fail "job $id: --sbatch-arg=--comment did not reach it"
done
for log in shard-0 shard-1 merge; do
  grep -q "site setup ran in job" "$S/site/slurm/logs/$log.log" || { cat "$S/site/slurm/logs/$log.log" >&2; fail "--setup did not run in $log"; }
done
rows_equal "$S/serial/runs.csv" "$S/site/runs.csv" || fail "merged runs.csv with site options differs from the serial run"
echo "slurm_array: ok ($requeue_note; site options on array $ARRAY and merge $MERGE)"
