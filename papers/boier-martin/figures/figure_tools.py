#!/usr/bin/python3
"""Helpers of make_figures.sh for what `fairshape render` does not draw by itself. Each writes
copies of results (.vtp) with their overlays beside them (<stem>_constraints.vtp), which
`fairshape render` draws per panel.

  figure_tools.py error RUN_DIR REF_RUN OUT_DIR RUN...
      OUT_DIR/<RUN>.vtp: the run's result with a point array `error` = |x - x_REF|, the distance
      of every finest vertex to the reference run's answer.
  figure_tools.py rest RESULT.vtp OUT.vtp
      the shape before the edit (points - displacement), its constraints where they started.
  figure_tools.py arc RESULT.vtp OUT.vtp --centre X Y Z --axis X Y Z --radius R --angle DEG [--lift H]
      the result with a rotation drawn into its overlay: its axis, an arc of the angle about it.
  figure_tools.py ladder RUN_DIR RUN OUT_DIR --above X
      OUT_DIR/level<l>.vtp: the ladder's levels (vtk/<RUN>_ladder_level<l>.vtp), each with the
      vertices its propagated constraints reach (`constrained`) drawn: as handles where x > X,
      as fixed vertices elsewhere; with --clip X Y Z R also level<l>_zoom.vtp, the part within R.
  figure_tools.py steps RUN_DIR RUN OUT_DIR
      copies of a drag's steps, each with its constraints as they were at that step.
  figure_tools.py max ARRAY VTP...            the largest |ARRAY| over the files (a shared range)
  figure_tools.py shrink PNG...               rewrites PNGs with a 256-colour palette (smaller files)
  figure_tools.py compose OUT.png ROW...      stacks images; a ROW is comma-separated PNGs side by side
"""
import argparse
import math
import os
import shutil
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkIdList, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter


def read(path):
    r = vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    pd = r.GetOutput()
    if pd.GetNumberOfPoints() == 0:
        sys.exit(f"figure_tools: {path}: no points")
    return pd


def points(pd):
    return vtk_to_numpy(pd.GetPoints().GetData()).astype(float)


def write(pd, path):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    w = vtkXMLPolyDataWriter()
    w.SetFileName(path)
    w.SetInputData(pd)
    if not w.Write():
        sys.exit(f"figure_tools: could not write {path}")


def cmd_error(a):
    vtk = os.path.join(a.run_dir, "vtk")
    ref = points(read(os.path.join(vtk, a.ref + ".vtp")))
    os.makedirs(a.out_dir, exist_ok=True)
    for run in a.runs:
        pd = read(os.path.join(vtk, run + ".vtp"))
        x = points(pd)
        if x.shape != ref.shape:
            sys.exit(f"figure_tools: run {run} has {len(x)} points, the reference {len(ref)}")
        err = np.linalg.norm(x - ref, axis=1)
        arr = numpy_to_vtk(err, deep=True)
        arr.SetName("error")
        pd.GetPointData().AddArray(arr)
        write(pd, os.path.join(a.out_dir, run + ".vtp"))
        overlay = os.path.join(vtk, run + "_constraints.vtp")
        if os.path.exists(overlay):
            shutil.copy(overlay, os.path.join(a.out_dir, run + "_constraints.vtp"))
        print(f"{run}: largest distance to {a.ref} {err.max():.3g}, RMS {math.sqrt((err ** 2).mean()):.3g}")


def write_points(path, xs):
    with open(path, "w") as f:
        for p in xs:
            f.write(f"v {p[0]:.9g} {p[1]:.9g} {p[2]:.9g}\n")


def overlay_arrays(pd):
    """A constraints overlay's points, kinds, offsets, normals and lines (lists of point ids)."""
    n = pd.GetNumberOfPoints()
    x = points(pd) if n else np.zeros((0, 3))
    get = lambda name, k: (vtk_to_numpy(pd.GetPointData().GetArray(name)).reshape(n, k).astype(float)
                           if pd.GetPointData().GetArray(name) is not None else np.zeros((n, k)))
    lines, ids = [], vtkIdList()
    cells = pd.GetLines()
    cells.InitTraversal()
    while cells.GetNextCell(ids):
        lines.append([ids.GetId(i) for i in range(ids.GetNumberOfIds())])
    return x, get("kind", 1)[:, 0], get("offset", 3), get("target_normal", 3), lines


