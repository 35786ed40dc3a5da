#!/usr/bin/env bash
# Figures 1, 3 and 4 of Sauvage, Hahmann and Bonneau: runs each config under configs/sauvage/,
# plots it (scripts/plot_curves.py) into papers/sauvage/figures/figN.png and keeps its CSVs in
# papers/sauvage/data/.
#   bash papers/sauvage/figures/make_figures.sh [fig1 fig3 fig4]   (after `make build`)
set -euo pipefail
cd "$(dirname "$0")/../../.."
figures=("$@")
[ ${#figures[@]} -gt 0 ] || figures=(fig1 fig3 fig4)
for f in "${figures[@]}"; do
  out=results/figures/sauvage-$f
  build/bin/fairshape run "configs/sauvage/$f.yaml" --out "$out" --force
  /usr/bin/python3 scripts/plot_curves.py "$f" "$out" "papers/sauvage/figures/$f.png"
  cp "$out/runs.csv" "papers/sauvage/data/${f}_runs.csv"
  cp "$out/steps.csv" "papers/sauvage/data/${f}_steps.csv"
  cp "$out/run.json" "papers/sauvage/data/${f}_run.json"
done
