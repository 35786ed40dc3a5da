# Every experiment under configs/ still runs: each validates in full (every sweep point, with
# --dry-run), and its CI-sized variant (`--smoke`: the file's smoke: block of overrides) runs
# to the end with every run a success. A config without a smoke: block fails here.
source "$(dirname "$0")/lib.sh"

count=0
while IFS= read -r cfg; do
  name="$(echo "${cfg#configs/}" | tr '/' '_')"
  "$FS" run "$cfg" --dry-run --out "$SCRATCH/dry_$name" > "$SCRATCH/dry_$name.txt" 2>"$SCRATCH/err.txt" ||
    { cat "$SCRATCH/err.txt" >&2; fail "$cfg: --dry-run of the full experiment"; }
  "$FS" run "$cfg" --smoke --out "$SCRATCH/$name" > /dev/null 2>"$SCRATCH/err.txt" ||
    { cat "$SCRATCH/err.txt" >&2; fail "$cfg: its smoke variant did not run clean"; }
  [ "$(data_rows "$SCRATCH/$name/runs.csv")" -ge 1 ] || fail "$cfg: the smoke variant wrote no row"
  $PY - "$SCRATCH/$name/runs.csv" "$cfg" <<'PYEOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
bad = [r["termination"] for r in rows if r["termination"] not in ("converged", "energy_stalled", "schedule_completed")]
assert not bad, f"{sys.argv[2]}: terminations {bad}"
PYEOF
  count=$((count + 1))
done < <(find configs -name '*.yaml' -not -path 'configs/base/*' | sort)
[ "$count" -ge 25 ] || fail "only $count configs found"

# The smoke block is the file's, never a run's key; a file without one has no smoke variant.
sed '/^smoke:/,$d' configs/smoke/cow_nose_pull.yaml | sed "s#data/cow.off#$PWD/data/cow.off#; s#\.\./base/output.yaml#$PWD/configs/base/output.yaml#" \
  > "$SCRATCH/no_smoke.yaml"
"$FS" run "$SCRATCH/no_smoke.yaml" --dry-run > /dev/null 2>&1 || fail "the copy without a smoke block is valid"
expect_error 2 "no smoke: block" -- "$FS" run "$SCRATCH/no_smoke.yaml" --smoke --out "$SCRATCH/none"
printf 'smoke: 3\n' >> "$SCRATCH/no_smoke.yaml"
expect_error 2 "smoke: expected a map" -- "$FS" run "$SCRATCH/no_smoke.yaml" --dry-run
echo "every_config: ok ($count configs)"
