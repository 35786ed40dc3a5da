#!/usr/bin/python3
"""The slowest error mode of a two-grid cycle on a run's reduced system, and where it lives.

Reads the system a surface-edit run wrote with `output.system: true` (A_free, the hierarchy's
last prolongation, the free vertex ids) and the edit level's mesh (`fairshape subdivide`), builds
the two-grid the multigrid solver uses without its patch smoother — symmetric Gauss-Seidel
(`--sweeps` per side), the nested coarse space (coarse vertices whose own fine vertex is free),
an exact coarse solve of PᵀAP — and runs block subspace iteration on its error propagation.
Prints the top --modes eigenvalues (A-norm contractions per cycle) and where the slowest mode's
largest entries are: valences, position in the bounding box, distance to the pinned vertices.
Writes the mode per vertex (`--out`, .npy). `--stiff-stars R` adds the solver's stiff-star
patches (multigrid.stiff_stars: exact star solves where diag(A)·h⁴ > R × its median, one
multiplicative pass after the forward sweeps and before the backward ones).

  scripts/two_grid_slowest_mode.py RUN/system/<id> level4.obj --level 4 --out mode.npy
"""
import argparse
import os

import numpy as np
import scipy.io as io
import scipy.sparse as sp
import scipy.sparse.linalg as sla
from scipy.spatial import cKDTree


def symmetric_from_lower(path):
    L = sp.tril(io.mmread(path).tocsr())
    return (L + sp.tril(L, -1).T).tocsr()


def read_obj(path):
    V, F = [], []
    for line in open(path):
        if line.startswith("v "):
            V.append([float(t) for t in line.split()[1:4]])
        elif line.startswith("f "):
            F.append([int(t.split("/")[0]) - 1 for t in line.split()[1:]])
    return np.array(V), F


