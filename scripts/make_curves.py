#!/usr/bin/python3
"""Writes the bundled curves of data/curves (deterministic; rerun to regenerate).

wave129.obj   open planar curve, 129 = 2^7 + 1 points: a long wave with a finer ripple
              (the kind of curve of Sauvage et al.'s Figures 1 and 4).
ring128.obj   closed space curve, 128 = 2^5 * 4 points: a circle with a vertical wave.
helix257.obj  open space curve, 257 = 2^8 + 1 points: two turns of a helix.
"""
import math
import pathlib

OUT = pathlib.Path(__file__).resolve().parent.parent / "data" / "curves"


def write(name, pts, closed, comment):
    lines = [f"# {comment}"]
    lines += [f"v {x:.12g} {y:.12g} {z:.12g}" for x, y, z in pts]
    idx = list(range(1, len(pts) + 1)) + ([1] if closed else [])
    lines.append("l " + " ".join(map(str, idx)))
    (OUT / name).write_text("\n".join(lines) + "\n")


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    n = 129
    wave = []
    for i in range(n):
        t = i / (n - 1)
        wave.append((2 * t, 0.12 * math.sin(2 * math.pi * t) + 0.015 * math.sin(14 * math.pi * t), 0.0))
    write("wave129.obj", wave, False, "open planar wave, 129 points (scripts/make_curves.py)")
    m = 128
    ring = [(math.cos(2 * math.pi * i / m), math.sin(2 * math.pi * i / m), 0.2 * math.sin(6 * math.pi * i / m))
            for i in range(m)]
    write("ring128.obj", ring, True, "closed space curve, 128 points (scripts/make_curves.py)")
    k = 257
    helix = [(math.cos(4 * math.pi * i / (k - 1)), math.sin(4 * math.pi * i / (k - 1)), 1.5 * i / (k - 1))
             for i in range(k)]
    write("helix257.obj", helix, False, "open helix, 257 points (scripts/make_curves.py)")


if __name__ == "__main__":
    main()
