# `fairshape submit` without a scheduler at hand: the scripts it writes (into --out only), its
# refusals (exit 2, naming the option and the valid choices, nothing written); and the shards
# it relies on: `--shard i/n` run ids partition the serial run's, and a shard builds and
# validates only its own points (a bad point elsewhere does not stop it).
source "$(dirname "$0")/lib.sh"
CFG=tests/data/configs/small_sweep.yaml
OUT="$SCRATCH/sub"
"$FS" submit $CFG --slurm --array-size 4 --partition short --time 1-00:30 --cpus-per-task 2 --mem 2G \
  --set solver.tolerance=0 --out "$OUT" > "$SCRATCH/submit.out"
A="$OUT/slurm/array.sbatch"; M="$OUT/slurm/merge.sbatch"
for line in "--array=0-3" "--requeue" "--partition=short" "--time=1-00:30" "--cpus-per-task=2" "--mem=2G" \
            "--output=$OUT/slurm/logs/shard-%a.log" "--chdir=$PWD"; do
  grep -qx -- "#SBATCH $line" "$A" || fail "array.sbatch lacks '#SBATCH $line'"
done
grep -q -- "--shard \"\$shard/4\" --resume --out '$OUT/shards/'\"\$shard\" '--set' 'solver.tolerance=0'" "$A" ||
  fail "array.sbatch's run line"
grep -qx -- "#SBATCH --kill-on-invalid-dep=yes" "$M" || fail "merge.sbatch lacks --kill-on-invalid-dep"
grep -q -- "merge '$OUT'" "$M" || fail "merge.sbatch's merge line"
grep -q "sbatch --dependency=afterok" "$A" || fail "the scripts do not say how to submit them by hand"
grep -q "submit with: bash $OUT/slurm/submit.sh" "$SCRATCH/submit.out" || fail "submit did not say how to submit"
bash -n "$A" && bash -n "$M" && bash -n "$OUT/slurm/submit.sh" || fail "a written script is not valid bash"
[ "$(cd "$OUT" && find . -type f | sort | tr '\n' ' ')" = "./slurm/array.sbatch ./slurm/merge.sbatch ./slurm/submit.sh " ] ||
  fail "submit wrote other files: $(cd "$OUT" && find . -type f)"
# Run by hand as Slurm would (task ids 0..3), then the merge script: the serial run's rows.
"$FS" run $CFG --set solver.tolerance=0 --out "$SCRATCH/serial" 2>/dev/null
for i in 0 1 2 3; do SLURM_ARRAY_TASK_ID=$i bash "$A" >/dev/null 2>&1 || fail "task $i"; done
bash "$M" >/dev/null 2>&1 || fail "merge script"
rows_equal "$SCRATCH/serial/runs.csv" "$OUT/runs.csv" || fail "the scripts' merged rows differ from the serial run"
# A task run again (a requeue) finds its shard done and changes nothing.
SLURM_ARRAY_TASK_ID=2 SLURM_RESTART_COUNT=1 bash "$A" > "$SCRATCH/again.log" 2>&1 || fail "task 2 again"
grep -q "0 to do here (4 already done)" "$SCRATCH/again.log" || { cat "$SCRATCH/again.log"; fail "a re-run task did not resume"; }

# A site's own sbatch options and set-up lines: --sbatch-arg lines in every job's #SBATCH block,
# --setup lines in order after it and before the job's command.
"$FS" submit $CFG --slurm --array-size 2 --sbatch-arg=--account=proj1 --sbatch-arg=--gres=gpu:1 \
  --setup 'module load gcc/12' --setup 'export OMP_NUM_THREADS=2' --out "$SCRATCH/site" > /dev/null || fail "--sbatch-arg, --setup"
for script in "$SCRATCH/site/slurm/array.sbatch" "$SCRATCH/site/slurm/merge.sbatch"; do
  $PY - "$script" <<'PYEOF' || fail "$script: the site lines"
import sys
lines = open(sys.argv[1]).read().splitlines()
at = lambda text: lines.index(text)
last_sbatch = max(i for i, l in enumerate(lines) if l.startswith("#SBATCH"))
command = min(i for i, l in enumerate(lines) if not l.startswith("#") and (" run " in l or " merge " in l))
assert "#SBATCH --account=proj1" in lines and "#SBATCH --gres=gpu:1" in lines, lines
assert last_sbatch < at("module load gcc/12") < at("export OMP_NUM_THREADS=2") < command, lines
PYEOF
  bash -n "$script" || fail "$script is not valid bash"
done