def write_overlay(path, x, kind, offset, normal, lines):
    pd = vtkPolyData()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(x, dtype=float), deep=True))
    pd.SetPoints(pts)
    for name, values in (("kind", np.asarray(kind, float)), ("offset", offset), ("target_normal", normal)):
        arr = numpy_to_vtk(np.ascontiguousarray(values, dtype=float), deep=True)
        arr.SetName(name)
        pd.GetPointData().AddArray(arr)
    cells = vtkCellArray()
    for line in lines:
        cells.InsertNextCell(len(line))
        for i in line:
            cells.InsertCellPoint(i)
    pd.SetLines(cells)
    write(pd, path)


def overlay_of(vtp):
    o = vtp[:-len(".vtp")] + "_constraints.vtp"
    return o if os.path.exists(o) else None


def cmd_rest(a):
    """The rest shape of a result (x - displacement) with its constraints where they started."""
    pd = read(a.vtp)
    d = vtk_to_numpy(pd.GetPointData().GetArray("displacement")).astype(float)
    rest = vtkPolyData()
    rest.SetPolys(pd.GetPolys())
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points(pd) - d), deep=True))
    rest.SetPoints(pts)
    write(rest, a.out)
    o = overlay_of(a.vtp)
    if o:
        x, kind, offset, normal, lines = overlay_arrays(read_any(o))
        handle = kind == 1
        x[handle] -= offset[handle]
        offset[:] = 0.0
        write_overlay(a.out[:-len(".vtp")] + "_constraints.vtp", x, kind, offset, normal, lines)


def read_any(path):
    r = vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    return r.GetOutput()


def rotation_lines(centre, axis, radius, angle, lift, axis_length):
    """The rotation as polylines: an arc of `angle` degrees at `radius` about the axis through
    `centre` (raised by `lift` along it), an arrow head at its end, and the axis itself."""
    centre, axis = np.asarray(centre, float), np.asarray(axis, float) / np.linalg.norm(axis)
    u = np.cross(axis, [1.0, 0.0, 0.0] if abs(axis[0]) < 0.9 else [0.0, 1.0, 0.0])
    u /= np.linalg.norm(u)
    v = np.cross(axis, u)
    n = max(8, int(abs(angle) / 3))
    t = np.radians(np.linspace(0.0, angle, n + 1))
    arc = [centre + lift * axis + radius * (math.cos(s) * u + math.sin(s) * v) for s in t]
    end, tangent = arc[-1], arc[-1] - arc[-2]
    tangent /= np.linalg.norm(tangent)
    radial = (end - centre - lift * axis) / radius
    h = 0.15 * radius
    head = [end - h * tangent + 0.5 * h * radial, end, end - h * tangent - 0.5 * h * radial]
    return [arc, head, [centre - axis_length * axis, centre + (lift + axis_length) * axis]]


def cmd_arc(a):
    """A copy of a result with the rotation (arc and axis) added to its overlay."""
    shutil.copy(a.vtp, a.out)
    o = overlay_of(a.vtp)
    x, kind, offset, normal, lines = overlay_arrays(read_any(o)) if o else (np.zeros((0, 3)), np.zeros(0), np.zeros((0, 3)), np.zeros((0, 3)), [])
    if a.no_arrows:  # the constrained vertices only, where they are now
        offset[:] = 0.0
    x, kind, offset, normal = list(x), list(kind), list(offset), list(normal)
    # Each line drawn as a bundle of parallel copies, `--width` apart: one overlay tube is thin.
    shifts = [np.zeros(3)] + [s * a.width * e for e in np.eye(3) for s in (-1.0, 1.0)]
    for line in (np.array(l) + d for l in rotation_lines(a.centre, a.axis, a.radius, a.angle, a.lift, a.axis_length)
                 for d in shifts):
        ids = []
        for p in line:
            ids.append(len(x))
            x.append(p)
            kind.append(-1.0)  # a curve's point
            offset.append(np.zeros(3))
            normal.append(np.zeros(3))
        lines.append(ids)
    write_overlay(a.out[:-len(".vtp")] + "_constraints.vtp", np.array(x), kind, np.array(offset), np.array(normal), lines)


