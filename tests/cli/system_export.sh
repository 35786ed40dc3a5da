# output.system: the Figure 2 edit at level 1 in paper mode writes its problem
# as Matrix Market; SciPy solves the written reduced system and must get the run's own answer
# (final mesh − the subdivided rest), the constrained rows hold (A D = C), and every level's
# prolongation maps the level below onto the next. Regions of influence refuse the key by name.
source "$(dirname "$0")/lib.sh"
S=$(cd "$SCRATCH" && pwd)
C=configs/boier-martin/solvers.yaml
"$FS" run $C --out "$S/run" --set 'sweep.input.levels=[1]' --set 'sweep.solver.type=[cholesky]' \
  --set output.system=true --set output.final_mesh=true >"$S/run.log" 2>&1 || { cat "$S/run.log" >&2; fail "the run failed"; }
"$FS" subdivide data/cow.off "$S/rest.obj" --scheme catmull-clark --levels 1 >/dev/null || fail "subdivide"
"$FS" convert data/cow.off "$S/rest0.obj" >/dev/null || fail "convert"
$PY - "$S" <<'PYEOF'
import csv, glob, os, sys
import numpy as np
import scipy.io, scipy.sparse.linalg
d = sys.argv[1]
row = list(csv.DictReader(open(f"{d}/run/runs.csv")))[0]
assert row["termination"] == "converged", row
sysdir = f"{d}/run/system/{row['run_id']}"
files = sorted(os.path.basename(f) for f in glob.glob(sysdir + "/*"))
for need in ("H.mtx", "g.mtx", "A.mtx", "C.mtx", "P1.mtx", "A_free.mtx", "b_free.mtx", "free.txt", "constrained.txt",
             "D_constrained.mtx", "README.txt"):
    assert need in files, (need, files)
def obj(path):
    return np.array([[float(t) for t in l.split()[1:4]] for l in open(path) if l.startswith("v ")])
delta = obj(f"{d}/run/final.obj") - obj(f"{d}/rest.obj")  # one run: final.obj
H = scipy.io.mmread(f"{sysdir}/H.mtx").tocsc()
assert H.shape == (len(delta), len(delta)), (H.shape, delta.shape)
A_free = scipy.io.mmread(f"{sysdir}/A_free.mtx").tocsc()
b_free = scipy.io.mmread(f"{sysdir}/b_free.mtx")
free = np.loadtxt(f"{sysdir}/free.txt", dtype=int)
constrained = np.loadtxt(f"{sysdir}/constrained.txt", dtype=int)
assert len(free) + len(constrained) == len(delta) and len(np.intersect1d(free, constrained)) == 0
x = scipy.sparse.linalg.spsolve(A_free, b_free)
scale = np.abs(delta).max()
assert np.abs(x - delta[free]).max() < 1e-6 * scale, np.abs(x - delta[free]).max() / scale
assert np.abs(scipy.io.mmread(f"{sysdir}/D_constrained.mtx") - delta[constrained]).max() < 1e-6 * scale
A = scipy.io.mmread(f"{sysdir}/A.mtx").tocsr()
C = scipy.io.mmread(f"{sysdir}/C.mtx")
assert np.abs(A @ delta - C).max() < 1e-6 * scale
P1 = scipy.io.mmread(f"{sysdir}/P1.mtx").tocsr()
assert np.abs(P1 @ obj(f"{d}/rest0.obj") - obj(f"{d}/rest.obj")).max() < 1e-9
print(f"system_export: {len(free)} free + {len(constrained)} constrained; the written system gives the run's answer")
PYEOF
# A regional edit solves one system per pass: refused, naming the key.
rc=0
"$FS" run configs/smoke/cow_nose_pull.yaml --out "$S/regional" --set output.system=true \
  --set 'constraints=[{type: fixed, region: {axis: x, from: 0.0, to: 0.3}}, {type: position, nearest: [0.5, 0.0, 0.0], offset: [0.0, 0.05, 0.0], influence_level: 0}]' \
  >"$S/regional.log" 2>&1 || rc=$?
[ "$rc" -ne 0 ] || fail "output.system with a region of influence: exit 0"
grep -q "output.system" "$S/regional.log" "$S/regional/runs.csv" 2>/dev/null || { cat "$S/regional.log" >&2; fail "the refusal does not name output.system"; }
echo "system_export: ok"
