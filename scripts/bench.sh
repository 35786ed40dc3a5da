#!/usr/bin/env bash
# `make bench`: every Google Benchmark program, JSON into results/bench/<timestamp>/ (medians of 5 repetitions).
set -euo pipefail
cd "$(dirname "$0")/.."
out="results/bench/$(date -u +%Y%m%d-%H%M%S)"
mkdir -p "$out"
for b in build/bin/*_benchmark; do
  name=$(basename "$b")
  echo "== $name"
  "$b" --benchmark_repetitions=5 --benchmark_report_aggregates_only=true \
       --benchmark_out="$out/$name.json" --benchmark_out_format=json
done
echo "bench: JSON in $out"
