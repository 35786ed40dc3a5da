# fairshape render: what it draws can be checked in the pixels — a known scene covers what it
# should, the colour bar is where it should be, a ridge and a groove get opposite colours under
# signed colouring, panels share one colour range; .vtm, .pvd, curves and run folders render;
# a folder with several runs is refused rather than one guessed.
source "$(dirname "$0")/lib.sh"
command -v xvfb-run >/dev/null || { echo "render: xvfb-run missing (Debian package xvfb)"; exit 1; }
S="$SCRATCH"
# A z-up grid over [-1, 1]², raised along x < 0 (a ridge) and lowered along x > 0 (a groove),
# with its displacement as a point array; and the flat grid, and a .pvd of the two.
$PY - "$S" <<'PYEOF'
import math, sys
d = sys.argv[1]
n = 41
def grid(scale):
    pts, disp = [], []
    for j in range(n):
        for i in range(n):
            x, y = -1 + 2 * i / (n - 1), -1 + 2 * j / (n - 1)
            h = scale * 0.15 * math.exp(-((abs(x) - 0.5) ** 2) / 0.02) * (1 if x < 0 else -1)
            pts.append((x, y, h))
            disp.append((0, 0, h))
    quads = [(j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i) for j in range(n - 1) for i in range(n - 1)]
    return pts, disp, quads
def vtp(path, scale):
    pts, disp, quads = grid(scale)
    fl = lambda rows: " ".join(f"{v:.6f}" for r in rows for v in r)
    with open(path, "w") as f:
        f.write('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">\n<PolyData>\n')
        f.write(f'<Piece NumberOfPoints="{len(pts)}" NumberOfPolys="{len(quads)}">\n')
        f.write(f'<PointData><DataArray type="Float64" Name="displacement" NumberOfComponents="3" format="ascii">{fl(disp)}</DataArray></PointData>\n')
        f.write(f'<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">{fl(pts)}</DataArray></Points>\n')
        f.write('<Polys><DataArray type="Int64" Name="connectivity" format="ascii">' + " ".join(str(v) for q in quads for v in q) + '</DataArray>\n')
        f.write('<DataArray type="Int64" Name="offsets" format="ascii">' + " ".join(str(4 * (k + 1)) for k in range(len(quads))) + '</DataArray></Polys>\n')
        f.write('</Piece>\n</PolyData>\n</VTKFile>\n')
vtp(f"{d}/ridge_groove.vtp", 1.0)
vtp(f"{d}/half.vtp", 0.5)
with open(f"{d}/steps.pvd", "w") as f:
    f.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1"><Collection>\n'
            '<DataSet timestep="0" file="half.vtp"/>\n<DataSet timestep="1" file="ridge_groove.vtp"/>\n</Collection></VTKFile>\n')
PYEOF
TOP=(--up z --view top --width 400 --height 400)
"$FS" render "$S/ridge_groove.vtp" "$S/signed.png" --array displacement --component normal "${TOP[@]}" 2>"$S/log" ||
  { cat "$S/log" >&2; fail "render of the ridge and groove"; }
"$FS" render "$S/ridge_groove.vtp" "$S/plain.png" "${TOP[@]}" --background transparent 2>"$S/log" ||
  { cat "$S/log" >&2; fail "plain render"; }
$PY - "$S" <<'PYEOF'
import sys
import matplotlib.image as mpimg
d = sys.argv[1]
img = mpimg.imread(f"{d}/signed.png")[:, :, :3]
# One 400 x 400 panel and the colour bar's 190-pixel strip beside it.
assert img.shape[:2] == (400, 590), img.shape
panel, bar = img[:, :400], img[:, 400:]
white = (panel.min(axis=2) > 0.97)
assert 0.2 < 1 - white.mean() < 0.95, f"the grid covers {1 - white.mean():.2f} of its panel"
assert (bar.min(axis=2) < 0.9).mean() > 0.05, "no colour bar"
# Top view, x to the right: the ridge (x < 0) warm, the groove (x > 0) cool, along the rows
# through the middle of the grid.
rows = slice(150, 250)
left, right = panel[rows, 100:180].reshape(-1, 3), panel[rows, 220:300].reshape(-1, 3)
lr, lb = left[:, 0].max(), left[:, 2].min()
assert (left[:, 0] - left[:, 2]).max() > 0.3, "no warm colour over the ridge"
assert (right[:, 2] - right[:, 0]).max() > 0.3, "no cool colour over the groove"
assert (left[:, 2] - left[:, 0]).max() < 0.3 and (right[:, 0] - right[:, 2]).max() < 0.3, "ridge and groove mixed"
plain = mpimg.imread(f"{d}/plain.png")
assert plain.shape == (400, 400, 4), f"no colour bar and an alpha channel expected, got {plain.shape}"
assert plain[0, 0, 3] == 0 and plain[200, 200, 3] == 1, "transparent background, opaque model"
PYEOF
# An overlay lands where its point is: project it with the camera the render wrote.
printf 'v 0.0 0.5 0.0\n' > "$S/point.obj"
"$FS" render "$S/ridge_groove.vtp" "$S/overlay.png" "${TOP[@]}" --overlay "$S/point.obj" --camera-out "$S/camera.json" ||
  fail "render with an overlay"
