#!/usr/bin/python3
"""Helpers for Khodakovsky & Schröder's figures (make_figures.sh); the panels themselves are
`fairshape render` calls, this script only prepares their inputs and puts them together.

  ks_panels.py input RUN_DIR RUN_ID OUT_DIR [--edit BASE.off --fixed-x FROM TO ... --handle X Y Z --offset DX DY DZ]
      the surface without the features (the finest level of the result minus its `displacement`
      array: `OUT_DIR/<RUN_ID>_input.vtp`) and the feature curves laid on it (each point of the
      run's overlay curves, which lie on the result, moved back by the displacement of the
      result's nearest vertex), written as an overlay for `fairshape render --overlay`
      (`OUT_DIR/<RUN_ID>_input_overlay.vtp`, with a level-0 edit's held vertices and handle when
      --edit is given): the input panel of a figure, what the designer drew on.
  ks_panels.py compose OUT.png --title TEXT [--columns N] PANEL.png ...
      one figure from several `fairshape render` images (each with its own colour bar, when the
      panels need different arrays or ranges), in rows of N under a title; the figure is
      stored with a 256-colour palette of its own colours (dithered) to keep it small.
"""
import argparse
import os
import sys

import numpy as np
import vtk
from vtk.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from PIL import Image, ImageDraw, ImageFont


def read_vtp(path):
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    if r.GetOutput().GetNumberOfPoints() == 0:
        sys.exit(f"ks_panels: {path}: no points")
    return r.GetOutput()


def make_input(a):
    result = read_vtp(os.path.join(a.run_dir, "vtk", a.run_id + ".vtp"))
    p = vtk_to_numpy(result.GetPoints().GetData())
    d = vtk_to_numpy(result.GetPointData().GetArray("displacement"))
    rest = vtk.vtkPolyData()
    points = vtk.vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(p - d), deep=True))
    rest.SetPoints(points)
    rest.SetPolys(result.GetPolys())
    os.makedirs(a.out_dir, exist_ok=True)
    w = vtk.vtkXMLPolyDataWriter()
    w.SetFileName(os.path.join(a.out_dir, a.run_id + "_input.vtp"))
    w.SetInputData(rest)
    w.Write()
    # The curves: moved back by the displacement of the nearest result vertex (the feature moves
    # its crest along the normal by about h; the nearest vertex is within half a finest edge).
    # The run's overlay holds each curve where the feature is on the result (README, "Exports");
    # curves/<run>_*.obj hold them on the surface each was drawn on, which for a finer feature
    # is the surface with the coarser features.
    locator = vtk.vtkPointLocator()
    locator.SetDataSet(result)
    locator.BuildLocator()
    shown = read_vtp(os.path.join(a.run_dir, "vtk", a.run_id + "_constraints.vtp"))
    kind = vtk_to_numpy(shown.GetPointData().GetArray("kind"))
    q = vtk_to_numpy(shown.GetPoints().GetData())
    overlay = Overlay()
    lines, ids, curves = shown.GetLines(), vtk.vtkIdList(), 0
    lines.InitTraversal()
    while lines.GetNextCell(ids):
        line = [ids.GetId(j) for j in range(ids.GetNumberOfIds())]
        if kind[line[0]] != CURVE_POINT:
            continue  # the neighbourhoods' outline: the result's, not the input's
        overlay.line([q[i] - d[locator.FindClosestPoint(q[i])] for i in line], CURVE_POINT)
        curves += 1
    if a.edit:
        add_edit(a, overlay)
    overlay.write(os.path.join(a.out_dir, a.run_id + "_input_overlay.vtp"))
    print(f"ks_panels: wrote {a.out_dir}/{a.run_id}_input.vtp and _input_overlay.vtp ({curves} curves)")


# The overlay format of `fairshape render` (src/io/constraint_overlay.h): per point a `kind`
# (-1 a curve's point, 0 a fixed vertex, 1 a handle), an `offset` (a handle started at point −
# offset) and a `target_normal`; curves are polylines.
CURVE_POINT, FIXED, HANDLE = -1, 0, 1