def cmd_ladder(a):
    """Copies of a run's ladder levels, each with an overlay of the vertices its propagated
    constraints reach: the handle's (x > --above) as handles, the fixed region's as fixed."""
    vtk = os.path.join(a.run_dir, "vtk")
    prefix = a.run + "_ladder_level"
    files = sorted(f for f in os.listdir(vtk) if f.startswith(prefix) and f.endswith(".vtp"))
    if not files:
        sys.exit(f"figure_tools: no ladder levels of run {a.run} in {vtk}")
    os.makedirs(a.out_dir, exist_ok=True)
    for f in files:
        level = f[len(prefix):-len(".vtp")]
        pd = read(os.path.join(vtk, f))
        x = points(pd)
        c = vtk_to_numpy(pd.GetPointData().GetArray("constrained"))
        if c.ndim > 1:
            c = np.abs(c).max(axis=1)
        on = c != 0
        handle = on & (x[:, 0] > a.above)
        fixed = on & ~handle
        out = os.path.join(a.out_dir, f"level{level}.vtp")
        shutil.copy(os.path.join(vtk, f), out)
        sel = np.concatenate([np.where(handle)[0], np.where(fixed)[0]])
        kind = np.concatenate([np.ones(handle.sum()), np.zeros(fixed.sum())])
        write_overlay(out[:-len(".vtp")] + "_constraints.vtp", x[sel], kind, np.zeros((len(sel), 3)),
                      np.zeros((len(sel), 3)), [])
        if a.clip:
            clip(out, out[:-len(".vtp")] + "_zoom.vtp", np.array(a.clip[:3]), a.clip[3], x[sel], kind)
        print(f"level {level}: {int(handle.sum())} vertices reached by the handle's propagated rows, "
              f"{int(fixed.sum())} by the fixed region's, {len(x)} in all")


def clip(vtp, out, centre, radius, marks, kind):
    """The faces of VTP within `radius` of `centre` (and the marks there): a zoom whose own
    bounds set the size of the overlay's glyphs, so they stay smaller than the faces."""
    pd = read(vtp)
    x = points(pd)
    inside = np.linalg.norm(x - centre, axis=1) < radius
    keep, ids, cells = np.full(len(x), -1), vtkIdList(), pd.GetPolys()
    faces = []
    cells.InitTraversal()
    while cells.GetNextCell(ids):
        f = [ids.GetId(i) for i in range(ids.GetNumberOfIds())]
        if inside[f].all():
            faces.append(f)
    used = sorted({i for f in faces for i in f})
    keep[used] = np.arange(len(used))
    sub = vtkPolyData()
    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(x[used]), deep=True))
    sub.SetPoints(pts)
    polys = vtkCellArray()
    for f in faces:
        polys.InsertNextCell(len(f))
        for i in f:
            polys.InsertCellPoint(int(keep[i]))
    sub.SetPolys(polys)
    for k in range(pd.GetPointData().GetNumberOfArrays()):
        arr = pd.GetPointData().GetArray(k)
        v = vtk_to_numpy(arr)[used]
        na = numpy_to_vtk(np.ascontiguousarray(v), deep=True)
        na.SetName(arr.GetName())
        sub.GetPointData().AddArray(na)
    write(sub, out)
    near = np.linalg.norm(marks - centre, axis=1) < radius
    write_overlay(out[:-len(".vtp")] + "_constraints.vtp", marks[near], kind[near], np.zeros((near.sum(), 3)),
                  np.zeros((near.sum(), 3)), [])


def cmd_steps(a):
    """Copies of a drag's steps (vtk/<RUN>_step<k>.vtp), each with the run's overlay as it was
    at that step: handles at their start plus k/N of their offset, fixed vertices as they are."""
    vtk = os.path.join(a.run_dir, "vtk")
    steps = sorted((int(f[len(a.run) + 5:-4]), f) for f in os.listdir(vtk)
                   if f.startswith(a.run + "_step") and f.endswith(".vtp") and f[len(a.run) + 5:-4].isdigit())
    if not steps:
        sys.exit(f"figure_tools: no drag steps of run {a.run} in {vtk}")
    x, kind, offset, normal, lines = overlay_arrays(read_any(os.path.join(vtk, a.run + "_constraints.vtp")))
    n = steps[-1][0]
    os.makedirs(a.out_dir, exist_ok=True)
    for k, f in steps:
        shutil.copy(os.path.join(vtk, f), os.path.join(a.out_dir, f))
        xs, os_ = x.copy(), offset * (k / n)
        handle = kind == 1
        xs[handle] = x[handle] - offset[handle] + os_[handle]
        write_overlay(os.path.join(a.out_dir, f[:-4] + "_constraints.vtp"), xs, kind, os_, normal, lines)


