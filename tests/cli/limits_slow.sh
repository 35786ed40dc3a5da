# The heavy documented limits at the limit itself (label slow: `make test-all`, not CI's
# `make test`): a B-spline sheet of the largest base grid solves; a mesh file of 2 GiB is read.
source "$(dirname "$0")/lib.sh"
cat > "$SCRATCH/sheet_max.yaml" <<'YAML'
name: sheet_max
sheets:
  - {name: sheet, spans: [512, 512], size: [1, 1]}
energy: {alpha: 0.01, beta: 1}
constraints:
  - {type: point, uv: [0.05, 0.05], by: [0, 0, 0]}
  - {type: point, uv: [0.95, 0.05], by: [0, 0, 0]}
  - {type: point, uv: [0.05, 0.95], by: [0, 0, 0]}
  - {type: point, uv: [0.95, 0.95], by: [0, 0, 0]}
  - {type: point, uv: [0.75, 0.7], by: [0, 0, 0.1]}
solver: {type: kkt}
output: {samples_per_span: 1, vtk: none}
YAML
"$FS" run "$SCRATCH/sheet_max.yaml" --out "$SCRATCH/sheet_max" 2>"$SCRATCH/err.txt" || { cat "$SCRATCH/err.txt"; fail "a sheet of 512 x 512 spans"; }
grep -q ",converged," "$SCRATCH/sheet_max/runs.csv" || fail "the largest sheet did not converge"
# A mesh file of 2 GiB (a triangulated grid, padded by a comment to exactly the limit) is read.
$PY - "$SCRATCH/big.obj" <<'PYEOF'
import sys
n, limit = 2900, 2**31  # 8.4M vertices, 16.8M triangles: about 0.6 GB of text, padded
with open(sys.argv[1], "w") as f:
    for j in range(n):
        f.write("".join(f"v {i} {j} 0\n" for i in range(n)))
    for j in range(n - 1):
        f.write("".join(f"f {j*n+i+1} {j*n+i+2} {(j+1)*n+i+2}\nf {j*n+i+1} {(j+1)*n+i+2} {(j+1)*n+i+1}\n" for i in range(n - 1)))
    size = f.tell()
    f.write("#" + "x" * (limit - size - 2) + "\n")
PYEOF
[ "$(stat -c %s "$SCRATCH/big.obj")" -eq 2147483648 ] || fail "the padded mesh is not 2 GiB"
"$FS" info "$SCRATCH/big.obj" > "$SCRATCH/info.txt" 2>"$SCRATCH/err.txt" || { cat "$SCRATCH/err.txt"; fail "a 2 GiB mesh file"; }
grep -q "8410000" "$SCRATCH/info.txt" || fail "the 2 GiB mesh's vertex count: $(head -3 "$SCRATCH/info.txt")"
rm -f "$SCRATCH/big.obj"
echo "limits_slow: ok"
