#!/usr/bin/env bash
# Figures 11 (on the patch and on the helmet), 14, 15, 16 and 17 of Khodakovsky & Schröder and the sparse adaptive helmet: runs each config under
# configs/khodakovsky-schroder/, renders it (scripts/panels.py, VTK offscreen, coloured by the
# signed normal displacement) into papers/khodakovsky-schroder/figures/ and keeps its runs.csv in
# papers/khodakovsky-schroder/data/.
#   bash papers/khodakovsky-schroder/figures/make_figures.sh      (after `make build`)
set -euo pipefail
cd "$(dirname "$0")/../../.."
figs=papers/khodakovsky-schroder/figures
data=papers/khodakovsky-schroder/data
out=results/figures/ks
# The patch is z-up; colour: the displacement along the surface normal (ridges warm, grooves cool).
patch_view=(--up z --view front --elevation 40 --azimuth 10 --zoom 1.35 --width 900 --height 700 --component normal
            --colour-label "normal displacement")
# Exit 3 (constraints_unmet: a feature outside its profile tolerance) still finished the run: its
# miss is in runs.csv and features.csv, which are kept with the figure.
run() { build/bin/fairshape run "configs/khodakovsky-schroder/$1.yaml" --out "$out-$1" --force || [ $? -eq 3 ]
        cp "$out-$1/features.csv" "$data/$1_features.csv"; cp "$out-$1/runs.csv" "$data/$1_runs.csv"; cp "$out-$1/run.json" "$data/$1_run.json"; }
run fig11
/usr/bin/python3 scripts/panels.py --allow-unmet $out-fig11 $figs/fig11.png --rest data/ks_patch.off \
  --title "Figure 11/16: three overlapping feature lines drawn on level 2 (two ridges, one groove), level 4 shown" \
  --label "{vertices_moved:.0f} vertices moved, max {max_displacement:.3f}" --render "${patch_view[@]}"
build/bin/fairshape render "$out-fig11/adaptive/$(tail -1 $out-fig11/runs.csv | cut -d, -f1).obj" $figs/fig11_adaptive.png \
  --edges --flat --up z --view top --zoom 1.3 --width 900 --height 700 --title "Figure 11: the adaptive mesh"
# Figure 11 on the helmet, the paper's subject: seen from above the crown, curves drawn, the
# features' neighbourhoods outlined, signed colouring (ridges warm, grooves cool).
run fig11_helmet
/usr/bin/python3 scripts/panels.py --allow-unmet $out-fig11_helmet $figs/fig11_helmet.png --rest data/helmet.off \
  --title "Figure 11 on the helmet: three overlapping feature lines drawn on level 2 (two ridges, one groove), level 4 shown" \
  --label "{vertices_moved:.0f} vertices moved, max {max_displacement:.4f}" \
  --render --view top --up z --focus 0.04 0.0 0.33 --radius 0.2 --width 900 --height 700 --component normal \
  --colour-label "normal displacement"
run fig16
/usr/bin/python3 scripts/panels.py --allow-unmet $out-fig16 $figs/fig16.png --columns 3 \
  --title "Figure 16: one parameter at a time (radius, crease, groove, left/right ratio, end height ratio)" \
  --label "r {feature_defaults_radius}, h {feature_defaults_height}, crease {feature_defaults_crease}, L/R {feature_defaults_left_right_ratio}, end {feature_defaults_end_height_ratio}" \
  --render "${patch_view[@]}"
run fig14
/usr/bin/python3 scripts/panels.py --allow-unmet $out-fig14 $figs/fig14.png \
  --title "Figure 14: a wide ridge drawn on level 1, two fine grooves on level 3 that follow it" \
  --label "{features:.0f} features on levels 1 and 3" --render "${patch_view[@]}"
run fig15
/usr/bin/python3 scripts/panels.py --allow-unmet $out-fig15 $figs/fig15.png \
  --title "Figure 15: a detail-preserving level-0 edit carries the features; a groove drawn after it sits on the edited surface" \
  --label "handle offset {edit_constraints_2_offset}, edit {edit_s:.2f} s" --render "${patch_view[@]}"
run fig17
# The helmet is z-up with its face opening towards −x: seen from behind its left side.
/usr/bin/python3 scripts/panels.py --allow-unmet $out-fig17 $figs/fig17.png --rest data/helmet.off \
  --title "Figure 17: six placed features on level 1 of the helmet (sections, geodesics, a file), level 3 shown" \
  --label "{features:.0f} features, {segments:.0f} segments, {vertices_moved:.0f} vertices moved, max {max_displacement:.4f}" \
  --render --view front --up z --elevation 20 --azimuth 35 --zoom 1.3 --width 900 --height 700 --component normal \
  --colour-label "normal displacement"
# Truly adaptive evaluation (issue 24 part 3): the helmet's groove on level 4 evaluated on a sparse
# hierarchy; the adaptive mesh with its edges, whole and around the groove (the curve drawn).
run adaptive_helmet
sparse="$out-adaptive_helmet/adaptive/$(tail -1 $out-adaptive_helmet/runs.csv | cut -d, -f1).obj"
groove=$(ls "$out-adaptive_helmet"/curves/*_groove.obj)
build/bin/fairshape render "$sparse" $figs/adaptive_helmet.png --edges --flat --view front --width 900 --height 700 \
  --overlay "$groove" --title "Sparse adaptive evaluation: a groove on level 4 of the helmet (14,568 triangles; uniform: 256,000)"
build/bin/fairshape render "$sparse" $figs/adaptive_helmet_zoom.png --edges --flat --view front --focus 0.06 0.0 0.34 \
  --radius 0.12 --width 900 --height 700 --overlay "$groove" --title "Around the groove: finest level, then one level per ring outwards"
