#!/usr/bin/env bash
# Runs the libFuzzer targets on their committed corpora (tests/fuzz/<name>/), as CI does:
# `bash scripts/fuzz.sh [runs per target]` after `make sanitize`. A fixed seed and a fixed number
# of runs make CI's fuzzing deterministic (no finding appears on one machine and not on the
# next); run with more runs, or libFuzzer's -max_total_time, to search further. New inputs go
# to a scratch corpus; a finding fails the run and its input is kept in build-sanitize/findings/ —
# add it to tests/fuzz/<name>/ with the fix, so it is a regression input from then on.
# The VTK reader's target runs fewer times: every input goes through a file and VTK's parser.
set -euo pipefail
cd "$(dirname "$0")/.."
runs="${1:-100000}"
findings=build-sanitize/findings
mkdir -p "$findings"
status=0
for pair in obj:fuzz_read_obj:1 off:fuzz_read_off:1 ply:fuzz_read_ply:1 config:fuzz_config:1 sheet:fuzz_read_sheet:1 vtp:fuzz_read_vtp:5; do
  IFS=: read -r corpus target slower <<< "$pair"
  target_runs=$((runs / slower))
  work="$(mktemp -d)"
  echo "fuzz: $target, $target_runs runs on tests/fuzz/$corpus" >&2
  if ! ASAN_OPTIONS=detect_leaks=0 "build-sanitize/bin/$target" -runs="$target_runs" -seed=1 -rss_limit_mb=2048 -timeout=10 \
       -artifact_prefix="$findings/$target-" -print_final_stats=0 "$work" "tests/fuzz/$corpus" > "$work.log" 2>&1; then
    tail -40 "$work.log" >&2
    echo "fuzz: $target found an input that fails (kept in $findings/)" >&2
    status=1
  fi
  rm -rf "$work" "$work.log"
done
exit $status
