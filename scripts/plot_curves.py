#!/usr/bin/python3
"""Figures of Sauvage, Hahmann and Bonneau from `fairshape run configs/sauvage/...` results.

    plot_curves.py fig1 RESULT_DIR OUT.png   β sweep: C_R, edit, C_F for three β values
    plot_curves.py fig3 RESULT_DIR OUT.png   the stages of one editing loop
    plot_curves.py fig4 RESULT_DIR OUT.png   two successive editing loops
    plot_curves.py helix RESULT_DIR OUT.png  a 3-D curve: each edit and its results for every β

Curves come from RESULT_DIR/curves/<run_id>_edit<k>_<stage>.obj; the level-j control polygon
of a lazy-wavelet curve is every 2^(L-j)-th point, so polygons are sampled from the curves.
"""
import csv
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_obj(path):
    pts = [tuple(map(float, l.split()[1:4])) for l in open(path) if l.startswith("v ")]
    return [p[0] for p in pts], [p[1] for p in pts]


def levels_of(n):
    segs, levels = n - 1, 0
    while segs % 2 == 0 and segs // 2 >= 1:
        segs //= 2
        levels += 1
    return levels


def polygon(curve, level):
    xs, ys = curve
    stride = 2 ** (levels_of(len(xs)) - level)
    return xs[::stride], ys[::stride]


def runs(result):
    with open(result / "runs.csv") as f:
        return list(csv.DictReader(f))


def stage(result, run_id, edit, name):
    return read_obj(result / "curves" / f"{run_id}_edit{edit}_{name}.obj")


def config(result):
    import json
    return json.load(open(result / "run.json"))["config"]


def panel(ax, title):
    ax.set_title(title, fontsize=9)
    ax.set_aspect("equal")
    ax.axis("off")


def same_frame(axes, curves):
    """One scale for every panel, so a compressed curve looks compressed."""
    xs = [x for c in curves for x in c[0]]
    ys = [y for c in curves for y in c[1]]
    pad = 0.03 * (max(xs) - min(xs))
    for ax in axes:
        ax.set_xlim(min(xs) - pad, max(xs) + pad)
        ax.set_ylim(min(ys) - pad, max(ys) + pad)


def draw(ax, curve, **kw):
    ax.plot(curve[0], curve[1], **kw)


def draw_polygon(ax, curve, level, color="tab:red"):
    px, py = polygon(curve, level)
    ax.plot(px, py, "-o", color=color, lw=1, ms=3.5)


def mark_moved(ax, before, after, edit, legend=True):
    """The control points an edit moved: hollow red circles where they went, arrows from where
    they were."""
    for k, i in enumerate(moved_fine_indices(len(before[0]), edit)):
        x0, y0, x1, y1 = before[0][i], before[1][i], after[0][i], after[1][i]
        ax.annotate("", xy=(x1, y1), xytext=(x0, y0), arrowprops=dict(arrowstyle="->", color="tab:red", lw=1.3))
        ax.plot([x1], [y1], "o", ms=9, mfc="none", mec="tab:red", mew=2,
                label="moved control point" if legend and k == 0 else None)
    if legend:
        ax.legend(loc="upper right", fontsize=7, frameon=False)


