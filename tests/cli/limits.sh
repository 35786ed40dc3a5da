# The documented limits (README, "Limits") at the limit itself: accepted there, refused just
# above (hostile_input.sh has the refusals of the larger ones). The heavy ones — a mesh file of
# 2 GiB, a sheet of the largest base grid — are in limits_slow.sh.
source "$(dirname "$0")/lib.sh"
SMOKE="$PWD/configs/smoke/cow_nose_pull.yaml"

# A config file of exactly 16 MiB (the config padded with a comment) is read; one byte more is not.
$PY - "$SMOKE" "$SCRATCH/at_limit.yaml" <<'PYEOF'
import sys
text = f"defaults: [{sys.argv[1]}]\nname: at_limit\n# "
open(sys.argv[2], "w").write(text + "x" * (16 * 2**20 - len(text) - 1) + "\n")
PYEOF
[ "$(stat -c %s "$SCRATCH/at_limit.yaml")" -eq 16777216 ] || fail "the padded config is not 16 MiB"
"$FS" run "$SCRATCH/at_limit.yaml" --dry-run > /dev/null 2>"$SCRATCH/err.txt" || { cat "$SCRATCH/err.txt"; fail "a 16 MiB config"; }
printf 'x' >> "$SCRATCH/at_limit.yaml"
expect_error 2 "above the input limit of 16 MiB" -- "$FS" run "$SCRATCH/at_limit.yaml" --dry-run

# `defaults:` nested 16 deep is loaded; 17 deep is refused.
chain() {  # file0 -> ... -> file<n> -> the smoke config -> base/output.yaml: n + 2 includes deep
  local depth=$1 d
  for d in $(seq 0 $((depth - 1))); do printf 'defaults: [chain%s_%s.yaml]\nname: chain\n' "$depth" $((d + 1)) > "$SCRATCH/chain${depth}_$d.yaml"; done
  printf 'defaults: [%s]\n' "$SMOKE" > "$SCRATCH/chain${depth}_$depth.yaml"
  echo "$SCRATCH/chain${depth}_0.yaml"
}
"$FS" run "$(chain 14)" --dry-run > /dev/null 2>"$SCRATCH/err.txt" || { cat "$SCRATCH/err.txt"; fail "defaults 16 deep"; }
expect_error 2 "nest more than 16 deep" -- "$FS" run "$(chain 15)" --dry-run

# B-spline sheets: at most 2^18 base spans (limits_slow.sh solves one of 512 x 512).
cat > "$SCRATCH/sheet_over.yaml" <<'YAML'
name: sheet_over
sheets: [{name: sheet, spans: [513, 512], size: [1, 1]}]
energy: {alpha: 0.01, beta: 1}
constraints: [{type: point, uv: [0.5, 0.5], by: [0, 0, 0.1]}]
YAML
expect_error 2 "at most 262144" -- "$FS" run "$SCRATCH/sheet_over.yaml" --dry-run

# A sweep of 10^6 points: one shard of a thousand is validated and listed at once, with the
# whole sweep's size (the full dry run is timed in experiments/bench/sweep_benchmark.cpp).
$PY - "$SMOKE" "$SCRATCH/million.yaml" <<'PYEOF'
import sys
seeds = ", ".join(str(i) for i in range(1000))
iters = ", ".join(str(100 + i) for i in range(1000))
open(sys.argv[2], "w").write(f"""defaults: [{sys.argv[1]}]
name: million
solver: {{type: conjugate_gradient}}
sweep:
  seed: [{seeds}]
  solver.max_iterations: [{iters}]
""")
PYEOF
start=$(date +%s)
timeout 120 "$FS" run "$SCRATCH/million.yaml" --dry-run --shard 0/1000 > "$SCRATCH/million.txt" 2>"$SCRATCH/err.txt" ||
  { cat "$SCRATCH/err.txt"; fail "a 10^6-point sweep's shard"; }
head -1 "$SCRATCH/million.txt" | grep -q "^1000 of 1000000 point(s)" || fail "shard 0/1000 of 10^6: $(head -1 "$SCRATCH/million.txt")"
echo "limits: 10^6-point shard validated in $(( $(date +%s) - start )) s"
echo "limits: ok"
