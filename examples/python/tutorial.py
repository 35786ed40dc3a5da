"""fairshape from Python: a tutorial in the order a notebook would take it.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/tutorial.py [--out DIR]

(from the repository root; after `make install`, the installed package needs no PYTHONPATH
under /usr/local). About 40 s on 2 cores. Every step checks what it claims, so the script
fails loudly if a result changes (ctest python.tutorial runs it):

1. the demo (configs/demo.yaml, Boier-Martin et al. Figure 2) through fairshape.run, in its
   CI-sized variant (smoke=True: a 200-face remesh of the cow, 2 levels, instead of 600
   faces and 3): the thin plate fairs the cow's details away, the detail-preserving energy
   keeps them (runs.csv's detail_change);
2. the same edit through the bindings: the remeshed hierarchy, constraints from NumPy index
   arrays, the energies by name, the solve and the detail change, equal to step 1's;
3. one small result of each other paper through fairshape.run: Sauvage et al.'s
   length-preserving curve edit (Figure 3), Welch & Witkin's variational sheet (Figure 1),
   Khodakovsky & Schröder's feature curves on a Loop hierarchy (Figure 11);
4. the same papers through their direct bindings, on NumPy arrays: the Figure 3 curve edit
   (fairshape.edit_curve, equal to step 3's final curve), a variational sheet under point and
   curve constraints (fairshape.design_sheet) and a ridge on a Loop hierarchy
   (fairshape.apply_features) with its achieved profile.
Re-running into the same --out replaces its results (force=True).
"""

import argparse
import os
import tempfile

import numpy as np

import fairshape

parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("--out", default=None, help="output folder (default: a new temporary folder)")
out = parser.parse_args().out or tempfile.mkdtemp(prefix="fairshape-tutorial-")
print(f"fairshape {fairshape.__version__}; outputs under {out}")

# --- 1. The demo through fairshape.run ---------------------------------------------------
# The config's sweep zips three runs: the thin plate with the back third fixed, the thin
# plate with everything but the nose's level-1 region of influence fixed, and the
# detail-preserving energy. Both thin plates
# fold the surface where they fair the details away, as the config expects (its `expect` column).
demo = fairshape.run("configs/demo.yaml", out=os.path.join(out, "demo"), smoke=True, force=True)
print(demo[["param.energy", "n_fine", "iterations", "detail_change", "flipped_faces", "termination"]].to_string())
assert (demo["termination"] == demo["expect"].replace("success", "converged")).all()
thin_plate, thin_plate_head, detail_preserving = demo["detail_change"]
assert detail_preserving < 0.5 * min(thin_plate, thin_plate_head), "the details should ride along"

# --- 2. The same edit through the bindings -----------------------------------------------
cow = fairshape.read_mesh("data/cow.off")           # Mesh: cow.V is n×3 float64, cow.F m×3 int32
rest, report = fairshape.remesh(cow, base_faces=200, levels=2)  # what input.remesh_base_faces does
print(f"remeshed: {report['fine_vertices']} vertices at level {rest.levels}, "
      f"Hausdorff {100 * report['hausdorff_relative']:.2f}% of the diagonal")
P = rest.positions()                                 # read-only view of the finest level, no copy
lo, hi = P[:, 0].min(), P[:, 0].max()
back = np.flatnonzero(P[:, 0] <= lo + 0.3 * (hi - lo))          # the config's region {axis: x, to: 0.3}
nose = np.argmin(np.linalg.norm(P - [0.5, 0.0, 0.0], axis=1))   # the config's nearest: [0.5, 0, 0]
constraints = [fairshape.fixed(back), fairshape.position([nose], [0.15, 0.0, 0.08])]
changes = {}
for name, run_row in (("surface_thin_plate", 0), ("detail_preserving", 2)):
    # check=False: the thin plate folds the surface, and the edit says so (`folded`, as the run did)
    # rather than raising; its result is still the thin plate's answer.
    r = fairshape.edit(rest, [fairshape.energy(name, alpha=0.1, beta=1.0)], constraints, solver="cholesky", check=False)
    assert r.flipped_faces == demo["flipped_faces"][run_row] and r.summary.termination == demo["termination"][run_row]
    # runs.csv's detail_change: the edited finest level analysed into a hierarchy again, its
    # local details against the rest shape's.
    reanalysed = fairshape.MultiresSurface.analyze(rest.mesh(0), r.hierarchy.positions(), rest.levels)
    changes[name] = fairshape.relative_detail_change(rest, reanalysed)
    moved = np.linalg.norm(r.delta, axis=1)
    print(f"{name}: {r.summary.termination} ({r.flipped_faces} faces flipped), nose moved {moved[nose]:.3f}, "
          f"detail change {changes[name]:.3f}")
    assert abs(moved[nose] - np.hypot(0.15, 0.08)) < 1e-9 and moved[back].max() < 1e-12
    fairshape.write_mesh(r.hierarchy.mesh(), os.path.join(out, f"cow_{name}.obj"))
