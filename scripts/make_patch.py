#!/usr/bin/env python3
"""Writes data/ks_patch.off: a gently curved triangulated sheet (z = 0.12 (x^2 - 0.5 y^2) over
[-1, 1]^2, 12 x 12 cells, alternating diagonals) - the smooth patch the Khodakovsky-Schroder
figures draw their feature lines on."""
import sys

n = 12
out = sys.argv[1] if len(sys.argv) > 1 else "data/ks_patch.off"
verts, faces = [], []
for j in range(n + 1):
    for i in range(n + 1):
        x, y = -1 + 2 * i / n, -1 + 2 * j / n
        verts.append((x, y, 0.12 * (x * x - 0.5 * y * y)))
for j in range(n):
    for i in range(n):
        a = j * (n + 1) + i
        b, c, d = a + 1, a + n + 1, a + n + 2
        faces += [(a, b, d), (a, d, c)] if (i + j) % 2 == 0 else [(a, b, c), (b, d, c)]
with open(out, "w") as f:
    f.write(f"OFF\n{len(verts)} {len(faces)} 0\n")
    f.writelines(f"{x:.9g} {y:.9g} {z:.9g}\n" for x, y, z in verts)
    f.writelines(f"3 {a} {b} {c}\n" for a, b, c in faces)