def fig1(result, out):
    rows = [r for r in runs(result) if r.get("optimization.solver.linearized.linearization", "newton") == "newton"]
    picks = [r for r in rows if float(r["optimization.beta"]) in (0.0001, 0.01, 0.5)] or rows[:3]
    first = rows[0]["run_id"]
    ref, att = stage(result, first, 0, "reference"), stage(result, first, 0, "attracting")
    fig, axes = plt.subplots(len(picks) + 2, 1, figsize=(7, 1.5 * (len(picks) + 2)))
    draw(axes[0], ref, color="k", lw=1)
    draw_polygon(axes[0], ref, 0)
    panel(axes[0], "(a) initial curve C_R (129 points) and its level-0 polygon")
    draw(axes[1], att, color="0.5", lw=1)
    draw_polygon(axes[1], att, 0)
    mark_moved(axes[1], ref, att, config(result)["edits"][0])
    panel(axes[1], "(b) level-0 polygon compressed to 70%: attracting curve C_A (gray), 30% too short")
    for k, r in enumerate(picks):
        ax = axes[k + 2]
        draw(ax, att, color="0.7", lw=1)
        draw(ax, stage(result, r["run_id"], 0, "final"), color="k", lw=1)
        panel(ax, f"({chr(99 + k)}) β = {float(r['optimization.beta']):g}: {r['wrinkles']} curvature sign changes, "
                  f"{r['solves']} solves, max length error {float(r['length_error_max']):.1e}")
    same_frame(axes, [ref] + [stage(result, r["run_id"], 0, "final") for r in picks])
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def fig3(result, out):
    cfg = config(result)
    edit = cfg["edits"][0]
    e = int(edit["level"])
    rows = runs(result)
    main = next(r for r in rows if r.get("edits.0.wrinkle_level", str(edit.get("wrinkle_level"))) != "-1")
    plain = next((r for r in rows if r.get("edits.0.wrinkle_level") == "-1"), None)
    w = int(main.get("edits.0.wrinkle_level", edit.get("wrinkle_level")))
    rid = main["run_id"]
    ref, ed, att, fin = (stage(result, rid, 0, s) for s in ("reference", "edited", "attracting", "final"))
    fig, axes = plt.subplots(5, 1, figsize=(7, 8))
    draw(axes[0], ref, color="k", lw=1)
    draw_polygon(axes[0], ref, e)
    panel(axes[0], f"(a) decomposition: C_R and its level-{e} polygon")
    draw(axes[1], ed, color="k", lw=1, ls=":")
    draw_polygon(axes[1], ed, e)
    mark_moved(axes[1], ref, ed, edit)
    panel(axes[1], f"(b) edit at level e = {e}: deformed polygon, C_D dotted (not of the reference length)")
    draw_polygon(axes[2], ed, w, color="0.6")
    draw_polygon(axes[2], att, w + 1, color="tab:blue")
    panel(axes[2], f"(c) level w = {w} of C_D (gray); explicit step: level-{w + 1} polygon with reference edge lengths (blue)")
    draw(axes[3], att, color="k", lw=1)
    panel(axes[3], f"(d) reconstruction: attracting curve C_A, max length error {float(main['attractor_length_error']):.2g}")
    draw(axes[4], att, color="0.7", lw=1)
    draw(axes[4], fin, color="k", lw=1)
    extra = f" (without the explicit step: {plain['solves']})" if plain else ""
    panel(axes[4], f"(e) smoothing by the optimization: C_F, {main['solves']} solves{extra}, "
                   f"length error {float(main['length_error_max']):.0e}")
    same_frame(axes, [ref, ed, att, fin])
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def fig4(result, out):
    cfg = config(result)
    e0, e1 = cfg["edits"][0], cfg["edits"][1]
    rid = runs(result)[0]["run_id"]
    ref = stage(result, rid, 0, "reference")
    first = stage(result, rid, 0, "final")
    ed1 = stage(result, rid, 1, "edited")
    fin = stage(result, rid, 1, "final")
    fig, axes = plt.subplots(4, 1, figsize=(7, 6.5))
    draw(axes[0], ref, color="k", lw=1)
    draw_polygon(axes[0], ref, int(e0["level"]))
    mark_moved(axes[0], ref, stage(result, rid, 0, "edited"), e0)
    panel(axes[0], "(a) initial curve, 129 points, and the first edit")
    draw(axes[1], first, color="k", lw=1)
    panel(axes[1], f"(b) compressed at e = {e0['level']}, wrinkles at w = {e0['wrinkle_level']}: large wrinkles")
    draw(axes[2], ed1, color="k", lw=1, ls=":")
    draw_polygon(axes[2], ed1, int(e1["level"]))
    mark_moved(axes[2], first, ed1, e1)
    panel(axes[2], f"(c) two neighbouring level-{e1['level']} control points pushed together")
    draw(axes[3], first, color="0.7", lw=1)
    draw(axes[3], fin, color="k", lw=1)
    r = runs(result)[0]
    panel(axes[3], f"(d) wrinkles at w = {e1['wrinkle_level']}: small and local, C_F (black) over (b) (gray) "
                   f"(max length error {float(r['length_error_max']):.0e}, {r['solves']} solves in all)")
    same_frame(axes, [ref, first, ed1, fin])
    fig.tight_layout()
    fig.savefig(out, dpi=130)


def read_obj3(path):
    return [tuple(map(float, l.split()[1:4])) for l in open(path) if l.startswith("v ")]


def moved_fine_indices(n_points, edit):
    """Fine-level indices of the control points an edit moved (negative: from the end)."""
    levels = levels_of(n_points)
    stride = 2 ** (levels - int(edit["level"]))
    m = (n_points - 1) // stride + 1
    return [(int(mv["index"]) % m) * stride for mv in edit["moves"]]


