#!/usr/bin/env bash
# Figures 1 b/c, 2, 7, 8 and 9 (top) of Boier-Martin et al.: runs each config under
# configs/boier-martin/, renders every run (VTK offscreen) side by side into
# papers/boier-martin/figures/figN.png and keeps its runs.csv in papers/boier-martin/data/.
# Figure 8's panels are coloured by the distance to the converged answer, and Figures 8 and 9
# draw what the paper draws (the propagated constraints close up, the rotation's arc and axis)
# through figure_tools.py. Last, readme_numbers.py rewrites the README's tables from data/.
#   bash papers/boier-martin/figures/make_figures.sh [fig1 fig2 fig7 fig7_vase fig8 fig9 fig9_vase dense_scan_kkt numbers]   (after `make build`)
# (fig8_render: Figure 8's panels from the last fig8 run, without running it again.)
set -euo pipefail
cd "$(dirname "$0")/../../.."
figures=("$@")
[ ${#figures[@]} -gt 0 ] || figures=(fig1 fig2 fig7 fig7_vase fig8 fig9 fig9_vase dense_scan_kkt)
cow_view=(--view front --zoom 1.5)

figure() {  # name config panels-arguments...
  local name=$1 config=$2
  shift 2
  local out=results/figures/$name
  local rc=0
  build/bin/fairshape run "configs/boier-martin/$config.yaml" --out "$out" --force || rc=$?
  [ $rc -eq 0 ] || grep -q "expect:" "configs/boier-martin/$config.yaml" || exit $rc  # exit 3: runs that end as they expect
  /usr/bin/python3 scripts/panels.py "$out" "papers/boier-martin/figures/$name.png" "$@"
  mkdir -p papers/boier-martin/data
  cp "$out/runs.csv" "papers/boier-martin/data/${name}_runs.csv"
  cp "$out/run.json" "papers/boier-martin/data/${name}_run.json"
}

# The edits' rest shape, as the input panel: the cow remeshed as the configs remesh it (the
# remesher is deterministic, so this is the hierarchy the runs edit), finest level shown.
rest_hierarchy() {
  local vtm=results/figures/cow_remeshed_600_3.vtm
  [ -f "$vtm" ] || build/bin/fairshape remesh data/cow.off --scheme catmull-clark --base-faces 600 --levels 3 "$vtm" >&2
  echo "$vtm"
}

tools=(/usr/bin/python3 papers/boier-martin/figures/figure_tools.py)

# Figure 8 top: every mode coloured by its distance to the converged answer (the reference of
# error_vs_reference), so the panels show what tells them apart; the input with the handle.
fig8_errors() {
  local out=results/figures/fig8 copies=results/figures/fig8_error converged
  converged=$(awk -F, 'NR > 1 && $2 == "converged" {print $1}' $out/runs.csv)
  "${tools[@]}" error $out "$converged" $copies $(awk -F, 'NR > 1 {print $1}' $out/runs.csv)
  "${tools[@]}" rest $out/vtk/$converged.vtp $copies/rest.vtp
  /usr/bin/python3 scripts/panels.py $out papers/boier-martin/figures/fig8.png --inputs-from $copies --allow-folded \
    --array error --colour-label "distance to converged" --rest $copies/rest.vtp \
    --title "One nose pull at the accuracies of §5 (colour: each vertex's distance to the converged answer)" \
    --label "interactive: error {error_vs_reference:.1e}, {solve_s:.2f} s; {flipped_faces:.0f} face flipped ({termination})" \
    --label "improved, 10 Gauss-Seidel sweeps per level (the paper's): error {error_vs_reference:.1e}" \
    --label "improved, 1 multigrid-CG iteration per level: error {error_vs_reference:.1e}" \
    --label "improved, 2 multigrid-CG iterations per level (default): error {error_vs_reference:.1e}" \
    --label "improved, 5 multigrid-CG iterations per level: error {error_vs_reference:.1e}" \
    --label "converged (the reference): error {error_vs_reference:.1e}, {solve_s:.2f} s" \
    --columns 4 --render "${cow_view[@]}" --width 560 --height 400
}

# Figure 8 d-f: the default improved run's ladder (columns: run_id, accuracy, relaxation, sweeps):
# each level's control mesh with the vertices its propagated constraints reach (the fixed back
# third grey, the nose handle's rows red), whole and close up under the moved nose.
fig8_ladder() {
  local improved copies=results/figures/fig8_ladder
  improved=$(awk -F, 'NR > 1 && $2 == "improved" && $3 == "multigrid_cg" && $4 == 2 {print $1}' results/figures/fig8/runs.csv)
  "${tools[@]}" ladder results/figures/fig8 "$improved" $copies --above -0.1 --clip 0.62 0.12 0.08 0.06 \
    > papers/boier-martin/data/fig8_ladder_constrained.txt
  build/bin/fairshape render $copies/level2.vtp $copies/level3.vtp $copies/level4.vtp $copies/whole.png \
    --array constrained --colour-label "reached by the constraints" --flat \
    --title "The cascade's levels 2, 3, 4 (2 multigrid-CG iterations per level): the optimized control mesh and the constraints propagated to it" \
    --label "level 2: control mesh" --label "level 3: control mesh" --label "level 4: control mesh" \
    --view front --zoom 1.5 --width 560 --height 370
  build/bin/fairshape render $copies/level2_zoom.vtp $copies/level3_zoom.vtp $copies/level4_zoom.vtp $copies/zoom.png \
    --array constrained --colour-label "reached by the constraints" --flat --edges \
    --label "level 2, under the nose: the handle's propagated rows" --label "level 3" --label "level 4: the handle's own vertex" \
    --view front --elevation -50 --azimuth 30 --width 560 --height 370
  "${tools[@]}" compose papers/boier-martin/figures/fig8_levels.png $copies/whole.png $copies/zoom.png
  cp results/figures/fig8/steps.csv papers/boier-martin/data/fig8_steps.csv
}

# Figure 9 top: the input with its constraints, then each turn with the rotation drawn (its
# axis, and an arc of its angle above the lifted rim).
fig9_rotations() {
  local out=results/figures/fig9 copies=results/figures/fig9_arcs first
  first=$(awk -F, 'NR == 2 {print $1}' $out/runs.csv)
  "${tools[@]}" rest $out/vtk/$first.vtp $copies/rest.vtp
  /usr/bin/python3 - $out/runs.csv <<'PY' | while read -r run angle; do
import csv, re, sys
for r in csv.DictReader(open(sys.argv[1])):
    print(r["run_id"], re.findall(r"angle_deg: ([-0-9.]+)", r["constraints"])[-1])
PY
    "${tools[@]}" arc $out/vtk/$run.vtp $copies/$run.vtp --axis 0 0 1 --radius 0.5 --angle "$angle" \
      --lift 0.7 --axis-length 0.3 --width 0.006 --no-arrows
  done
  /usr/bin/python3 scripts/panels.py $out papers/boier-martin/figures/fig9.png --inputs-from $copies --rest $copies/rest.vtp --runs 1,2 \
    --title "Inner rim of an annulus turned about z (axis and arc drawn) and lifted by 0.4, outer rim fixed (red: the turned rim; grey: the fixed one)" \
    --label "turned 45 degrees: energy {energy:.3g}, constraint residual {constraint_violation:.0e}, {flipped_faces:.0f} faces flipped" \
    --label "turned 60 degrees: energy {energy:.3g}, constraint residual {constraint_violation:.0e}, {flipped_faces:.0f} faces flipped" \
    --render --view front --azimuth 20 --elevation 35 --width 620 --height 530 --edges
}

for f in "${figures[@]}"; do
  case $f in
    fig1) figure fig1 fig1_region_of_influence --rest "$(rest_hierarchy)" --runs 1,2 \
            --title "Regions of influence (§4.2). Top: the nose pulled on level 0 or 1 changes the head (b). Bottom, close up: a bump on the back solved on level 2 or 3 stays local (c). Colour: displacement; wireframe: the base patches, as edited" \
            --label "(b) nose, influence level 0: {region_fraction:.0%} of the surface in its region, detail change {detail_change:.3f}" \
            --label "nose, influence level 1: {region_fraction:.0%}, detail change {detail_change:.3f}" \
            --columns 3 --render "${cow_view[@]}" --control-level 0 --width 620 --height 430
          mv papers/boier-martin/figures/fig1.png results/figures/fig1/top.png
          /usr/bin/python3 scripts/panels.py results/figures/fig1 results/figures/fig1/bottom.png --runs 6,7,8 --title "" \
            --label "bump on the back, level 2, 2 rings: {region_fraction:.1%} of the surface, a peak" \
            --label "(c) bump on the back, level 2, 8 rings: {region_fraction:.1%}, smooth" \
            --label "bump on the back, level 3, 8 rings: {region_fraction:.1%}" \
            --render --view front --focus 0.05 0.25 0.0 --radius 0.12 --width 620 --height 370
          "${tools[@]}" compose papers/boier-martin/figures/fig1.png results/figures/fig1/top.png results/figures/fig1/bottom.png ;;
    fig2) figure fig2 fig2_nose_pull --rest "$(rest_hierarchy)" --allow-folded \
            --title "Nose pulled on the finest level of a Catmull-Clark hierarchy (colour: displacement; grey: held vertices)" \
            --label "thin plate, back third held: the front collapses ({flipped_faces:.0f} faces flipped, detail change {detail_change:.2f})" \
            --label "(b) thin plate, held but for the nose's level-1 region: smoothed ({flipped_faces:.0f} faces flipped, {detail_change:.2f})" \
            --label "(c) detail-preserving, back third held: detail change {detail_change:.2f}, {flipped_faces:.0f} flipped" \
            --columns 2 --render "${cow_view[@]}" --width 660 --height 460 ;;
    fig7) figure fig7 fig7_constraint_kinds --rest "$(rest_hierarchy)" \
            --title "Point, normal and curve constraints, detail-preserving energy, hooves fixed (colour: displacement)" \
            --label "{kind} constraints: detail change {detail_change:.3f}" \
            --render "${cow_view[@]}" --width 800 --height 560 ;;
    fig8) out=results/figures/fig8
          build/bin/fairshape run configs/boier-martin/fig8_accuracy.yaml --out "$out" --force || [ $? -eq 3 ]  # the interactive run folds
          mkdir -p papers/boier-martin/data
          cp "$out/runs.csv" papers/boier-martin/data/fig8_runs.csv
          cp "$out/run.json" papers/boier-martin/data/fig8_run.json
          fig8_errors
          fig8_ladder ;;
    fig8_render)  # Figure 8's panels again from results/figures/fig8 (its run takes ~10 minutes)
          cp results/figures/fig8/runs.csv papers/boier-martin/data/fig8_runs.csv
          cp results/figures/fig8/run.json papers/boier-martin/data/fig8_run.json
          fig8_errors
          fig8_ladder ;;
    fig9) out=results/figures/fig9
          build/bin/fairshape run configs/boier-martin/fig9_annulus_twist.yaml --out "$out" --force
          mkdir -p papers/boier-martin/data
          cp "$out/runs.csv" papers/boier-martin/data/fig9_runs.csv
          cp "$out/run.json" papers/boier-martin/data/fig9_run.json
          fig9_rotations ;;
    fig7_vase) figure fig7_vase fig7_vase --rest data/vase.obj \
            --title "Point, normal and curve constraints on a fluted vase of revolution, detail-preserving energy, foot fixed (colour: displacement)" \
            --label "{kind} constraints: energy {energy:.3g}, constraint residual {constraint_violation:.0e}" \
            --render --view front --up z --width 600 --height 700 ;;
    fig9_vase) out=results/figures/fig9_vase copies=results/figures/fig9_vase_steps
          build/bin/fairshape run configs/boier-martin/fig9_vase_drag.yaml --out "$out" --force
          run=$(awk -F, 'NR == 2 {print $1}' "$out/runs.csv")
          "${tools[@]}" steps "$out" "$run" "$copies"
          "${tools[@]}" rest "$out/vtk/$run.vtp" "$copies/rest.vtp"
          /usr/bin/python3 scripts/panels.py "$out" papers/boier-martin/figures/fig9_vase.png --steps "$run" \
            --inputs-from "$copies" --rest "$copies/rest.vtp" \
            --title "Interactive editing (Figure 9, bottom): the vase's lip dragged in 4 steps, each the level-1 solve subdivided with the details (colour: displacement; red: the handle, grey: the held foot)" \
            --label "step {step:.0f} of 4: solved in {solve_s:.3f} s" \
            --render --view front --up z --width 520 --height 640
          mkdir -p papers/boier-martin/data
          cp "$out/runs.csv" papers/boier-martin/data/fig9_vase_runs.csv
          cp "$out/steps.csv" papers/boier-martin/data/fig9_vase_steps.csv ;;
    dense_scan_kkt) out=results/figures/dense_scan_kkt  # numbers only: "KKT on badly scaled systems"
          build/bin/fairshape run configs/boier-martin/dense_scan_kkt.yaml --out "$out" --force
          mkdir -p papers/boier-martin/data
          cp "$out/runs.csv" papers/boier-martin/data/dense_scan_kkt_runs.csv ;;
    numbers) ;;
    *) echo "unknown figure '$f' (choose from fig1 fig2 fig7 fig7_vase fig8 fig8_render fig9 fig9_vase dense_scan_kkt numbers)" >&2; exit 2 ;;
  esac
done

# Renders above 600 KB are rewritten with a 256-colour palette (the repository keeps them; the
# palette bands the shading a little, so the panels above are sized to stay below it).
for f in "${figures[@]}"; do
  for png in papers/boier-martin/figures/"${f%_render}".png papers/boier-martin/figures/"${f%_render}"_levels.png; do
    [ -f "$png" ] && [ "$(stat -c %s "$png")" -gt 600000 ] && "${tools[@]}" shrink "$png"
  done
done

# The numbers the README's figure sections quote, from data/ (between its "numbers:" markers).
/usr/bin/python3 papers/boier-martin/figures/readme_numbers.py