class Overlay:
    def __init__(self):
        self.points, self.kinds, self.offsets, self.lines = [], [], [], []

    def point(self, p, kind, offset=(0.0, 0.0, 0.0)):
        self.points.append(np.asarray(p, float))
        self.kinds.append(kind)
        self.offsets.append(np.asarray(offset, float))
        return len(self.points) - 1

    def line(self, pts, kind):
        self.lines.append([self.point(p, kind) for p in pts])

    def write(self, path):
        pd = vtk.vtkPolyData()
        points = vtk.vtkPoints()
        points.SetData(numpy_to_vtk(np.array(self.points), deep=True))
        pd.SetPoints(points)
        cells = vtk.vtkCellArray()
        for line in self.lines:
            cells.InsertNextCell(len(line))
            for i in line:
                cells.InsertCellPoint(i)
        pd.SetLines(cells)
        for name, values in (("kind", np.array(self.kinds, float)), ("offset", np.array(self.offsets)),
                             ("target_normal", np.zeros((len(self.points), 3)))):
            arr = numpy_to_vtk(np.ascontiguousarray(values), deep=True)
            arr.SetName(name)
            pd.GetPointData().AddArray(arr)
        w = vtk.vtkXMLPolyDataWriter()
        w.SetFileName(path)
        w.SetInputData(pd)
        w.Write()


def add_edit(a, overlay):
    """A level-0 edit's constraints (Figure 15) on the base mesh: the vertices held in x-slabs
    (fractions of the bounding box, as the config's `region`) and the handle (the base vertex
    nearest to `--handle`, moved by `--offset`: drawn where it is asked to go, with an arrow
    from where it starts)."""
    t = open(a.edit).read().split()
    nv = int(t[1])
    base = np.array(t[4:4 + 3 * nv], float).reshape(-1, 3)
    lo, hi = base.min(0), base.max(0)
    for f0, f1 in a.fixed_x or []:
        x = (base[:, 0] - lo[0]) / (hi[0] - lo[0])
        for i in np.where((x >= f0 - 1e-12) & (x <= f1 + 1e-12))[0]:
            overlay.point(base[i], FIXED)
    if a.handle:
        i = int(np.argmin(np.linalg.norm(base - np.array(a.handle), axis=1)))
        overlay.point(base[i] + np.array(a.offset), HANDLE, a.offset)


def font(size):
    for name in ("DejaVuSans.ttf", "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"):
        try:
            return ImageFont.truetype(name, size)
        except OSError:
            pass
    return ImageFont.load_default()


def compose(a):
    panels = [Image.open(p).convert("RGB") for p in a.panels]
    cols = a.columns or len(panels)
    rows = [panels[i:i + cols] for i in range(0, len(panels), cols)]
    width = max(sum(p.width for p in row) for row in rows)
    title_h = 50
    height = title_h + sum(max(p.height for p in row) for row in rows)
    fig = Image.new("RGB", (width, height), "white")
    y = title_h
    for row in rows:
        x = (width - sum(p.width for p in row)) // 2
        for p in row:
            fig.paste(p, (x, y))
            x += p.width
        y += max(p.height for p in row)
    draw = ImageDraw.Draw(fig)
    f = font(24)
    tw = draw.textlength(a.title, font=f)
    draw.text(((width - tw) / 2, 12), a.title, fill=(25, 25, 25), font=f)
    tmp = a.out_png + ".tmp.png"
    # A median-cut palette of the figure's own colours, Floyd-Steinberg dithered (without the
    # dithering the shading shows bands): about half the size of the RGB image.
    palette = fig.quantize(colors=256, method=Image.Quantize.MEDIANCUT)
    fig.quantize(palette=palette, dither=Image.Dither.FLOYDSTEINBERG).save(tmp, optimize=True)
    os.replace(tmp, a.out_png)  # never a truncated figure
    print(f"ks_panels: wrote {a.out_png} ({len(panels)} panels)")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="cmd", required=True)
    i = sub.add_parser("input")
    i.add_argument("run_dir")
    i.add_argument("run_id")
    i.add_argument("out_dir")
    i.add_argument("--edit", metavar="BASE.off", help="the run has a level-0 edit of this base mesh: draw its constraints")
    i.add_argument("--fixed-x", nargs=2, type=float, action="append", metavar=("FROM", "TO"),
                   help="with --edit: base vertices in this x-slab (fractions of the bounding box) are held")
    i.add_argument("--handle", nargs=3, type=float, metavar=("X", "Y", "Z"),
                   help="with --edit: the handle is the base vertex nearest to this point")
    i.add_argument("--offset", nargs=3, type=float, default=[0.0, 0.0, 0.0], metavar=("DX", "DY", "DZ"),
                   help="with --handle: the handle's offset")
    c = sub.add_parser("compose")
    c.add_argument("out_png")
    c.add_argument("--title", required=True)
    c.add_argument("--columns", type=int, default=0)
    c.add_argument("panels", nargs="+")
    a = p.parse_args()
    make_input(a) if a.cmd == "input" else compose(a)


if __name__ == "__main__":
    main()
