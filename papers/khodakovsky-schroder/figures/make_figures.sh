#!/usr/bin/env bash
# Figures 11 (on the patch and on the helmet), 14, 15, 16 and 17 of Khodakovsky & Schröder and the sparse adaptive helmet: runs each config under
# configs/khodakovsky-schroder/, renders it (`fairshape render` through scripts/panels.py or
# ks_panels.py, VTK offscreen, coloured by the signed normal displacement) into
# papers/khodakovsky-schroder/figures/, keeps its runs.csv, features.csv and run.json in
# papers/khodakovsky-schroder/data/, and regenerates the README's table of measured numbers from
# them (readme_numbers.py).
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
# Figures 11, 14, 15 and 17 and the adaptive helmet are put together from several `fairshape
# render` calls (ks_panels.py compose): an input panel (the surface without features and the
# curves drawn on it: ks_panels.py input), and panels that colour different arrays, each on its
# own scale.
ks=papers/khodakovsky-schroder/figures/ks_panels.py
row() { awk -F, -v n="$2" 'NR == n + 1 { print $1 }' "$1/runs.csv"; }   # the run id of runs.csv's n-th row
col() { /usr/bin/python3 -c 'import csv, sys; print(f"{int(float(list(csv.DictReader(open(sys.argv[1])))[0][sys.argv[2]])):,}")' \
          "$1/runs.csv" "$2"; }   # a count from runs.csv's first row, with thousands separators
num() { /usr/bin/python3 -c 'import csv, sys; print(f"{float(list(csv.DictReader(open(sys.argv[1])))[0][sys.argv[2]]):.4g}")' \
          "$1/runs.csv" "$2"; }   # a number from runs.csv's first row, 4 digits
tmp=$out-panels; mkdir -p "$tmp"
patch=(--up z --view front --azimuth 15 --zoom 1.35 --width 620 --height 500)
panel=("${patch[@]}" --elevation 30); above=("${patch[@]}" --elevation 55)
# Figure 11 (§2.3-2.4): the input with the curves, and the result with the curves where the
# features are and the neighbourhoods outlined (the paper draws the outline on the drawn level).
# fig11_pair NAME SUBJECT TITLE VIEW...: the input and result panels of run NAME side by side.
fig11_pair() {
  local name=$1 subject=$2 title=$3; shift 3
  run $name
  local id; id=$(row $out-$name 1)
  /usr/bin/python3 $ks input $out-$name $id $tmp
  build/bin/fairshape render $tmp/${id}_input.vtp $tmp/${name}_a.png --overlay $tmp/${id}_input_overlay.vtp \
    --label "input: $subject (level 4) and the curves drawn on level 2" "$@"
  build/bin/fairshape render $out-$name@$id $tmp/${name}_b.png --array displacement --component normal \
    --colour-label "normal displacement" "$@" \
    --label "result, level 4: $(col $out-$name vertices_moved) vertices moved (outlined), max $(num $out-$name max_displacement)"
  /usr/bin/python3 $ks compose $figs/$name.png --columns 2 $tmp/${name}_{a,b}.png --title "$title"
}
fig11_pair fig11 "the patch" \
  "Figure 11/16: three overlapping feature lines drawn on level 2 (two ridges, one groove; orange: curves)" \
  --up z --view front --elevation 40 --azimuth 10 --zoom 1.35 --width 800 --height 620
build/bin/fairshape render "$out-fig11/adaptive/$(row $out-fig11 1).obj" $figs/fig11_adaptive.png \
  --edges --flat --up z --view top --zoom 1.3 --width 900 --height 700 --title "Figure 11: the adaptive mesh"
# On the helmet, the paper's subject: seen from above the crown, signed colouring.
fig11_pair fig11_helmet "the helmet" \
  "Figure 11 on the helmet: three overlapping feature lines drawn on level 2 (two ridges, one groove; orange: curves)" \
  --view top --up z --focus 0.04 0.0 0.33 --radius 0.2 --width 800 --height 620
