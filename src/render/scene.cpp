#include "fairshape/render/scene.h"

#include <vtkActor.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkTubeFilter.h>

#include "fairshape/core/error.h"

namespace fairshape::render {

const NameTable<Component>& component_names() {
  static const NameTable<Component> t{{Component::Magnitude, "magnitude"}, {Component::X, "x"}, {Component::Y, "y"},
                                      {Component::Z, "z"}, {Component::Normal, "normal"}};
  return t;
}

namespace {

vtkSmartPointer<vtkPolyData> with_normals(vtkPolyData* data) {
  vtkNew<vtkPolyDataNormals> n;
  n->SetInputData(data);
  n->SplittingOff();  // one normal per point: the surface is smooth, creases are the model's
  n->ComputePointNormalsOn();
  n->ComputeCellNormalsOff();
  n->ConsistencyOff();  // fairshape's meshes are oriented; reordering would break the point order
  n->AutoOrientNormalsOff();
  n->Update();
  return n->GetOutput();
}

void shade(vtkActor* actor) {
  vtkProperty* p = actor->GetProperty();
  p->SetInterpolationToPhong();
  p->SetAmbient(0.12);
  p->SetDiffuse(0.8);
  p->SetSpecular(0.18);
  p->SetSpecularPower(24);
}

}  // namespace

vtkSmartPointer<vtkDoubleArray> panel_scalars(vtkPolyData* data, const Colouring& c, const std::string& path) {
  vtkDataArray* a = data->GetPointData()->GetArray(c.array.c_str());
  if (!a) {
    std::string known;
    for (int i = 0; i < data->GetPointData()->GetNumberOfArrays(); ++i)
      if (const char* name = data->GetPointData()->GetArrayName(i)) known += (known.empty() ? "" : ", ") + std::string(name);
    throw InvalidInput("render: " + path + " has no point array '" + c.array + "' (available: " +
                       (known.empty() ? "none" : known) + ")");
  }
  const int n = a->GetNumberOfComponents();
  const Component comp = c.component_given ? c.component : Component::Magnitude;
  if (n == 1 && comp != Component::Magnitude)
    throw InvalidInput("render: '" + c.array + "' has one component; --component " +
                       std::string(component_names().name(comp)) + " needs a vector array");
  if (n != 1 && n != 3 && comp != Component::Magnitude)
    throw InvalidInput("render: '" + c.array + "' has " + std::to_string(n) + " components; x, y, z and normal need 3");
  vtkSmartPointer<vtkPolyData> normals;
  if (comp == Component::Normal) normals = with_normals(data);
  auto out = vtkSmartPointer<vtkDoubleArray>::New();
  out->SetName("__scalar");
  out->SetNumberOfTuples(a->GetNumberOfTuples());
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i) {
    double v = 0;
    switch (n == 1 ? Component::X : comp) {
      case Component::Magnitude:
        for (int k = 0; k < n; ++k) v += a->GetComponent(i, k) * a->GetComponent(i, k);
        v = std::sqrt(v);
        break;
      case Component::X: v = a->GetComponent(i, 0); break;
      case Component::Y: v = a->GetComponent(i, 1); break;
      case Component::Z: v = a->GetComponent(i, 2); break;
      case Component::Normal: {
        const double* nn = normals->GetPointData()->GetNormals()->GetTuple3(i);
        for (int k = 0; k < 3; ++k) v += a->GetComponent(i, k) * nn[k];
        break;
      }
    }
    out->SetValue(i, v);
  }
  return out;
}

std::vector<vtkSmartPointer<vtkProp>> panel_props(const RenderSource& source, vtkDoubleArray* scalars,
                                                  vtkScalarsToColors* colours, double lo, double hi,
                                                  const SurfaceStyle& style, double diagonal) {
  std::vector<vtkSmartPointer<vtkProp>> props;
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->ShallowCopy(source.data);
  if (scalars) data->GetPointData()->AddArray(scalars);
  vtkNew<vtkPolyDataMapper> mapper;
  if (source.curve()) {
    vtkNew<vtkTubeFilter> tube;
    tube->SetInputData(data);
    tube->SetRadius(style.tube_radius * diagonal);
    tube->SetNumberOfSides(16);
    tube->CappingOn();
    mapper->SetInputConnection(tube->GetOutputPort());
  } else if (style.flat) {
    mapper->SetInputData(data);
  } else {
    mapper->SetInputData(with_normals(data));
  }
  if (colours && scalars) {
    mapper->SetLookupTable(colours);
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray("__scalar");
    mapper->SetScalarRange(lo, hi);
    mapper->ScalarVisibilityOn();
  } else {
    mapper->ScalarVisibilityOff();
  }
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  shade(actor);
  actor->GetProperty()->SetColor(source.curve() ? 0.2 : 0.86, source.curve() ? 0.35 : 0.78, source.curve() ? 0.7 : 0.66);
  if (style.flat) actor->GetProperty()->SetInterpolationToFlat();
  if (style.edges && !source.curve()) {
    actor->GetProperty()->EdgeVisibilityOn();
    actor->GetProperty()->SetEdgeColor(0.25, 0.25, 0.25);
  }
  props.push_back(actor);
  if (style.control_level >= 0) {
    if (source.levels_path.empty())
      throw InvalidInput("render: --control-level needs a hierarchy: " + source.path +
                         " is neither a .vtm nor a run with vtk/<run>_levels.vtm");
    vtkNew<vtkPolyDataMapper> cm;
    cm->SetInputData(load_level(source.levels_path, style.control_level));
    cm->ScalarVisibilityOff();
    auto wire = vtkSmartPointer<vtkActor>::New();
    wire->SetMapper(cm);
    wire->GetProperty()->SetRepresentationToWireframe();
    wire->GetProperty()->SetColor(0.1, 0.1, 0.1);
    wire->GetProperty()->SetLineWidth(1.5);
    wire->GetProperty()->LightingOff();
    props.push_back(wire);
  }
  return props;
}

}  // namespace fairshape::render
