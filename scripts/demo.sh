#!/usr/bin/env bash
# `make demo`: the default experiment on the bundled cow, then pictures of it.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/bin/fairshape
out=results/demo
mkdir -p "$out"
"$bin" run configs/demo.yaml --out "$out" --force
"$bin" render data/cow.off "$out/rest.png" --azimuth 0 --elevation 0 --width 900 --height 560
"$bin" render "$out" "$out/final.png" --array displacement_norm --azimuth 0 --elevation 0 --width 900 --height 560
echo "demo: results in $out (runs.csv, run.json, final.obj, vtk/*.vtp, rest.png, final.png)"
echo "      open $out/vtk/*.vtp in ParaView and colour by 'displacement_norm'"