run fig16
/usr/bin/python3 scripts/panels.py --allow-unmet $out-fig16 $figs/fig16.png --columns 3 \
  --title "Figure 16: one parameter at a time (radius, crease, groove, left/right ratio, end height ratio)" \
  --label "r {feature_defaults_radius}, h {feature_defaults_height}, crease {feature_defaults_crease}, L/R {feature_defaults_left_right_ratio}, end {feature_defaults_end_height_ratio}" \
  --render "${patch_view[@]}"
# Figure 14 (§2.6, features on two levels): the input with the three curves; each level's own
# layer (`feature_displacement` of levels/<run>_level<l>.vtp: the offsets that level's features
# put on its control points, the layer kept apart from the surface), each on its own scale; the
# result, on a scale fitted to the grooves' depth (0.02) so that they read as grooves (the
# ridge's 0.12 saturates, its shape is in the shading).
run fig14
id=$(row $out-fig14 1)
/usr/bin/python3 $ks input $out-fig14 $id $tmp
build/bin/fairshape render $tmp/${id}_input.vtp $tmp/f14a.png --overlay $tmp/${id}_input_overlay.vtp \
  --label "input: the patch (level 4) and the curves" "${panel[@]}"
build/bin/fairshape render $out-fig14/levels/${id}_level1.vtp $tmp/f14b.png --array feature_displacement --component normal \
  --range -0.12 0.12 --colour-label "level-1 layer (normal)" --label "level 1: the ridge's layer (h 0.12, r 0.45)" "${panel[@]}"
build/bin/fairshape render $out-fig14/levels/${id}_level3.vtp $tmp/f14c.png --array feature_displacement --component normal \
  --range -0.02 0.02 --colour-label "level-3 layer (normal)" \
  --label "level 3, over the ridge: the grooves' layer (h -0.02, r 0.07)" "${panel[@]}"
build/bin/fairshape render $out-fig14@$id $tmp/f14d.png --array displacement --component normal --range -0.03 0.03 \
  --colour-label "normal displacement" --label "result, level 4 (scale fitted to the grooves)" "${panel[@]}"
/usr/bin/python3 $ks compose $figs/fig14.png --columns 2 $tmp/f14{a,b,c,d}.png \
  --title "Figure 14: a ridge drawn on level 1, two grooves on level 3 that follow it (orange: curves; dark: the neighbourhoods)"
# Figure 15 (§2.6, a coarse edit carries the features): the input with the edit's constraints
# (held ends grey, the lifted base vertex red with its 0.2 arrow), the result without and with the
# lift on the grooves' scale, and the lifted run's level-1 and level-3 layers: the ridge and the
# grooves ride on the bump with their own heights.
run fig15
flat=$(row $out-fig15 1); lift=$(row $out-fig15 2)
/usr/bin/python3 $ks input $out-fig15 $flat $tmp --edit data/ks_patch.off --fixed-x 0.0 0.1 --fixed-x 0.9 1.0 \
  --handle 0 0 0 --offset 0 0 0.2
build/bin/fairshape render $tmp/${flat}_input.vtp $tmp/f15a.png --overlay $tmp/${flat}_input_overlay.vtp \
  --label "input: curves, held ends (grey), lifted base vertex (red)" "${panel[@]}"
build/bin/fairshape render $out-fig15@$flat $out-fig15@$lift $tmp/f15b.png --array displacement --component normal \
  --range -0.03 0.03 --colour-label "normal displacement" \
  --label "no lift (result, level 4)" --label "lift 0.2 (result, level 4; the top groove drawn after it)" "${panel[@]}"
# The layers seen from higher up (elevation 55): at 30 the key light falls square on the bump's
# top and pales the ridge's colour there.
build/bin/fairshape render $out-fig15/levels/${lift}_level1.vtp $tmp/f15c.png --array feature_displacement --component normal \
  --range -0.12 0.12 --colour-label "level-1 layer (normal)" --label "lift 0.2, level 1: the ridge's layer on the bump (from above)" \
  "${above[@]}"
build/bin/fairshape render $out-fig15/levels/${lift}_level3.vtp $tmp/f15d.png --array feature_displacement --component normal \
  --range -0.02 0.02 --colour-label "level-3 layer (normal)" --label "lift 0.2, level 3: the grooves' layer (from above)" \
  "${above[@]}"
