#!/usr/bin/env bash
# Figures 1, 3 and 4 of Sauvage, Hahmann and Bonneau and a 3-D helix: runs each config under configs/sauvage/,
# plots it (scripts/plot_curves.py) into papers/sauvage/figures/figN.png and keeps its CSVs in
# papers/sauvage/data/. `wrinkle_scale`: the w × e × β sweep of §4's claims, plotted with
# scripts/plot.py (wavelength and amplitude of C_F − C_A against w, one line per β, e = 0 and 1).
# `bench`: the benchmarks behind scaling.png, time_to_accuracy.png and the README's Performance and
# "Second-order checks cheaper than the solve" blocks (medians of 5; about 15 minutes on 2 cores),
# then figures/readme_numbers.py. Not in the default list.
#   bash papers/sauvage/figures/make_figures.sh [fig1 fig3 fig4 helix wrinkle_scale bench]   (after `make build`)
set -euo pipefail
cd "$(dirname "$0")/../../.."
figures=("$@")
[ ${#figures[@]} -gt 0 ] || figures=(fig1 fig3 fig4 helix wrinkle_scale)
for f in "${figures[@]}"; do
  if [ "$f" = bench ]; then
    bench=papers/sauvage/data/bench
    reps=(--benchmark_repetitions=5 --benchmark_report_aggregates_only=true --benchmark_out_format=json)
    build/bin/curve_benchmark --benchmark_filter='BM_Edit129|BM_EditScaling' "${reps[@]}" --benchmark_out=$bench/curve_benchmark.json
    build/bin/curve_benchmark --benchmark_filter='BM_TimeToAccuracy|BM_SecondOrderCheck' "${reps[@]}" --benchmark_out=$bench/time_to_accuracy.json
    build/bin/curve_drag_benchmark "${reps[@]}" --benchmark_out=$bench/curve_drag_benchmark.json
    /usr/bin/python3 scripts/plot_curve_bench.py $bench/curve_benchmark.json papers/sauvage/figures
    /usr/bin/python3 scripts/plot_curve_bench.py $bench/time_to_accuracy.json papers/sauvage/figures
    /usr/bin/python3 papers/sauvage/figures/readme_numbers.py
    continue
  fi
  out=results/figures/sauvage-$f
  # Exit 3: a run of the sweep ended short of its tolerance (max_iterations, not_a_minimum); it
  # is in runs.csv with its termination, and the figure shows it.
  build/bin/fairshape run "configs/sauvage/$f.yaml" --out "$out" --force || [ $? -eq 3 ]
  if [ "$f" = wrinkle_scale ]; then
    for e in 0 1; do
      /usr/bin/python3 scripts/plot.py "$out/runs.csv" --x edits.0.wrinkle_level --y wrinkle_wavelength_segments \
        --hue optimization.beta --filter edits.0.level=$e --logy --xlabel "wrinkle level w (explicit length step)" \
        --ylabel "dominant wavelength of C_F − C_A (segments)" \
        --title "Wrinkle scale against w and β (edit level e = $e, 129 points)" -o "papers/sauvage/figures/wrinkle_wavelength_e$e.png"
      /usr/bin/python3 scripts/plot.py "$out/runs.csv" --x edits.0.wrinkle_level --y wrinkle_amplitude \
        --hue optimization.beta --filter edits.0.level=$e --logy --xlabel "wrinkle level w (explicit length step)" \
        --ylabel "RMS of C_F − C_A" \
        --title "Wrinkle amplitude against w and β (edit level e = $e, 129 points)" -o "papers/sauvage/figures/wrinkle_amplitude_e$e.png"
    done
    cp "$out/runs.csv" "papers/sauvage/data/${f}_runs.csv"; cp "$out/run.json" "papers/sauvage/data/${f}_run.json"
    continue
  fi
  /usr/bin/python3 scripts/plot_curves.py "$f" "$out" "papers/sauvage/figures/$f.png"
  cp "$out/runs.csv" "papers/sauvage/data/${f}_runs.csv"
  cp "$out/steps.csv" "papers/sauvage/data/${f}_steps.csv"
  cp "$out/run.json" "papers/sauvage/data/${f}_run.json"
done
