#!/usr/bin/env bash
# The bundled cow remeshed into a Catmull-Clark hierarchy (about 600 base faces, 4 levels),
# every level rendered, then one strip: papers/boier-martin/figures/cow_hierarchy.png.
#   bash papers/boier-martin/figures/cow_hierarchy.sh   (after `make build`)
set -euo pipefail
cd "$(dirname "$0")/../../.."
out=results/cow_hierarchy
mkdir -p "$out"
build/bin/fairshape remesh data/cow.off --scheme catmull-clark --base-faces 600 --levels 4 "$out/cow.vtm" | tee "$out/remesh.txt"
for l in 0 1 2 3 4; do
  edges=$([ "$l" -le 2 ] && echo --edges || true)
  build/bin/fairshape render "$out/cow/cow_$l.vtp" "papers/boier-martin/figures/cow_hierarchy_L$l.png" \
    --view front --zoom 1.6 --width 600 --height 380 $edges
done
/usr/bin/python3 - <<'PYEOF'
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt, matplotlib.image as mpimg
fig, axes = plt.subplots(1, 5, figsize=(20, 3.4), dpi=100)
for l, ax in enumerate(axes):
    ax.imshow(mpimg.imread(f"papers/boier-martin/figures/cow_hierarchy_L{l}.png"))
    ax.set_title(f"level {l}")
    ax.axis("off")
fig.tight_layout()
fig.savefig("papers/boier-martin/figures/cow_hierarchy.png")
PYEOF
cp "$out/remesh.txt" papers/boier-martin/figures/cow_hierarchy_remesh.txt
