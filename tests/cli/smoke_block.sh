# The smoke: block is the file's, never a run's key; a file without one has no smoke variant.
source "$(dirname "$0")/lib.sh"
sed '/^smoke:/,$d' configs/smoke/cow_nose_pull.yaml | sed "s#data/cow.off#$PWD/data/cow.off#; s#\.\./base/output.yaml#$PWD/configs/base/output.yaml#" \
  > "$SCRATCH/no_smoke.yaml"
"$FS" run "$SCRATCH/no_smoke.yaml" --dry-run > /dev/null 2>&1 || fail "the copy without a smoke block is valid"
expect_error 2 "no smoke: block" -- "$FS" run "$SCRATCH/no_smoke.yaml" --smoke --out "$SCRATCH/none"
printf 'smoke: 3\n' >> "$SCRATCH/no_smoke.yaml"
expect_error 2 "smoke: expected a map" -- "$FS" run "$SCRATCH/no_smoke.yaml" --dry-run
# Every config under configs/ has its own cli.every_config.* test (a config added since the
# build was configured is found by the glob's CONFIGURE_DEPENDS at the next build).
configured="$(ctest --test-dir "${BUILD_DIR:?}" -N -R '^cli\.every_config\.' | grep -c 'cli.every_config.' || true)"
present="$(find configs -name '*.yaml' -not -path 'configs/base/*' | wc -l)"
[ "$configured" -eq "$present" ] || fail "$present configs under configs/, $configured cli.every_config tests: re-run cmake"
[ "$present" -ge 25 ] || fail "only $present configs found"
echo "smoke_block: ok ($present configs, each its own test)"
