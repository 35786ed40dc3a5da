#!/usr/bin/env python3
"""Feature curves along a mesh: the shortest edge path between vertex pairs (Dijkstra), every
k-th vertex kept, printed as the `points` of a fairshape feature config. With --facing, paths
only use vertices whose normal faces that direction (so the curves are visible from there).
Figure 17's curves: make_feature_paths.py data/knot.off 10 --seed 3 --stride 3 --facing 0 0 1
Reads OFF only; needs no third-party module."""
import argparse
import heapq
import math
import random


def read_off(path):
    tok = open(path).read().split()
    nv, nf = int(tok[1]), int(tok[2])
    i = 4
    V = [tuple(float(t) for t in tok[i + 3 * k:i + 3 * k + 3]) for k in range(nv)]
    i += 3 * nv
    F = []
    for _ in range(nf):
        n = int(tok[i])
        F.append([int(t) for t in tok[i + 1:i + 1 + n]])
        i += 1 + n
    return V, F


def vertex_normals(V, F):
    N = [[0.0, 0.0, 0.0] for _ in V]
    for f in F:
        a, b, c = (V[f[0]], V[f[1]], V[f[2]])
        u = [b[k] - a[k] for k in range(3)]
        w = [c[k] - a[k] for k in range(3)]
        n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
        for v in f:
            for k in range(3):
                N[v][k] += n[k]
    return [[x / (math.sqrt(sum(y * y for y in n)) or 1) for x in n] for n in N]


def shortest_path(V, adj, a, b):
    dist, prev = {a: 0.0}, {}
    heap = [(0.0, a)]
    while heap:
        d, v = heapq.heappop(heap)
        if v == b:
            break
        if d > dist[v]:
            continue
        for w in adj[v]:
            nd = d + math.dist(V[v], V[w])
            if nd < dist.get(w, math.inf):
                dist[w], prev[w] = nd, v
                heapq.heappush(heap, (nd, w))
    path = [b]
    while path[-1] != a:
        path.append(prev[path[-1]])
    return path[::-1], dist[b]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mesh")
    ap.add_argument("count", type=int)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--stride", type=int, default=3)
    ap.add_argument("--min-length", type=float, default=0.35)
    ap.add_argument("--max-length", type=float, default=0.6)
    ap.add_argument("--facing", type=float, nargs=3)
    ap.add_argument("--min-cos", type=float, default=0.3)
    args = ap.parse_args()
    V, F = read_off(args.mesh)
    adj = [set() for _ in V]
    for f in F:
        for k in range(len(f)):
            adj[f[k]].add(f[(k + 1) % len(f)])
            adj[f[(k + 1) % len(f)]].add(f[k])
    allowed = list(range(len(V)))
    if args.facing:
        N = vertex_normals(V, F)
        allowed = [v for v in allowed if sum(N[v][k] * args.facing[k] for k in range(3)) > args.min_cos]
        keep = set(allowed)
        adj = [a & keep if v in keep else set() for v, a in enumerate(adj)]
    rng = random.Random(args.seed)
    made = 0
    while made < args.count:
        a, b = rng.choice(allowed), rng.choice(allowed)
        try:
            path, length = shortest_path(V, adj, a, b)
        except KeyError:  # not connected through allowed vertices
            continue
        if not (args.min_length <= length <= args.max_length):
            continue
        kept = path[::args.stride]
        if kept[-1] != path[-1]:
            kept.append(path[-1])
        pts = ", ".join("[%.5f, %.5f, %.5f]" % V[v] for v in kept)
        print(f"  - {{ name: f{made}, points: [{pts}] }}")
        made += 1


if __name__ == "__main__":
    main()
