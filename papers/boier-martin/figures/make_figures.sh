#!/usr/bin/env bash
# Figures 1 b/c, 2, 7, 8 and 9 (top) of Boier-Martin et al.: runs each config under
# configs/boier-martin/, renders every run (VTK offscreen) side by side into
# papers/boier-martin/figures/figN.png and keeps its runs.csv in papers/boier-martin/data/.
#   bash papers/boier-martin/figures/make_figures.sh [fig1 fig2 fig7 fig8 fig9]   (after `make build`)
set -euo pipefail
cd "$(dirname "$0")/../../.."
figures=("$@")
[ ${#figures[@]} -gt 0 ] || figures=(fig1 fig2 fig7 fig8 fig9)
cow_view=(--view front --zoom 1.5 --width 800 --height 560)

figure() {  # name config panels-arguments...
  local name=$1 config=$2
  shift 2
  local out=results/figures/$name
  build/bin/fairshape run "configs/boier-martin/$config.yaml" --out "$out" --force
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

for f in "${figures[@]}"; do
  case $f in
    fig1) figure fig1 fig1_constraint_level \
            --title "One nose handle solved exactly on level 0, 1 or 3: same reach, details kept better on coarse levels (colour: displacement)" \
            --label "edit level {input_edit_level:.0f}: detail change {detail_change:.3f}" \
            --render "${cow_view[@]}" ;;
    fig2) figure fig2 fig2_nose_pull --rest "$(rest_hierarchy)" \
            --title "Nose pulled on the finest level of a Catmull-Clark hierarchy (colour: displacement)" \
            --label "{kind}: detail change {detail_change:.2f}, constraint residual {constraint_violation:.0e}" \
            --render "${cow_view[@]}" ;;
    fig7) figure fig7 fig7_constraint_kinds --rest "$(rest_hierarchy)" \
            --title "Point, normal and curve constraints, detail-preserving energy, hooves fixed (colour: displacement)" \
            --label "{kind} constraints: detail change {detail_change:.3f}" \
            --render "${cow_view[@]}" ;;
    fig8) figure fig8 fig8_accuracy --rest data/cow.off \
            --title "One nose pull at three accuracies: level 2 solved and subdivided, the paper's cascade, converged (colour: displacement)" \
            --label "{problem_accuracy}: error {error_vs_reference:.1e}, {solve_s:.3f} s" \
            --render "${cow_view[@]}"
          improved=$(awk -F, 'NR > 1 && $2 == "improved" {print $1}' results/figures/fig8/runs.csv)
          /usr/bin/python3 scripts/panels.py results/figures/fig8 papers/boier-martin/figures/fig8_levels.png \
            --title "The cascade's levels 2, 3, 4: the optimized control mesh and the constraints propagated to it" \
            --ladder "$improved" --render "${cow_view[@]}"
          cp results/figures/fig8/steps.csv papers/boier-martin/data/fig8_steps.csv ;;
    fig9) figure fig9 fig9_annulus_twist --rest data/annulus.obj \
            --title "Inner rim of an annulus turned 45 and 90 degrees about z and lifted by 0.4, outer rim fixed" \
            --label "{kind}, energy {energy:.3g}, constraint residual {constraint_violation:.0e}" \
            --render --view front --azimuth 20 --elevation 35 --width 700 --height 600 --edges ;;
    *) echo "unknown figure '$f' (choose from fig1 fig2 fig7 fig8 fig9)" >&2; exit 2 ;;
  esac
done
