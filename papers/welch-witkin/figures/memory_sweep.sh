#!/usr/bin/env bash
# Peak memory against refinement depth (README, "Memory of deep refinement"): runs
# configs/welch-witkin/memory.yaml once per max_level, each in its own process, and appends
# (build, max_level, dofs, peak RSS, wall time) to data/memory_rss.csv. The peak is
# /usr/bin/time's maximum resident set, which any build reports (older ones have no
# peak_rss_mb column), so two builds are compared by the same measure:
#   bash papers/welch-witkin/figures/memory_sweep.sh BINARY LABEL [LEVELS...]   (default 3 4 5 6 7 8)
set -euo pipefail
cd "$(dirname "$0")/../../.."
bin=$1 label=$2
shift 2
levels=${*:-3 4 5 6 7 8}
csv=papers/welch-witkin/data/memory_rss.csv
[ -f "$csv" ] || echo "build,max_level,dofs,peak_rss_mb,time_s" > "$csv"
for level in $levels; do
  tmp=$(mktemp -d)
  # The runs end constraints_unmet (the tolerance is out of reach at every depth), as the
  # config's `expect:` says; an older build without `expect` for sheet runs exits 3.
  /usr/bin/time -f "%M %e" -o "$tmp/time" "$bin" run configs/welch-witkin/memory.yaml \
    --filter "refinement.max_level=$level" --out "$tmp/run" --force > /dev/null 2>&1 || [ $? -eq 3 ]
  read -r kb seconds < <(tail -n 1 "$tmp/time")
  dofs=$(/usr/bin/python3 -c "import csv, sys; print(next(csv.DictReader(open(sys.argv[1])))['dofs'])" "$tmp/run/runs.csv")
  echo "$label,$level,$dofs,$(( kb / 1024 )),$seconds" >> "$csv"
  rm -rf "$tmp"
done
