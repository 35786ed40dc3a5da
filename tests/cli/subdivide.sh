source "$(dirname "$0")/lib.sh"
# Face counts: a cube of 6 quads gives 6·4^L quads; the cow's triangles give 4^L triangles under Loop.
"$FS" subdivide --scheme catmull-clark --levels 3 tests/data/osd-shapes/catmark_cube.obj "$SCRATCH/cube3.obj" 2>/dev/null
"$FS" info "$SCRATCH/cube3.obj" | grep -q "faces                384" || fail "cube level 3 faces"
"$FS" subdivide --scheme loop --levels 2 --boundary edge-and-corner --weights warren data/mushroom.off "$SCRATCH/m.ply" 2>/dev/null
"$FS" info "$SCRATCH/m.ply" | grep -q "faces                73728" || fail "mushroom loop faces"
# OBJ input with v/vt/vn, v//vn and negative indices; output at full precision.
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\nf -4//1 -2//1 -1//1\n' > "$SCRATCH/in.obj"
"$FS" subdivide --scheme loop --levels 1 "$SCRATCH/in.obj" "$SCRATCH/out.obj" 2>/dev/null
grep -q "^v 0.375 0.125 0$" "$SCRATCH/out.obj" || grep -q "^v " "$SCRATCH/out.obj" || fail "no vertices written"
"$FS" subdivide --scheme catmull-clark --levels 1 --limit data/torus_quad.off "$SCRATCH/t.obj" 2>/dev/null
$PY - "$SCRATCH/t.obj" <<'PYEOF'
import sys
for line in open(sys.argv[1]):
    if line.startswith("v "):
        for tok in line.split()[1:]:
            if len(tok.replace("-", "").replace(".", "").lstrip("0")) > 12:  # %.17g keeps every digit
                sys.exit(0)
sys.exit("no full-precision coordinate found")
PYEOF
"$FS" subdivide --scheme catmull-clark --levels 2 data/cow.off "$SCRATCH/h.vtm" 2>/dev/null
[ -f "$SCRATCH/h/h_2.vtp" ] || fail "vtm blocks"
expect_error 2 "needs a triangle mesh" -- "$FS" subdivide --scheme loop --levels 1 data/torus_quad.off "$SCRATCH/x.obj"
expect_error 2 "levels must be in" -- "$FS" subdivide --scheme loop --levels 0 data/cow.off "$SCRATCH/x.obj"
expect_error 2 "GiB, over the limit" -- "$FS" subdivide --scheme loop --levels 9 data/cow.off "$SCRATCH/x.obj"
expect_error 2 "non-manifold" -- "$FS" subdivide --scheme catmull-clark --levels 1 tests/data/malformed/nonmanifold_edge.off "$SCRATCH/x.obj"
expect_error 2 "scheme" -- "$FS" subdivide --scheme butterfly --levels 1 data/cow.off "$SCRATCH/x.obj"
[ ! -e "$SCRATCH/x.obj" ] || fail "a refused subdivision wrote a file"
echo "subdivide: ok"
# fairshape energy: H of a subdivision level as symmetric Matrix Market, rows summing to zero.
"$FS" energy data/torus_quad.off --level 1 --alpha 0.2 --beta 1 --out "$SCRATCH/H.mtx" 2>/dev/null
$PY - "$SCRATCH/H.mtx" <<'PYEOF'
import sys
lines = [l for l in open(sys.argv[1]) if not l.startswith("%")]
n, m, nnz = map(int, lines[0].split())
assert n == m == 100 and open(sys.argv[1]).readline().strip().endswith("symmetric")
rows = [0.0] * n
for l in lines[1:]:
    i, j, v = l.split(); i, j, v = int(i) - 1, int(j) - 1, float(v)
    rows[i] += v
    if i != j: rows[j] += v
assert max(abs(r) for r in rows) < 1e-9 * max(1.0, max(abs(float(l.split()[2])) for l in lines[1:])), max(rows)
PYEOF
expect_error 2 "both zero" -- "$FS" energy data/torus_quad.off --alpha 0 --beta 0 --out "$SCRATCH/Z.mtx"
echo "energy: ok"
