#!/usr/bin/env bash
# Figures 1 b/c, 2, 7, 8 and 9 (top) of Boier-Martin et al.: runs each config under
# configs/boier-martin/, renders every run (VTK offscreen) side by side into
# papers/boier-martin/figures/figN.png and keeps its runs.csv in papers/boier-martin/data/.
#   bash papers/boier-martin/figures/make_figures.sh [fig1 fig2 fig7 fig7_vase fig8 fig9 fig9_vase]   (after `make build`)
set -euo pipefail
cd "$(dirname "$0")/../../.."
figures=("$@")
[ ${#figures[@]} -gt 0 ] || figures=(fig1 fig2 fig7 fig7_vase fig8 fig9 fig9_vase)
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

# Figure 8 d-f: the default improved run's ladder (columns: run_id, accuracy, relaxation, sweeps).
fig8_ladder() {
  local improved
  improved=$(awk -F, 'NR > 1 && $2 == "improved" && $3 == "multigrid_cg" && $4 == 2 {print $1}' results/figures/fig8/runs.csv)
  /usr/bin/python3 scripts/panels.py results/figures/fig8 papers/boier-martin/figures/fig8_levels.png \
    --title "The cascade's levels 2, 3, 4 (2 multigrid-CG iterations per level): the optimized control mesh and the constraints propagated to it" \
    --ladder "$improved" --render "${cow_view[@]}"
  cp results/figures/fig8/steps.csv papers/boier-martin/data/fig8_steps.csv
}

for f in "${figures[@]}"; do
  case $f in
    fig1) figure fig1 fig1_region_of_influence --rest "$(rest_hierarchy)" \
            --title "One nose handle propagated to level 0, 1, 2 or 3 and solved on its region (2 rings): global on the base, a bump on the finest (colour: displacement; wireframe: the base patches)" \
            --label "influence level 0: {region_fraction:.0%} of the surface in its region, detail change {detail_change:.3f}" \
            --label "influence level 1: {region_fraction:.0%}, detail change {detail_change:.3f}" \
            --label "influence level 2: {region_fraction:.1%}, detail change {detail_change:.3f}" \
            --label "influence level 3: {region_fraction:.2%}, detail change {detail_change:.3f}" \
            --columns 3 --render "${cow_view[@]}" --control-level 0 ;;
    fig2) figure fig2 fig2_nose_pull --rest "$(rest_hierarchy)" \
            --title "Nose pulled on the finest level of a Catmull-Clark hierarchy (colour: displacement)" \
            --label "thin plate, back third fixed: detail change {detail_change:.2f}" \
            --label "thin plate, all but the head fixed (the paper's boundary constraints): {detail_change:.2f}" \
            --label "detail-preserving, back third fixed: detail change {detail_change:.2f}" \
            --columns 2 --render "${cow_view[@]}" ;;
    fig7) figure fig7 fig7_constraint_kinds --rest "$(rest_hierarchy)" \
            --title "Point, normal and curve constraints, detail-preserving energy, hooves fixed (colour: displacement)" \
            --label "{kind} constraints: detail change {detail_change:.3f}" \
            --render "${cow_view[@]}" ;;
    fig8) figure fig8 fig8_accuracy --rest data/cow.off \
            --title "One nose pull: level 2 solved and subdivided; the cascade relaxed by the paper's sweeps or by multigrid-CG iterations; converged (colour: displacement)" \
            --label "interactive: error {error_vs_reference:.1e}, {solve_s:.2f} s" \
            --label "improved, 10 Gauss-Seidel sweeps per level (the paper's): error {error_vs_reference:.1e}, {solve_s:.2f} s" \
            --label "improved, 1 multigrid-CG iteration per level: error {error_vs_reference:.1e}, {solve_s:.2f} s" \
            --label "improved, 2 multigrid-CG iterations per level (default): error {error_vs_reference:.1e}, {solve_s:.2f} s" \
            --label "improved, 5 multigrid-CG iterations per level: error {error_vs_reference:.1e}, {solve_s:.2f} s" \
            --label "converged: error {error_vs_reference:.1e}, {solve_s:.2f} s" \
            --columns 3 --render "${cow_view[@]}"
          fig8_ladder ;;
    fig9) figure fig9 fig9_annulus_twist --rest data/annulus.obj \
            --title "Inner rim of an annulus turned 45 and 90 degrees about z and lifted by 0.4, outer rim fixed" \
            --label "{kind}, energy {energy:.3g}, constraint residual {constraint_violation:.0e}" \
            --render --view front --azimuth 20 --elevation 35 --width 700 --height 600 --edges ;;
    fig7_vase) figure fig7_vase fig7_vase --rest data/vase.obj \
            --title "Point, normal and curve constraints on a fluted vase of revolution, detail-preserving energy, foot fixed (colour: displacement)" \
            --label "{kind} constraints: energy {energy:.3g}, constraint residual {constraint_violation:.0e}" \
            --render --view front --up z --width 600 --height 700 ;;
    fig9_vase) out=results/figures/fig9_vase
          build/bin/fairshape run configs/boier-martin/fig9_vase_drag.yaml --out "$out" --force
          run=$(awk -F, 'NR == 2 {print $1}' "$out/runs.csv")
          /usr/bin/python3 scripts/panels.py "$out" papers/boier-martin/figures/fig9_vase.png --steps "$run" \
            --title "Interactive editing (Figure 9, bottom): the vase's lip dragged in 4 steps, each the level-1 solve subdivided with the details (colour: displacement)" \
            --label "step {step:.0f}: {solve_s:.3f} s, error vs CHOLMOD {error_vs_reference}" \
            --render --view front --up z --width 600 --height 700
          mkdir -p papers/boier-martin/data
          cp "$out/runs.csv" papers/boier-martin/data/fig9_vase_runs.csv
          cp "$out/steps.csv" papers/boier-martin/data/fig9_vase_steps.csv ;;
    *) echo "unknown figure '$f' (choose from fig1 fig2 fig7 fig7_vase fig8 fig9 fig9_vase)" >&2; exit 2 ;;
  esac
done
