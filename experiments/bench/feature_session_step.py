"""Region steps of fairshape.FeatureSession (Khodakovsky & Schröder §2.6) against the session's set-up.

  PYTHONPATH=build/python python3 experiments/bench/feature_session_step.py [homer|helmet|all] [--repeat N]

helmet: configs/khodakovsky-schroder/fig17_study.yaml as written (the helmet at 4 levels, 14
features placed by geodesics, sections and a file), the largest feature config the tests run;
then a groove of world points added on level 1 (across a badge) and moved, and a rib re-parameterized.
homer: configs/khodakovsky-schroder/adaptive_homer_level2.yaml evaluated uniformly (Homer at 4
levels: 1,261,570 finest vertices): its ridge between the centres of base faces 3726 and 5117,
given as world points, on level 2 (the config's) and on level 4 (the finest), each moved by a
tenth of its radius and raised. Prints one line per step: wall time of the Python call, solve_s
(the evaluation), check_s (vertices moved, folds), vertices recomputed, and the set-up time.
"""
import argparse
import time

import numpy as np
import yaml

import fairshape

KS = "configs/khodakovsky-schroder/"


def config_of(path):
    c = yaml.safe_load(open(path))
    for k in ("smoke", "adaptive", "output", "sweep", "defaults"):
        c.pop(k, None)
    return c


def timed(what, call, repeat):
    best = None
    for _ in range(repeat):
        t = time.perf_counter()
        step = call()
        wall = time.perf_counter() - t
        if best is None or wall < best[0]:
            best = (wall, step)
    wall, step = best
    print(f"  {what:<44} {wall * 1e3:9.1f} ms  solve {step['solve_s'] * 1e3:8.1f} ms  check {step['check_s'] * 1e3:7.1f} ms"
          f"  place {step['place_s'] * 1e3:6.1f} ms  {step['evaluation']:>6}  recomputed {step['vertices_recomputed']:>9,}"
          f"  moved {step['vertices_changed']:>7,}  {step['termination']}")
    return step


def setup(what, **config):
    t = time.perf_counter()
    s = fairshape.FeatureSession(**config)
    wall = time.perf_counter() - t
    first = s.first_step
    n = s.positions().shape[0]
    print(f"{what}: {n:,} finest vertices; set-up {wall:.2f} s (first evaluation {first['solve_s']:.2f} s, "
          f"{first['vertices_recomputed']:,} vertices)")
    return s


def helmet(repeat):
    c = config_of(KS + "fig17_study.yaml")
    s = setup("fig17_study (helmet, 4 levels, 14 features)", **c)
    timed("set rib_mid height 0.012 -> 0.014 (level 1)", lambda: s.set("rib_mid", height=0.014), 1)
    timed("set rib_mid height back", lambda: s.set("rib_mid", height=0.012), 1)
    s.add(name="dot", level=1, radius=0.04, height=-0.008, max_distance=0.05,
          points=[[0.1700, -0.3171, -0.2073], [0.2415, -0.3017, -0.2158]])
    sign = [1]

    def move():
        sign[0] = -sign[0]
        return s.move("dot", by=[0.004 * sign[0], 0, 0])

    timed(f"move a level-1 groove by 0.004 (best of {repeat})", move, repeat)


def homer_points():
    lines = [l.split() for l in open("data/homer.off") if l.strip() and not l.startswith("#")]
    nv, nf = int(lines[1][0]), int(lines[1][1])
    V = np.array([[float(x) for x in l[:3]] for l in lines[2:2 + nv]])
    F = [list(map(int, l[1:4])) for l in lines[2 + nv:2 + nv + nf]]
    return [V[F[3726]].mean(axis=0).tolist(), V[F[5117]].mean(axis=0).tolist()]


def homer(repeat):
    c = config_of(KS + "adaptive_homer_level2.yaml")
    points = homer_points()
    for level, scale in ((2, 1.0), (4, 0.25)):
        f = dict(c["features"][0])
        f.pop("surface_points")
        d = dict(c["feature_defaults"], radius=c["feature_defaults"]["radius"] * scale,
                 height=c["feature_defaults"]["height"] * scale)
        f.update(level=level, points=points, max_distance=0.05)
        s = setup(f"adaptive_homer_level2, uniform (Homer, 4 levels), ridge on level {level}",
                  input=c["input"], feature_defaults=d, features=[f], implementation=c.get("implementation", "optimized"))
        r = d["radius"]
        sign = [1]

        def move():
            sign[0] = -sign[0]
            return s.move("ridge", by=[0.1 * r * sign[0], 0, 0])

        timed(f"move the ridge by r/10 (best of {repeat})", move, repeat)
        timed("raise the ridge by 10 %", lambda: s.set("ridge", height=d["height"] * 1.1), 1)
        del s


def main():
    p = argparse.ArgumentParser()
    p.add_argument("which", nargs="?", default="all", choices=["homer", "helmet", "all"])
    p.add_argument("--repeat", type=int, default=3)
    a = p.parse_args()
    if a.which in ("helmet", "all"):
        helmet(a.repeat)
    if a.which in ("homer", "all"):
        homer(a.repeat)


if __name__ == "__main__":
    main()