def cmd_max(a):
    m = 0.0
    for f in a.vtps:
        arr = read(f).GetPointData().GetArray(a.array)
        v = vtk_to_numpy(arr).astype(float)
        m = max(m, float(np.linalg.norm(v, axis=1).max() if v.ndim > 1 else np.abs(v).max()))
    print(f"{m:.6g}")


def cmd_compose(a):
    from PIL import Image
    rows = [[Image.open(p).convert("RGB") for p in row.split(",")] for row in a.rows]
    width = max(sum(im.width for im in row) for row in rows)
    height = sum(max(im.height for im in row) for row in rows)
    out = Image.new("RGB", (width, height), "white")
    y = 0
    for row in rows:
        x = (width - sum(im.width for im in row)) // 2
        for im in row:
            out.paste(im, (x, y))
            x += im.width
        y += max(im.height for im in row)
    tmp = a.out + ".tmp.png"
    out.save(tmp, optimize=True)
    os.replace(tmp, a.out)
    print(f"figure_tools: wrote {a.out}")


def cmd_shrink(a):
    """Rewrites PNGs with an adaptive palette of 256 colours: a third to a half of the bytes of a
    shaded render, no visible change."""
    from PIL import Image
    for path in a.pngs:
        im = Image.open(path).convert("RGB")
        before = os.path.getsize(path)
        tmp = path + ".tmp.png"
        im.quantize(colors=256, method=Image.Quantize.FASTOCTREE, dither=Image.Dither.FLOYDSTEINBERG).save(tmp, optimize=True)
        os.replace(tmp, path)
        print(f"{path}: {before // 1024} KB -> {os.path.getsize(path) // 1024} KB")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    e = sub.add_parser("error")
    e.add_argument("run_dir")
    e.add_argument("ref")
    e.add_argument("out_dir")
    e.add_argument("runs", nargs="+")
    e.set_defaults(func=cmd_error)
    rs = sub.add_parser("rest")
    rs.add_argument("vtp")
    rs.add_argument("out")
    rs.set_defaults(func=cmd_rest)
    r = sub.add_parser("arc")
    r.add_argument("vtp")
    r.add_argument("out")
    r.add_argument("--centre", type=float, nargs=3, default=[0.0, 0.0, 0.0])
    r.add_argument("--axis", type=float, nargs=3, default=[0.0, 0.0, 1.0])
    r.add_argument("--radius", type=float, required=True)
    r.add_argument("--angle", type=float, required=True, help="degrees")
    r.add_argument("--lift", type=float, default=0.0, help="the arc's height along the axis")
    r.add_argument("--axis-length", type=float, default=0.5)
    r.add_argument("--width", type=float, default=0.0, help="draw each line as a bundle this far apart")
    r.add_argument("--no-arrows", action="store_true", help="drop the handles' arrows from where they started")
    r.set_defaults(func=cmd_arc)
    ld = sub.add_parser("ladder")
    ld.add_argument("run_dir")
    ld.add_argument("run")
    ld.add_argument("out_dir")
    ld.add_argument("--above", type=float, default=-math.inf)
    ld.add_argument("--clip", type=float, nargs=4, metavar=("X", "Y", "Z", "R"),
                    help="also OUT_DIR/level<l>_zoom.vtp: the faces within R of (X, Y, Z), for a close-up")
    ld.set_defaults(func=cmd_ladder)
    st = sub.add_parser("steps")
    st.add_argument("run_dir")
    st.add_argument("run")
    st.add_argument("out_dir")
    st.set_defaults(func=cmd_steps)
    mx = sub.add_parser("max")
    mx.add_argument("array")
    mx.add_argument("vtps", nargs="+")
    mx.set_defaults(func=cmd_max)
    sh = sub.add_parser("shrink")
    sh.add_argument("pngs", nargs="+")
    sh.set_defaults(func=cmd_shrink)
    c = sub.add_parser("compose")
    c.add_argument("out")
    c.add_argument("rows", nargs="+")
    c.set_defaults(func=cmd_compose)
    a = p.parse_args()
    a.func(a)


if __name__ == "__main__":
    main()
