source "$(dirname "$0")/lib.sh"
command -v xvfb-run >/dev/null || { echo "render: xvfb-run missing (Debian package xvfb)"; exit 1; }
"$FS" run configs/demo.yaml --out "$SCRATCH/run" 2>"$SCRATCH/run.log" || { cat "$SCRATCH/run.log" >&2; fail "run"; }
"$FS" render "$SCRATCH/run" "$SCRATCH/final.png" --array displacement_norm --width 320 --height 240 2>"$SCRATCH/render.log" || { cat "$SCRATCH/render.log" >&2; fail "render"; }
$PY - "$SCRATCH/final.png" <<'PYEOF'
import sys
import matplotlib.image as mpimg
img = mpimg.imread(sys.argv[1])
assert img.shape[:2] == (240, 320), img.shape
# Not blank: the coloured cow covers a good part of the white background.
coloured = (abs(img[:, :, 0] - img[:, :, 2]) > 0.2).mean()
assert coloured > 0.05, coloured
PYEOF
expect_error 2 "available: constrained, displacement, displacement_norm" -- \
  "$FS" render "$SCRATCH/run" "$SCRATCH/x.png" --array curvature
[ ! -e "$SCRATCH/x.png" ] || fail "failed render left a file"
echo "render: ok"
