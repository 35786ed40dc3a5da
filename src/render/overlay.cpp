#include "fairshape/render/overlay.h"

#include <vtkActor.h>
#include <vtkArrowSource.h>
#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkGlyph3DMapper.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkSphereSource.h>
#include <vtkTubeFilter.h>

#include <array>

#include "fairshape/io/constraint_overlay.h"

namespace fairshape::render {
namespace {

using Colour = std::array<double, 3>;
constexpr Colour kFixed{0.35, 0.35, 0.38}, kHandle{0.85, 0.1, 0.1}, kNormal{0.8, 0.1, 0.75}, kCurve{1.0, 0.55, 0.0},
                 kOutline{0.15, 0.15, 0.2};

vtkSmartPointer<vtkActor> coloured(vtkMapper* m, const Colour& c) {
  auto a = vtkSmartPointer<vtkActor>::New();
  a->SetMapper(m);
  a->GetProperty()->SetColor(c[0], c[1], c[2]);
  a->GetProperty()->SetSpecular(0.3);
  return a;
}

// Spheres of `radius` at `points`, or arrows along `directions` (unit) of `length`.
vtkSmartPointer<vtkActor> glyphs(vtkPoints* points, vtkDoubleArray* directions, double size, const Colour& c) {
  vtkNew<vtkPolyData> at;
  at->SetPoints(points);
  vtkNew<vtkGlyph3DMapper> m;
  m->SetInputData(at);
  if (directions) {
    directions->SetName("direction");
    at->GetPointData()->AddArray(directions);
    vtkNew<vtkArrowSource> arrow;
    arrow->SetTipResolution(16);
    arrow->SetShaftResolution(16);
    m->SetSourceConnection(arrow->GetOutputPort());
    m->SetOrientationArray("direction");
    m->OrientOn();
  } else {
    vtkNew<vtkSphereSource> sphere;
    sphere->SetThetaResolution(16);
    sphere->SetPhiResolution(12);
    sphere->SetRadius(1.0);
    m->SetSourceConnection(sphere->GetOutputPort());
  }
  // Every glyph the same size: the factor alone, no data array.
  m->ScalingOn();
  m->SetScaleModeToNoDataScaling();
  m->SetScaleFactor(size);
  m->ScalarVisibilityOff();
  return coloured(m, c);
}

vtkSmartPointer<vtkActor> tubes(vtkPolyData* lines, double radius, const Colour& c) {
  vtkNew<vtkTubeFilter> t;
  t->SetInputData(lines);
  t->SetRadius(radius);
  t->SetNumberOfSides(12);
  t->CappingOn();
  vtkNew<vtkPolyDataMapper> m;
  m->SetInputConnection(t->GetOutputPort());
  m->ScalarVisibilityOff();
  return coloured(m, c);
}

}  // namespace

std::vector<vtkSmartPointer<vtkProp>> overlay_props(vtkPolyData* overlay, double d, double curve_radius) {
  std::vector<vtkSmartPointer<vtkProp>> props;
  vtkDataArray* kind = overlay->GetPointData()->GetArray(kOverlayKind);
  if (overlay->GetNumberOfLines() > 0) {
    // Curves and outlines apart: a line is an outline when its first point is one.
    vtkNew<vtkCellArray> curve_lines, outline_lines;
    vtkCellArray* all = overlay->GetLines();
    vtkNew<vtkIdList> ids;
    for (all->InitTraversal(); all->GetNextCell(ids);) {
      const bool outline = kind && ids->GetNumberOfIds() > 0 &&
                           static_cast<int>(kind->GetComponent(ids->GetId(0), 0)) == static_cast<int>(OverlayKind::OutlinePoint);
      (outline ? outline_lines : curve_lines)->InsertNextCell(ids);
    }
    const auto draw = [&](vtkCellArray* cells, double radius, const Colour& c) {
      if (cells->GetNumberOfCells() == 0) return;
      vtkNew<vtkPolyData> lines;
      lines->SetPoints(overlay->GetPoints());
      lines->SetLines(cells);
      props.push_back(tubes(lines, radius * d, c));
    };
    draw(curve_lines, curve_radius, kCurve);
    draw(outline_lines, 0.5 * curve_radius, kOutline);
  }
  vtkDataArray* offset = overlay->GetPointData()->GetArray(kOverlayOffset);
  vtkDataArray* normal = overlay->GetPointData()->GetArray(kOverlayNormal);
  if (!kind) {
    if (overlay->GetNumberOfLines() == 0) {  // a point file: its points
      vtkNew<vtkPoints> all;
      all->DeepCopy(overlay->GetPoints());
      props.push_back(glyphs(all, nullptr, 0.008 * d, kHandle));
    }
    return props;
  }
  vtkNew<vtkPoints> fixed, handles, starts, normal_at;
  vtkNew<vtkDoubleArray> normal_dirs;
  normal_dirs->SetNumberOfComponents(3);
  vtkNew<vtkPolyData> arrows;
  vtkNew<vtkPoints> arrow_points;
  vtkNew<vtkCellArray> arrow_lines;
  for (vtkIdType i = 0; i < overlay->GetNumberOfPoints(); ++i) {
    double p[3];
    overlay->GetPoint(i, p);
    const auto k = static_cast<OverlayKind>(static_cast<int>(kind->GetComponent(i, 0)));
    if (k == OverlayKind::Fixed) fixed->InsertNextPoint(p);
    if (k == OverlayKind::Handle && offset) {
      handles->InsertNextPoint(p);
      const double* o = offset->GetTuple3(i);
      const double s[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]};
      starts->InsertNextPoint(s);
      const vtkIdType a = arrow_points->InsertNextPoint(s), b = arrow_points->InsertNextPoint(p);
      const vtkIdType ids[2] = {a, b};
      arrow_lines->InsertNextCell(2, ids);
    }
    if (k == OverlayKind::Normal && normal) {
      normal_at->InsertNextPoint(p);
      normal_dirs->InsertNextTuple(normal->GetTuple3(i));
    }
  }
  if (fixed->GetNumberOfPoints()) props.push_back(glyphs(fixed, nullptr, 0.0035 * d, kFixed));
  if (handles->GetNumberOfPoints()) {
    props.push_back(glyphs(handles, nullptr, 0.011 * d, kHandle));
    props.push_back(glyphs(starts, nullptr, 0.006 * d, {1.0, 0.6, 0.6}));
    arrows->SetPoints(arrow_points);
    arrows->SetLines(arrow_lines);
    props.push_back(tubes(arrows, 0.0025 * d, kHandle));
  }
  if (normal_at->GetNumberOfPoints()) props.push_back(glyphs(normal_at, normal_dirs, 0.1 * d, kNormal));
  return props;
}

}  // namespace fairshape::render
