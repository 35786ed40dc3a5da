#!/usr/bin/python3
"""The slowest error mode of a two-grid cycle on a run's reduced system, and where it lives.

Reads the system a surface-edit run wrote with `output.system: true` (A_free, the hierarchy's
last prolongation, the free vertex ids) and the edit level's mesh (`fairshape subdivide`), builds
the two-grid the multigrid solver uses without its patch smoother — symmetric Gauss-Seidel
(`--sweeps` per side), the nested coarse space (coarse vertices whose own fine vertex is free),
an exact coarse solve of PᵀAP — and runs power iteration on its error propagation. Prints the
A-norm contraction per cycle and where the mode's largest entries are: valences, position in the
bounding box, distance to the pinned vertices. Writes the mode per vertex (`--out`, .npy).

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


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("system_dir")
    ap.add_argument("mesh", help="the edit level's mesh, vertex ids as the hierarchy's (fairshape subdivide)")
    ap.add_argument("--level", type=int, required=True, help="the edit level (P<level>.mtx is its prolongation)")
    ap.add_argument("--sweeps", type=int, default=2)
    ap.add_argument("--iterations", type=int, default=60)
    ap.add_argument("--out", default="")
    ap.add_argument("--patch-vertex", type=int, default=-1,
                    help="also solve exactly on the free vertices within --rings mesh rings of this vertex (a test)")
    ap.add_argument("--rings", type=int, default=2)
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

    def schwarz(e):
        if patch is not None:
            e = e.copy()
            e[patch] -= patch_solve.solve((A @ e)[patch])
        return e

    def cycle(e):  # the error propagation of one symmetric two-grid cycle (zero right-hand side)
        for _ in range(a.sweeps):
            e = e - lower.solve(A @ e)
        e = schwarz(e)
        e = e - P @ coarse.solve(P.T @ (A @ e))
        e = schwarz(e)
        for _ in range(a.sweeps):
            e = e - upper.solve(A @ e)
        return e

    e = np.random.default_rng(1).standard_normal(A.shape[0])
    e /= np.sqrt(e @ (A @ e))
    for _ in range(a.iterations):
        e = cycle(e)
        rho = np.sqrt(e @ (A @ e))
        e /= rho
    print(f"A-norm contraction per two-grid cycle after {a.iterations} power steps: {rho:.4f}")
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
