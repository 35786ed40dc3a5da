# Helpers for the command-line tests. $1 of each test script is the fairshape binary.
set -euo pipefail
FS="$1"
# Each run gets a folder of its own under the test's ($SCRATCH from ctest): the script of an
# interrupted run, left running, then never shares files with the next run's. Removed when the
# script succeeds, kept (and named) when it fails. A script with an EXIT trap of its own keeps it.
if [ -n "${SCRATCH:-}" ]; then mkdir -p "$SCRATCH" && SCRATCH="$(mktemp -d "$SCRATCH/r.XXXXXX")"; else SCRATCH="$(mktemp -d)"; fi
trap 'rc=$?; if [ "$rc" -eq 0 ]; then rm -rf "$SCRATCH"; else echo "scratch kept: $SCRATCH" >&2; fi' EXIT
PY=/usr/bin/python3

fail() { echo "FAIL: $*" >&2; exit 1; }

# expect_error CODE PATTERN -- command...: the command must exit with CODE and print PATTERN on stderr.
expect_error() {
  local code="$1" pattern="$2"; shift 3
  local err="$SCRATCH/stderr.txt" rc=0
  "$@" 2>"$err" >/dev/null || rc=$?
  [ "$rc" -eq "$code" ] || { cat "$err" >&2; fail "exit $rc, expected $code: $*"; }
  grep -q -- "$pattern" "$err" || { cat "$err" >&2; fail "stderr lacks '$pattern': $*"; }
}

# rows_equal A B: the same runs with the same deterministic results (timings left out).
rows_equal() {
  $PY - "$1" "$2" <<'PYEOF'
import csv, sys
TIMING = {"assemble_s", "analyze_s", "solve_s", "solve_min_s", "time_s", "peak_rss_mb", "solve_extra_mb"}
def load(p):
    with open(p, newline="") as f:
        return {r["run_id"]: {k: v for k, v in r.items() if k not in TIMING} for r in csv.DictReader(f)}
a, b = load(sys.argv[1]), load(sys.argv[2])
if a != b:
    print(f"differ: {len(a)} vs {len(b)} rows; only in first {sorted(set(a) - set(b))[:5]}, "
          f"only in second {sorted(set(b) - set(a))[:5]}", file=sys.stderr)
    for k in set(a) & set(b):
        if a[k] != b[k]:
            print("row", k, {c: (a[k][c], b[k].get(c)) for c in a[k] if a[k][c] != b[k].get(c)}, file=sys.stderr)
            break
    sys.exit(1)
PYEOF
}

data_rows() { echo $(( $(wc -l < "$1") - 1 )); }
