#!/usr/bin/env bash
# Constraints at surface points (issue 22, part 3): runs configs/boier-martin/limit_points.yaml
# (a handle at (face, u, v), a normal at a limit point, a curve as limit points; remeshed cow,
# edited on the finest level, exact solve) and renders its three runs side by side into
# papers/boier-martin/figures/limit_points.png.
#   bash papers/boier-martin/figures/limit_points.sh   (after `make build`)
set -euo pipefail
cd "$(dirname "$0")/../../.."
out=results/limit_points
build/bin/fairshape run configs/boier-martin/limit_points.yaml --force --out "$out"
ids=$(/usr/bin/python3 -c "
import csv, sys
print(' '.join(sys.argv[1] + '@' + r['run_id'] for r in csv.DictReader(open(sys.argv[1] + '/runs.csv'))))" "$out")
# shellcheck disable=SC2086
xvfb-run -a build/bin/fairshape render $ids papers/boier-martin/figures/limit_points.png \
  --label "handle at (face, u, v)" "normal at a limit point" "curve as limit points" \
  --array displacement_norm --colour-label "displacement" --view front --zoom 1.5 --width 800 --height 560
