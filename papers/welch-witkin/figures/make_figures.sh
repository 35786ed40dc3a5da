#!/usr/bin/env bash
# Figures 1-3 of Welch & Witkin and the constrained-solver sweep: runs each config under
# configs/welch-witkin/, renders it (scripts/plot_sheets.py) into papers/welch-witkin/figures/
# and keeps its CSVs in papers/welch-witkin/data/.
#   bash papers/welch-witkin/figures/make_figures.sh      (after `make build`)
set -euo pipefail
cd "$(dirname "$0")/../../.."
mkdir -p papers/welch-witkin/data
keep() { for f in runs steps cells; do [ -f "$1/$f.csv" ] && cp "$1/$f.csv" "papers/welch-witkin/data/${2}_$f.csv"; done; cp "$1/run.json" "papers/welch-witkin/data/${2}_run.json"; }
out=results/figures/ww
build/bin/fairshape run configs/welch-witkin/fig1.yaml --out $out-fig1 --force
/usr/bin/python3 scripts/plot_sheets.py steps $out-fig1 papers/welch-witkin/figures/fig1.png \
  --title "Figure 1: push-pins and a promoted surface curve, edited; a second control curve" \
  --labels "pins + surface curve" "space curve pulled up" "second curve added" "second curve pushed down"
keep $out-fig1 fig1
build/bin/fairshape run configs/welch-witkin/fig2.yaml --out $out-fig2 --force
/usr/bin/python3 scripts/plot_sheets.py steps $out-fig2 papers/welch-witkin/figures/fig2.png \
  --title "Figure 2: two sheets joined along one space curve, which is then reshaped" \
  --labels "joined" "shared curve reshaped"
keep $out-fig2 fig2
build/bin/fairshape run configs/welch-witkin/fig2_free.yaml --out $out-fig2-free --force
/usr/bin/python3 scripts/plot_sheets.py steps $out-fig2-free papers/welch-witkin/figures/fig2_free.png \
  --title "Figure 2 with a free joint: two sheets and a variational curve solved together; the curve's middle dragged" \
  --labels "joined (curve ends and middle held)" "curve's middle dragged"
keep $out-fig2-free fig2_free
build/bin/fairshape run configs/welch-witkin/fig3.yaml --out $out-fig3 --force
/usr/bin/python3 scripts/plot_sheets.py cells $out-fig3 papers/welch-witkin/figures/fig3.png \
  --title "Figure 3: a 4 x 4-span bicubic sheet, four points and a curve; automatic refinement by constraint error"
keep $out-fig3 fig3
build/bin/fairshape run configs/welch-witkin/primitives.yaml --out $out-primitives --force
/usr/bin/python3 scripts/plot_sheets.py steps $out-primitives papers/welch-witkin/figures/primitives.png \
  --title "Section 4.2's offsets and regions and section 5's ribbon: a terrace, a lifted region, an offset pair" \
  --labels "ribbon: curve lifted, slope across it kept flat" "region held, the curve raised beside it" "offset: a point 0.25 above its partner"
keep $out-primitives primitives
build/bin/fairshape run configs/welch-witkin/metrics.yaml --out $out-metrics --force
/usr/bin/python3 scripts/plot_sheets.py runs $out-metrics papers/welch-witkin/figures/metrics.png \
  --title "Section 4.1: one point pulled up; thin plate (eq. 6) vs control-point displacement, plain and refined sheet" \
  --label "{energy_metric}, {dofs} unknowns" --profile-v 1 --size-v 2 --spans-v 8 --per-span 8
cp $out-metrics/runs.csv papers/welch-witkin/data/metrics_runs.csv
# qr_penalty without refinement steps does not meet the constraints: said in its row, exit 3.
build/bin/fairshape run configs/welch-witkin/solvers.yaml --out $out-solvers --force || [ $? -eq 3 ]
cp $out-solvers/runs.csv papers/welch-witkin/data/solvers_runs.csv
build/bin/fairshape run configs/welch-witkin/resolution.yaml --out $out-resolution --force
/usr/bin/python3 scripts/plot_sheets.py convergence $out-resolution papers/welch-witkin/figures/resolution.png \
  --title "Figure 1's design at 8 to 64 base spans (design units): kkt, range_space and qr_penalty"
cp $out-resolution/runs.csv papers/welch-witkin/data/resolution_runs.csv
# The README's marked blocks from data/ (the drag-step benchmark and memory sweep data are
# written by sheet_step_benchmark --benchmark_out and figures/memory_sweep.sh).
/usr/bin/python3 papers/welch-witkin/figures/readme_numbers.py