def stiff_star_passes(A, V, F, free, ratio):
    """The stiff-star patches of multigrid.cpp as one sparse block-inverse matrix per colour
    (patches of a colour neither share nor couple unknowns, so one product is their sequential
    pass)."""
    slot = -np.ones(len(V), int)
    slot[free] = np.arange(len(free))
    star = [{v} for v in range(len(V))]
    for f in F:
        for v in f:
            star[v].update(f)
    size2 = np.array([np.mean([np.sum((V[u] - V[v]) ** 2) for u in star[v] if u != v]) for v in free])
    stiffness = A.diagonal() * size2 ** 2
    chosen = np.flatnonzero(stiffness > ratio * np.median(stiffness))
    patches = [np.array(sorted(slot[u] for u in star[free[i]] if slot[u] >= 0)) for i in chosen]
    owners = [[] for _ in range(A.shape[0])]
    for k, p in enumerate(patches):
        for i in p:
            owners[i].append(k)
    coupled = (A != 0).tocsr()
    colour = -np.ones(len(patches), int)
    for k, p in enumerate(patches):
        taken = {colour[q] for i in np.unique(coupled[p].indices) for q in owners[i] if colour[q] >= 0}
        colour[k] = next(c for c in range(len(patches) + 1) if c not in taken)
    passes = []
    for c in range(colour.max() + 1 if len(patches) else 0):
        rows, cols, vals = [], [], []
        for k in np.flatnonzero(colour == c):
            p = patches[k]
            rows.append(np.repeat(p, len(p)))
            cols.append(np.tile(p, len(p)))
            vals.append(np.linalg.inv(A[p][:, p].toarray()).ravel())
        passes.append(sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=A.shape))
    print(f"stiff stars: {len(patches)} of {A.shape[0]} free vertices, {len(passes)} colours")
    return passes


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("system_dir")
    ap.add_argument("mesh", help="the edit level's mesh, vertex ids as the hierarchy's (fairshape subdivide)")
    ap.add_argument("--level", type=int, required=True, help="the edit level (P<level>.mtx is its prolongation)")
    ap.add_argument("--sweeps", type=int, default=2)
    ap.add_argument("--iterations", type=int, default=40)
    ap.add_argument("--modes", type=int, default=8, help="block size of the subspace iteration")
    ap.add_argument("--out", default="")
    ap.add_argument("--patch-vertex", type=int, default=-1,
                    help="also solve exactly on the free vertices within --rings mesh rings of this vertex (a test)")
    ap.add_argument("--rings", type=int, default=2)
    ap.add_argument("--stiff-stars", type=float, default=0.0, help="ratio R of the stiff-star patches (0: none)")
    a = ap.parse_args()
    A = symmetric_from_lower(os.path.join(a.system_dir, "A_free.mtx"))
    free = np.loadtxt(os.path.join(a.system_dir, "free.txt"), dtype=int)
    P_full = io.mmread(os.path.join(a.system_dir, f"P{a.level}.mtx")).tocsr()
    P = P_full[free][:, free[free < P_full.shape[1]]].tocsr()
    coarse = sla.splu((P.T @ A @ P).tocsc())
    lower = sla.splu(sp.tril(A).tocsc(), permc_spec="NATURAL", diag_pivot_thresh=0)
    upper = sla.splu(sp.triu(A).tocsc(), permc_spec="NATURAL", diag_pivot_thresh=0)

    V, F = read_obj(a.mesh)
    patch, patch_solve = None, None
    if a.patch_vertex >= 0:
        neighbours = [set() for _ in range(len(V))]
        for f in F:
            for u, v in zip(f, f[1:] + f[:1]):
                neighbours[u].add(v)
                neighbours[v].add(u)
        ring, seen = {a.patch_vertex}, {a.patch_vertex}
        for _ in range(a.rings):
            ring = {w for u in ring for w in neighbours[u]} - seen
            seen |= ring
        slot = -np.ones(len(V), int)
        slot[free] = np.arange(len(free))
        patch = np.array(sorted(slot[v] for v in seen if slot[v] >= 0))
        patch_solve = sla.splu(A[patch][:, patch].tocsc())
        print(f"patch: {len(patch)} free unknowns within {a.rings} rings of vertex {a.patch_vertex}")

    star_passes = stiff_star_passes(A, V, F, free, a.stiff_stars) if a.stiff_stars > 0 else []

    def stars(e, forward):
        for B in (star_passes if forward else star_passes[::-1]):
            e = e - B @ (A @ e)
        return e

    def schwarz(e):
        if patch is not None:
            e = e.copy()
            e[patch] -= patch_solve.solve((A @ e)[patch])
        return e

    def cycle(e):  # the error propagation of one symmetric two-grid cycle (zero right-hand side)
        for _ in range(a.sweeps):
            e = e - lower.solve(A @ e)
        e = stars(schwarz(e), True)
        e = e - P @ coarse.solve(P.T @ (A @ e))
        e = schwarz(stars(e, False))
        for _ in range(a.sweeps):
            e = e - upper.solve(A @ e)
        return e

    # Block subspace iteration with Rayleigh-Ritz in the A inner product (the symmetric cycle's
    # error propagation is A-self-adjoint): a single power iteration converges slowly when the
    # top of the spectrum is a band, and understated level 3's contraction (0.976 vs 0.992).
    X = np.random.default_rng(1).standard_normal((A.shape[0], a.modes))
    for _ in range(a.iterations):
        X = np.column_stack([cycle(X[:, j]) for j in range(a.modes)])
        R = np.linalg.cholesky(X.T @ (A @ X))
        X = np.linalg.solve(R, X.T).T  # A-orthonormal columns
    EX = np.column_stack([cycle(X[:, j]) for j in range(a.modes)])
    M = X.T @ (A @ EX)
    mu, W = np.linalg.eigh((M + M.T) / 2)
    mu, W = mu[::-1], W[:, ::-1]
    print(f"two-grid error propagation, top {a.modes} eigenvalues after {a.iterations} block steps: "
          + " ".join(f"{m:.4f}" for m in mu))
    e = X @ W[:, 0]
    valence = np.zeros(len(V), int)
    for f in F:
        for u, v in zip(f, f[1:] + f[:1]):
            if u < v:
                valence[u] += 1
                valence[v] += 1
    top = np.argsort(-np.abs(e))[: max(1, len(e) // 200)]  # the largest 0.5 %
    lo, hi = V.min(0), V.max(0)
    diag = np.linalg.norm(hi - lo)
    pinned = np.setdiff1d(np.arange(len(V)), free)
    to_pinned = cKDTree(V[pinned]).query(V[free])[0] / diag
    vals, counts = np.unique(valence[free[top]], return_counts=True)
    print("largest 0.5 %: valences", dict(zip(vals.tolist(), counts.tolist())),
          "| share of the mode's squared norm", round(float((e[top] ** 2).sum() / (e ** 2).sum()), 3))
    print("their centre, as a fraction of the bounding box:", np.round((V[free[top]].mean(0) - lo) / (hi - lo), 3))
    print(f"distance to the pinned vertices / bbox diagonal: theirs {np.median(to_pinned[top]):.3f} "
          f"(median), every free vertex's {np.median(to_pinned):.3f}")
    if a.out:
        mode = np.zeros(len(V))
        mode[free] = e
        np.save(a.out, mode)


if __name__ == "__main__":
    main()