$PY - "$S" <<'PYEOF'
import json, sys
import numpy as np
import matplotlib.image as mpimg
d = sys.argv[1]
cam = json.load(open(f"{d}/camera.json"))
img = mpimg.imread(f"{d}/overlay.png")[:, :, :3]
W, H = cam["image"]
assert img.shape[:2] == (H, W)
panel = cam["panels"][0]
x0, y0, w, h = panel["pixels_from_bottom_left"]
def pixel(p):
    q = np.array(panel["world_to_ndc"]) @ np.array([*p, 1.0])
    ndc = q[:2] / q[3]
    return int(round(H - 1 - (y0 + (ndc[1] + 1) / 2 * h))), int(round(x0 + (ndc[0] + 1) / 2 * w))
r, c = pixel((0.0, 0.5, 0.0))
red = img[r, c]
assert red[0] > 0.55 and red[1] < 0.35 and red[2] < 0.35, f"pixel {r, c} under the overlay point is {red}"
r2, c2 = pixel((0.0, -0.5, 0.0))  # elsewhere on the grid: its plain colour
assert img[r2, c2][1] > 0.45, f"plain surface expected at {r2, c2}, got {img[r2, c2]}"
PYEOF
# An overlay's curves follow --overlay-tube-radius: five times the radius covers several times the pixels.
printf 'v -0.8 0.0 0.0\nv 0.8 0.0 0.0\nl 1 2\n' > "$S/line.obj"
for r in 0.002 0.01; do
  "$FS" render "$S/ridge_groove.vtp" "$S/tube_$r.png" "${TOP[@]}" --overlay "$S/line.obj" --overlay-tube-radius "$r" ||
    fail "render with --overlay-tube-radius $r"
done
"$FS" render "$S/ridge_groove.vtp" "$S/no_tube.png" "${TOP[@]}" || fail "render without the curve"
$PY - "$S" <<'PYEOF'
import sys
import numpy as np
import matplotlib.image as mpimg
d = sys.argv[1]
base = mpimg.imread(f"{d}/no_tube.png")[:, :, :3]
covered = {r: int((np.abs(mpimg.imread(f"{d}/tube_{r}.png")[:, :, :3] - base).sum(axis=2) > 0.1).sum()) for r in ("0.002", "0.01")}
assert covered["0.002"] > 0, "the thin curve drew nothing"
assert covered["0.01"] > 3 * covered["0.002"], f"pixels covered by the curve at radius 0.002 and 0.01: {covered}"
PYEOF
expect_error 2 "overlay-tube-radius" -- "$FS" render "$S/ridge_groove.vtp" "$S/x.png" --overlay-tube-radius -1
# Two panels share one range: the half-height grid is paler than the full one beside it, not
# stretched to the same colours.
"$FS" render "$S/half.vtp" "$S/ridge_groove.vtp" "$S/pair.png" --array displacement "${TOP[@]}" --label half --label full ||
  fail "two panels"
$PY - "$S/pair.png" <<'PYEOF'
import sys
import matplotlib.image as mpimg
img = mpimg.imread(sys.argv[1])[:, :, :3]
assert img.shape[:2] == (440, 990), img.shape  # two panels, their labels, the colour bar
# viridis brightens with the value: the full grid's ridge and groove reach colours the half
# grid's do not (not both stretched to the same range).
import numpy as np
half, full = img[40:, :400], img[40:, 400:800]
def top_green(p):
    model = p[p.min(axis=2) < 0.95]
    return np.percentile(model[:, 1], 99.5)
assert top_green(full) > top_green(half) + 0.15, (top_green(full), top_green(half))
PYEOF
# A .pvd's steps, a .vtm's levels, a curve, a run folder.
"$FS" render "$S/steps.pvd@0" "$S/steps.pvd" "$S/pvd.png" --array displacement "${TOP[@]}" || fail ".pvd"
expect_error 2 "no step 5 (it has steps 0..1)" -- "$FS" render "$S/steps.pvd@5" "$S/x.png"
"$FS" subdivide --scheme catmull-clark --levels 2 data/cross_quad.off "$S/cube.vtm" 2>/dev/null || fail "subdivide"
"$FS" render "$S/cube.vtm@0" "$S/cube.vtm" "$S/vtm.png" --control-level 0 --width 300 --height 300 || fail ".vtm"
expect_error 2 "no level 7" -- "$FS" render "$S/cube.vtm@7" "$S/x.png"
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nl 1 2 3 4\n' > "$S/curve.obj"
"$FS" render "$S/curve.obj" "$S/curve.png" --width 300 --height 300 || fail "a curve"
$PY - "$S/curve.png" <<'PYEOF'
import sys
import matplotlib.image as mpimg
img = mpimg.imread(sys.argv[1])[:, :, :3]
assert (img.min(axis=2) < 0.8).mean() > 0.01, "the curve's tube is not drawn"
PYEOF
"$FS" run configs/demo.yaml --out "$S/run" 2>"$S/run.log" || { cat "$S/run.log" >&2; fail "run"; }
expect_error 2 "holds 3 runs; name one with --run ID" -- "$FS" render "$S/run" "$S/x.png"
id=$(sed -n 2p "$S/run/runs.csv" | cut -d, -f1)
"$FS" render "$S/run" "$S/final.png" --run "$id" --array displacement --width 320 --height 240 --title "demo" \
  --label "run $id" --rest data/cow.off 2>"$S/log" || { cat "$S/log" >&2; fail "render of a run"; }