# The bindings and the run are one computation: the same remesh, the same solve.
assert abs(changes["surface_thin_plate"] - thin_plate) < 1e-6 * thin_plate
assert abs(changes["detail_preserving"] - detail_preserving) < 1e-6 * detail_preserving

# --- 3. One result of each other paper ----------------------------------------------------
# Sauvage, Hahmann, Bonneau: a multiresolution curve edited with its segment lengths kept.
curve = fairshape.run("configs/sauvage/fig3.yaml", out=os.path.join(out, "sauvage"), smoke=True, force=True)
print(curve[["run_id", "n_points", "length_error_max", "bending_energy", "termination"]].to_string())
assert (curve["termination"] == "converged").all() and (curve["length_error_max"] < 1e-9).all()

# Welch & Witkin: a hierarchical B-spline sheet minimizing thin plate energy under constraints.
sheet = fairshape.run("configs/welch-witkin/fig1.yaml", out=os.path.join(out, "welch-witkin"), smoke=True, force=True)
print(sheet[["run_id", "dofs", "constraint_rows", "constraint_residual", "energy", "termination"]].to_string())
# The constraint rows are met exactly; the curves, constrained in weak (mortar) form, only on
# average (max_constraint_error is their pointwise distance).
assert (sheet["termination"] == "converged").all() and (sheet["constraint_residual"] < 1e-9).all()

# Khodakovsky & Schröder: feature curves drawn on a Loop hierarchy, profiles within tolerance.
features = fairshape.run("configs/khodakovsky-schroder/fig11.yaml", out=os.path.join(out, "khodakovsky-schroder"),
                         smoke=True, force=True)
print(features[["run_id", "features", "n_fine", "vertices_moved", "max_displacement", "termination"]].to_string())
assert (features["termination"] == "converged").all() and (features["vertices_moved"] > 0).all()

# --- 4. The same papers through their direct bindings -------------------------------------
# Figure 3's edit (its first sweep point, wrinkle_level 3) on the curve as an n×2 array.
wave = np.array([[float(t) for t in line.split()[1:3]] for line in open("data/curves/wave129.obj") if line.startswith("v ")])
c = fairshape.Curve(wave)  # 129 points: 7 levels; c.level(2) is the 5-point polygon moved
r = fairshape.edit_curve(c, level=2, indices=[3, 4], offsets=[[-0.06, 0.03], [-0.3, 0.0]], wrinkle_level=3, beta=0.01,
                         solver="trust_region", length_tolerance=1e-12, stationarity_tolerance=1e-8, max_solves=2000)
print(f"edit_curve: {r.summary.termination} after {r.solves} solves, length error {r.length_error_max:.2e}")
run_id = curve.loc[curve["edits.0.wrinkle_level"] == 3, "run_id"].iloc[0]
final = np.array([[float(t) for t in line.split()[1:4]] for line in open(os.path.join(out, "sauvage", "final", f"{run_id}.obj"))
                  if line.startswith("v ")])
assert np.abs(r.points3 - final).max() < 1e-10  # the run's final curve

# A sheet held at its corners, a point lifted and a ridge curve it must follow.
s = fairshape.Sheet(spans=(8, 8), size=(2, 2))
corners = [[0.125, 0.125], [1.875, 0.125], [0.125, 1.875], [1.875, 1.875]]
ridge_uv = [[0.375, 0.5], [1.0, 1.05], [1.625, 0.5]]
ridge = s.trace(ridge_uv, 33) + np.outer(np.sin(np.linspace(0, np.pi, 33)), [0, 0, 0.5])
d = fairshape.design_sheet(s, corners + [[1.0, 1.6]], np.vstack([np.zeros((4, 3)), [0, 0, -0.2]]), relative=True,
                           curves=[(ridge_uv, ridge)], alpha=0.01, solver="kkt")
print(f"design_sheet: {d.summary.termination}, grid {d.grid.shape}, constraint error {d.max_constraint_error:.3g}")
assert d.summary.succeeded and d.constraint_residual < 1e-9

# A ridge on the Loop hierarchy of a patch: the limit surface shows its profile.
patch = fairshape.MultiresSurface(fairshape.read_mesh("data/ks_patch.off"), 4, scheme="loop")  # (3 levels: the finest level misses)
f = fairshape.apply_features(patch, [fairshape.feature([[-0.85, -0.3, 0.0813], [0.0, 0.05, -0.0002], [0.85, 0.3, 0.0813]],
                                                       level=1, name="ridge", radius=0.45, height=0.12, quadratic=True,
                                                       profile_tolerance=0.06)])
ridge = f.features[0]
print(f"apply_features: {f.positions.shape[0]} finest vertices, limit height error {ridge['limit']['height_error']:.2e}")
assert f.within_tolerance and np.abs(f.positions - patch.positions()).max() > 0.1 * 0.12
print("tutorial: ok")