# Refusals: exit 2, the option and the valid choices named, nothing written.
expect_error 2 "valid: --slurm" -- "$FS" submit $CFG --out "$SCRATCH/r1"
expect_error 2 "valid: 1 to 16" -- "$FS" submit $CFG --slurm --array-size 0 --out "$SCRATCH/r1"
expect_error 2 "valid: 1 to 16" -- "$FS" submit $CFG --slurm --array-size 17 --out "$SCRATCH/r1"
expect_error 2 "valid: 1 to 16" -- "$FS" submit $CFG --slurm --array-size 4x --out "$SCRATCH/r1"
expect_error 2 "valid: M, M:S, H:M:S" -- "$FS" submit $CFG --slurm --time 2h --out "$SCRATCH/r1"
expect_error 2 "valid: M, M:S, H:M:S" -- "$FS" submit $CFG --slurm --time 1:2:3:4 --out "$SCRATCH/r1"
expect_error 2 "valid: an integer in megabytes" -- "$FS" submit $CFG --slurm --mem 2GB --out "$SCRATCH/r1"
expect_error 2 "--partition 'a b'" -- "$FS" submit $CFG --slurm --partition 'a b' --out "$SCRATCH/r1"
expect_error 2 "cpus-per-task" -- "$FS" submit $CFG --slurm --cpus-per-task 0 --out "$SCRATCH/r1"
expect_error 2 "valid options: .*--array-size" -- "$FS" submit $CFG --slurm --array 4 --out "$SCRATCH/r1"
expect_error 2 "sbatch is not on PATH" -- env PATH=/nonexistent "$FS" submit $CFG --slurm --now --out "$SCRATCH/r1"
expect_error 2 "holds files already" -- "$FS" submit $CFG --slurm --out "$OUT"
expect_error 2 "spaces, quotes" -- "$FS" submit $CFG --slurm --out "$SCRATCH/with space"
expect_error 2 "solver.nonsense" -- "$FS" submit $CFG --slurm --set solver.nonsense=1 --out "$SCRATCH/r1"
expect_error 2 "--sbatch-arg 'account=proj1': not an sbatch option (valid: --name or --name=value" -- \
  "$FS" submit $CFG --slurm --sbatch-arg=account=proj1 --out "$SCRATCH/r1"
expect_error 2 "one word without spaces" -- "$FS" submit $CFG --slurm "--sbatch-arg=--comment=two words" --out "$SCRATCH/r1"
expect_error 2 "--array is set by --array-size" -- "$FS" submit $CFG --slurm --sbatch-arg=--array=0-3 --out "$SCRATCH/r1"
expect_error 2 "--time is set by --time" -- "$FS" submit $CFG --slurm --sbatch-arg=--time=5 --out "$SCRATCH/r1"
expect_error 2 "one line per --setup" -- "$FS" submit $CFG --slurm --setup $'module load a\nrm -rf x' --out "$SCRATCH/r1"
expect_error 2 "--setup '': an empty line" -- "$FS" submit $CFG --slurm --setup '' --out "$SCRATCH/r1"
[ ! -e "$SCRATCH/r1" ] && [ ! -e "$SCRATCH/with space/slurm" ] || fail "a refused submit wrote files"

# Shards partition the serial run's ids, for several n (one shard per point included).
"$FS" run $CFG --dry-run | awk 'NR > 1 {print $2}' | sort > "$SCRATCH/ids_serial"
[ "$(wc -l < "$SCRATCH/ids_serial")" -eq 16 ] || fail "the serial dry run lists $(wc -l < "$SCRATCH/ids_serial") ids"
for n in 1 3 5 16; do
  : > "$SCRATCH/ids_shards"
  for ((i = 0; i < n; ++i)); do "$FS" run $CFG --dry-run --shard $i/$n | awk 'NR > 1 {print $2}' >> "$SCRATCH/ids_shards"; done
  sort "$SCRATCH/ids_shards" | cmp -s - "$SCRATCH/ids_serial" || fail "the $n shards' run ids are not a partition of the serial run's"
done
# A point whose mesh does not exist (point 5 of 8) stops its own shard only: the shard rule is
# that each shard validates (and reads the inputs of) its own points.
expect_error 2 "missing_mesh" -- "$FS" run $CFG --dry-run --set 'sweep.input.mesh=[data/cow.off, data/missing_mesh.off]' --shard 1/2
"$FS" run $CFG --dry-run --set 'sweep.input.mesh=[data/cow.off, data/missing_mesh.off]' --shard 0/2 > "$SCRATCH/shard0.txt" ||
  fail "a bad point in another shard stopped shard 0"
grep -q "^16 of 32 point" "$SCRATCH/shard0.txt" || fail "shard 0's dry run: $(head -1 "$SCRATCH/shard0.txt")"
echo "submit_shards: ok"
