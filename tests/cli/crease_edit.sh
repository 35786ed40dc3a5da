# configs/boier-martin/fandisk_creases.yaml (smoke size): fandisk edited with creases marked by
# input.crease_angle, and the same edit without. In the edited finest level, the dihedral
# angles across the crease edges (final .obj files keep them as `t crease` tags) must stay
# far above the surface's elsewhere, and well above the same edges' in the uncreased edit.
source "$(dirname "$0")/lib.sh"
"$FS" run configs/boier-martin/fandisk_creases.yaml --smoke --out "$SCRATCH/fan" > /dev/null 2>"$SCRATCH/err.txt" ||
  { cat "$SCRATCH/err.txt" >&2; fail "the fandisk edit did not run"; }
$PY - "$SCRATCH/fan" <<'PYEOF'
import csv, glob, math, os, sys
out = sys.argv[1]
rows = list(csv.DictReader(open(os.path.join(out, "runs.csv"))))
assert len(rows) == 2, f"{len(rows)} runs"
for r in rows:
    assert r["termination"] == "converged", r["termination"]
    assert float(r["constraint_violation"]) < 1e-8, r["constraint_violation"]

def load(path):
    V, F, sharp = [], [], set()
    for line in open(path):
        t = line.split()
        if not t: continue
        if t[0] == "v": V.append(tuple(map(float, t[1:4])))
        elif t[0] == "f": F.append([int(x.split("/")[0]) - 1 for x in t[1:]])
        elif t[0] == "t" and t[1] == "crease": sharp.add(frozenset((int(t[3]), int(t[4]))))
    return V, F, sharp

def dihedrals(V, F):
    def normal(f):
        a, b, c = (V[i] for i in f[:3])
        u = [b[k] - a[k] for k in range(3)]; w = [c[k] - a[k] for k in range(3)]
        n = [u[1]*w[2] - u[2]*w[1], u[2]*w[0] - u[0]*w[2], u[0]*w[1] - u[1]*w[0]]
        l = math.sqrt(sum(x * x for x in n)); return [x / l for x in n]
    faces = {}
    for fi, f in enumerate(F):
        for i in range(len(f)): faces.setdefault(frozenset((f[i], f[(i + 1) % len(f)])), []).append(fi)
    out = {}
    for e, fs in faces.items():
        if len(fs) != 2: continue
        a, b = normal(F[fs[0]]), normal(F[fs[1]])
        out[e] = math.degrees(math.acos(max(-1.0, min(1.0, sum(x * y for x, y in zip(a, b))))))
    return out

meshes = [load(p) for p in sorted(glob.glob(os.path.join(out, "**", "*.obj"), recursive=True))]
creased = [m for m in meshes if m[2]]
plain = [m for m in meshes if not m[2]]
assert len(creased) == 1 and len(plain) == 1, f"{len(creased)} creased, {len(plain)} plain final meshes"
(Vc, Fc, sharp), (Vp, Fp, _) = creased[0], plain[0]
assert len(Fc) == len(Fp) and len(sharp) > 100, (len(Fc), len(Fp), len(sharp))
dc, dp = dihedrals(Vc, Fc), dihedrals(Vp, Fp)
median = lambda xs: sorted(xs)[len(xs) // 2]
on_crease = median([dc[e] for e in sharp if e in dc])
elsewhere = median([a for e, a in dc.items() if e not in sharp])
uncreased = median([dp[e] for e in sharp if e in dp])
print(f"median dihedral: crease edges {on_crease:.2f} deg, other edges {elsewhere:.2f} deg, "
      f"the crease edges without creases {uncreased:.2f} deg")
assert on_crease > 10 * elsewhere, "the creases are not sharper than the surface"
assert on_crease > 1.5 * uncreased, "the creases are no sharper than without them"
PYEOF
echo "crease_edit: ok"