/usr/bin/python3 $ks compose $figs/fig15.png --columns 2 $tmp/f15a.png $tmp/f15b.png $tmp/f15c.png $tmp/f15d.png \
  --title "Figure 15: a detail-preserving level-0 edit (lift 0.2) carries the ridge and the grooves (orange: curves)"
# Figure 17 (§3: a design study on an irregular shape): fourteen features drawn on level 1 of the
# helmet and laid over one another (ribs crossed by bands, stripes, badges, a ring), level 4
# shown (configs/khodakovsky-schroder/fig17_study.yaml): the input with the curves, the result
# from behind on the left, from above and from the right. One scale for the three result views.
# fig17.yaml (six features kept apart, one per placement tool: the tools' example) is run for its
# numbers only.
run fig17
run fig17_study
id=$(row $out-fig17_study 1)
/usr/bin/python3 $ks input $out-fig17_study $id $tmp
helmet=(--up z --zoom 1.3 --width 760 --height 620)
f17=(--array displacement --component normal --range -0.012 0.012 --colour-label "normal displacement")
build/bin/fairshape render $tmp/${id}_input.vtp $tmp/f17a.png --overlay $tmp/${id}_input_overlay.vtp \
  --label "input: the helmet (level 4 of data/helmet.off) and the 14 curves" "${helmet[@]}" --view front --elevation 20 --azimuth 35
build/bin/fairshape render $out-fig17_study@$id $tmp/f17b.png "${f17[@]}" --label "result: from behind on the left" \
  "${helmet[@]}" --view front --elevation 20 --azimuth 35
build/bin/fairshape render $out-fig17_study@$id $tmp/f17c.png "${f17[@]}" --no-overlays --label "from above (no curves drawn)" \
  "${helmet[@]}" --view top
build/bin/fairshape render $out-fig17_study@$id $tmp/f17d.png "${f17[@]}" --label "from the right" \
  "${helmet[@]}" --view front --elevation 20 --azimuth 145
/usr/bin/python3 $ks compose $figs/fig17.png --columns 2 $tmp/f17{a,b,c,d}.png \
  --title "Figure 17: a design study, 14 overlapping features on level 1 of the helmet (orange: curves; dark: the neighbourhoods)"
# §2.5, truly adaptive: the helmet's groove on level 4 evaluated on a sparse hierarchy; the
# adaptive mesh with its edges, whole and around the groove. Around the groove: the groove alone
# in smooth shading (0.004 deep: the mesh's edges hide it), the adaptive mesh, and the drawn
# curve over it (the curve lies on the surface before its groove, over the groove's bottom).
run adaptive_helmet
sparse="$out-adaptive_helmet/adaptive/$(row $out-adaptive_helmet 1).obj"
groove=$(ls "$out-adaptive_helmet"/curves/*_groove.obj)
build/bin/fairshape render "$sparse" $figs/adaptive_helmet.png --edges --flat --view front --width 900 --height 700 \
  --overlay "$groove" \
  --title "Sparse adaptive evaluation: a groove on level 4 of the helmet ($(col $out-adaptive_helmet triangles_adaptive) triangles; uniform: $(col $out-adaptive_helmet triangles_uniform))"
zoom=(--up z --view front --elevation 50 --focus 0.06 0.0 0.34 --radius 0.12 --width 600 --height 520)
build/bin/fairshape render "$sparse" $tmp/ad_a.png "${zoom[@]}" --label "the groove (h -0.004, r 0.02), shaded"
build/bin/fairshape render "$sparse" $tmp/ad_b.png "${zoom[@]}" --edges --flat --label "the adaptive mesh"
build/bin/fairshape render "$sparse" $tmp/ad_c.png "${zoom[@]}" --edges --flat --overlay "$groove" --label "the drawn curve (orange)"
/usr/bin/python3 $ks compose $figs/adaptive_helmet_zoom.png --columns 3 $tmp/ad_{a,b,c}.png \
  --title "Around the groove: the finest level along it, then one level less per ring outwards"
# The README's measured numbers, from the data just written.
/usr/bin/python3 papers/khodakovsky-schroder/figures/readme_numbers.py
