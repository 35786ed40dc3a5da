#include "fairshape/io/contour_lines.h"

#include <vtkCellArray.h>
#include <vtkContourFilter.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkPointData.h>
#include <vtkStripper.h>

#include "fairshape/core/error.h"
#include "fairshape/io/vtk_convert.h"

namespace fairshape {

std::vector<std::vector<Vec3>> contour_lines(const SurfaceMesh& mesh, const Eigen::VectorXd& values, double level) {
  if (values.size() != mesh.n_vertices())
    throw InvalidInput("contour_lines: " + std::to_string(values.size()) + " values for " + std::to_string(mesh.n_vertices()) +
                       " vertices");
  SurfaceMesh plain = mesh;
  plain.vertex_data.clear();
  plain.face_data.clear();
  vtkSmartPointer<vtkPolyData> pd = io::internal::to_polydata(plain, "contour");
  vtkNew<vtkDoubleArray> field;
  field->SetName("field");
  field->SetNumberOfValues(values.size());
  for (Eigen::Index i = 0; i < values.size(); ++i) field->SetValue(i, values[i]);
  pd->GetPointData()->SetScalars(field);
  vtkNew<vtkContourFilter> contour;
  contour->SetInputData(pd);
  contour->SetValue(0, level);
  vtkNew<vtkStripper> strip;  // joins the per-triangle segments into polylines
  strip->SetInputConnection(contour->GetOutputPort());
  strip->JoinContiguousSegmentsOn();
  strip->Update();
  vtkPolyData* out = strip->GetOutput();
  std::vector<std::vector<Vec3>> lines;
  vtkCellArray* cells = out->GetLines();
  vtkNew<vtkIdList> ids;
  for (cells->InitTraversal(); cells->GetNextCell(ids);) {
    std::vector<Vec3> line;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) {
      double p[3];
      out->GetPoint(ids->GetId(k), p);
      line.emplace_back(p[0], p[1], p[2]);
    }
    if (line.size() >= 2) lines.push_back(std::move(line));
  }
  return lines;
}

}  // namespace fairshape