# Two runs of a sweep without --label: labelled by their swept parameters (a label strip).
id2=$(sed -n 3p "$S/run/runs.csv" | cut -d, -f1)
"$FS" render "$S/run@$id" "$S/run@$id2" "$S/sweep.png" --width 300 --height 200 2>/dev/null || fail "two runs"
$PY - "$S/sweep.png" <<'PYEOF'
import sys
import matplotlib.image as mpimg
img = mpimg.imread(sys.argv[1])
assert img.shape[:2] == (240, 600), f"no label strip above the panels: {img.shape}"
assert (img[:40, :, :3].min(axis=2) < 0.5).mean() > 0.005, "the label strip is empty"
PYEOF
# The run wrote where its constraints are; a render draws them (its handle red) unless told not to.
[ -s "$S/run/vtk/${id}_constraints.vtp" ] || fail "the run wrote no constraints overlay"
"$FS" render "$S/run@$id" "$S/with.png" --view front --width 400 --height 300 2>/dev/null || fail "render with overlays"
"$FS" render "$S/run@$id" "$S/without.png" --view front --width 400 --height 300 --no-overlays 2>/dev/null ||
  fail "render without overlays"
$PY - "$S/with.png" "$S/without.png" <<'PYEOF'
import sys
import matplotlib.image as mpimg
red = lambda f: (lambda i: ((i[:, :, 0] > 0.6) & (i[:, :, 1] < 0.3) & (i[:, :, 2] < 0.3)).sum())(mpimg.imread(f)[:, :, :3])
assert red(sys.argv[1]) > 20 and red(sys.argv[2]) == 0, (red(sys.argv[1]), red(sys.argv[2]))
PYEOF
# Focused on the constraints: the handle sits in the middle of the picture.
"$FS" render "$S/run@$id" "$S/focus.png" --focus-constraints --view front --width 400 --height 300 2>/dev/null ||
  fail "render focused on the constraints"
$PY - "$S/focus.png" <<'PYEOF'
import sys
import numpy as np
import matplotlib.image as mpimg
img = mpimg.imread(sys.argv[1])[:, :, :3]
red = np.argwhere((img[:, :, 0] > 0.6) & (img[:, :, 1] < 0.3) & (img[:, :, 2] < 0.3))
assert len(red) > 50, len(red)
r, c = red.mean(axis=0)
assert abs(r / img.shape[0] - 0.5) < 0.2 and abs(c / img.shape[1] - 0.5) < 0.2, (r, c, img.shape)
PYEOF
expect_error 2 "give one" -- "$FS" render "$S/run@$id" "$S/x.png" --focus-constraints --focus 0 0 0
expect_error 2 "no run 'nope'" -- "$FS" render "$S/run@nope" "$S/x.png"
expect_error 2 "available: constrained, displacement, displacement_norm" -- \
  "$FS" render "$S/run@$id" "$S/x.png" --array curvature
expect_error 2 "one component; --component x needs a vector array" -- \
  "$FS" render "$S/run@$id" "$S/x.png" --array displacement_norm --component x
expect_error 2 "1 --label for 2 inputs" -- "$FS" render "$S/run@$id" "$S/run@$id" "$S/x.png" --label one
expect_error 2 "must end in .png" -- "$FS" render "$S/run@$id" "$S/x.jpg"
expect_error 2 "give --array" -- "$FS" render "$S/run@$id" "$S/x.png" --component normal
expect_error 2 "panel 1 shows nothing" -- "$FS" render "$S/run@$id" "$S/x.png" --focus 50 50 50 --width 200 --height 150
expect_error 2 "the output folder .*/nowhere does not exist" -- "$FS" render "$S/run@$id" "$S/nowhere/x.png"
! grep -q "ERR\|disk space" "$SCRATCH/stderr.txt" || fail "VTK's messages leaked"
expect_error 2 "'@0' and --block 1 choose differently" -- "$FS" render "$S/cube.vtm@0" "$S/x.png" --block 1
expect_error 2 "not a result folder (no runs.csv" -- "$FS" render configs "$S/x.png"
expect_error 2 "above 67108864 pixels" -- "$FS" render "$S/run@$id" "$S/run@$id" "$S/x.png" --width 8192 --height 8192
[ ! -e "$S/x.png" ] || fail "a failed render left a file"
echo "render: ok"