def helix(result, out):
    """A 3-D curve: per edit, the edit (C_R, C_D, the level-e polygon, the moved control points
    with arrows from where they were) and the result C_F over C_A for every β of the sweep."""
    cfg = config(result)
    rows = sorted(runs(result), key=lambda r: float(r["optimization.beta"]))
    edits = cfg["edits"]
    fig = plt.figure(figsize=(4.2 * (len(rows) + 1), 4.2 * len(edits)))

    def axes3(k, title):
        ax = fig.add_subplot(len(edits), len(rows) + 1, k, projection="3d")
        ax.set_title(title, fontsize=9)
        ax.view_init(elev=22, azim=-60)
        for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
            axis.set_ticklabels([])
        return ax

    def line(ax, pts, **kw):
        ax.plot([p[0] for p in pts], [p[1] for p in pts], [p[2] for p in pts], **kw)

    with open(result / "steps.csv") as f:
        finals = {(r["run_id"], int(r["edit"])): r for r in csv.DictReader(f) if r["stage"] == "final"}
    everything = [p for r in rows for k in range(len(edits)) for st in ("reference", "edited", "final")
                  for p in read_obj3(result / "curves" / f"{r['run_id']}_edit{k}_{st}.obj")]
    lo = [min(p[c] for p in everything) for c in range(3)]
    hi = [max(p[c] for p in everything) for c in range(3)]
    half = 0.5 * max(h - l for h, l in zip(hi, lo))

    def frame(ax):  # one cube for every panel: equal scales, so shapes compare
        for c, setter in enumerate((ax.set_xlim, ax.set_ylim, ax.set_zlim)):
            mid = 0.5 * (lo[c] + hi[c])
            setter(mid - half, mid + half)
        ax.set_box_aspect((1, 1, 1))

    rid = rows[0]["run_id"]
    for k, edit in enumerate(edits):
        e = int(edit["level"])
        ref = read_obj3(result / "curves" / f"{rid}_edit{k}_reference.obj")
        ed = read_obj3(result / "curves" / f"{rid}_edit{k}_edited.obj")
        stride = 2 ** (levels_of(len(ref)) - e)
        ax = axes3(k * (len(rows) + 1) + 1, f"edit {k}: level e = {e}, wrinkles at w = {edit['wrinkle_level']}")
        line(ax, ref, color="0.6", lw=1, label="C_R (before the edit)")
        line(ax, ed, color="k", lw=1, ls=":", label="C_D (edited, lengths not kept)")
        line(ax, ed[::stride], color="tab:red", lw=1, marker="o", ms=3, label=f"level-{e} control polygon")
        for i in moved_fine_indices(len(ref), edit):
            a, b = ref[i], ed[i]
            ax.quiver(a[0], a[1], a[2], b[0] - a[0], b[1] - a[1], b[2] - a[2], color="tab:red", lw=1.5, arrow_length_ratio=0.15)
            ax.scatter([b[0]], [b[1]], [b[2]], s=60, facecolors="none", edgecolors="tab:red", linewidths=2)
        ax.scatter([], [], s=60, facecolors="none", edgecolors="tab:red", linewidths=2, label="moved control point")
        frame(ax)
        if k == 0:
            ax.legend(loc="upper left", fontsize=7, frameon=False)
        for j, r in enumerate(rows):
            att = read_obj3(result / "curves" / f"{r['run_id']}_edit{k}_attracting.obj")
            fin = read_obj3(result / "curves" / f"{r['run_id']}_edit{k}_final.obj")
            step = finals[(r["run_id"], k)]
            ax = axes3(k * (len(rows) + 1) + j + 2,
                       f"β = {float(r['optimization.beta']):g}: C_F (black), C_A (gray)\n"
                       f"{step['solves']} solves, length error {float(step['length_error_max']):.0e}")
            line(ax, att, color="0.6", lw=1)
            line(ax, fin, color="k", lw=1.2)
            frame(ax)
    states = ";\n".join(f"β = {float(r['optimization.beta']):g} {r['termination']} "
                       f"(smallest reduced Hessian eigenvalue {float(r['min_reduced_hessian_eig']):.1e})" for r in rows)
    fig.suptitle(f"A helix ({len(ref)} points) edited twice, solved by {rows[0]['solver.type']}:\n{states}", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    figures = {"fig1": fig1, "fig3": fig3, "fig4": fig4, "helix": helix}
    if len(sys.argv) != 4 or sys.argv[1] not in figures:
        sys.exit(__doc__)
    pathlib.Path(sys.argv[3]).parent.mkdir(parents=True, exist_ok=True)
    figures[sys.argv[1]](pathlib.Path(sys.argv[2]), sys.argv[3])
