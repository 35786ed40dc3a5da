#include "io/render.h"

#include <X11/Xlib.h>
#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkWindowToImageFilter.h>

#include <cstdlib>
#include <filesystem>

#include "core/atomic_file.h"
#include "core/error.h"
#include "io/vtk_convert.h"

namespace fairshape {

bool display_available() {
  const char* d = std::getenv("DISPLAY");
  if (!d || !*d) return false;
  Display* x = XOpenDisplay(d);
  if (!x) return false;
  XCloseDisplay(x);
  return true;
}

static Eigen::MatrixXd scalar_field(const SurfaceMesh& mesh, const std::string& name) {
  auto it = mesh.vertex_data.find(name);
  if (it == mesh.vertex_data.end()) {
    std::string known;
    for (const auto& [k, v] : mesh.vertex_data) known += (known.empty() ? "" : ", ") + k;
    throw InvalidInput("render: no point array '" + name + "' (available: " + (known.empty() ? "none" : known) + ")");
  }
  return it->second.cols() == 1 ? it->second : Eigen::MatrixXd(it->second.rowwise().norm());
}

void render_png(const SurfaceMesh& mesh, const RenderOptions& opt, const std::string& path) {
  if (!display_available()) throw IOError("render: no X display (run under xvfb-run, or set DISPLAY)");
  SurfaceMesh shown = mesh;
  if (!opt.color_by.empty()) shown.vertex_data = {{"__color", scalar_field(mesh, opt.color_by)}};
  auto pd = io::internal::to_polydata(shown, path);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(pd);
  if (!opt.color_by.empty()) {
    const Eigen::MatrixXd& s = shown.vertex_data["__color"];
    vtkNew<vtkLookupTable> lut;
    lut->SetHueRange(0.667, 0.0);  // blue (low) to red (high)
    lut->Build();
    mapper->SetLookupTable(lut);
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectColorArray("__color");
    mapper->SetScalarRange(s.minCoeff(), s.maxCoeff() > s.minCoeff() ? s.maxCoeff() : s.minCoeff() + 1);
    mapper->ScalarVisibilityOn();
  } else {
    mapper->ScalarVisibilityOff();
  }
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(0.85, 0.75, 0.6);
  if (opt.edges) actor->GetProperty()->EdgeVisibilityOn();
  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(actor);
  renderer->SetBackground(1, 1, 1);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(opt.azimuth);
  renderer->GetActiveCamera()->Elevation(opt.elevation);
  renderer->GetActiveCamera()->OrthogonalizeViewUp();
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(opt.zoom);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->AddRenderer(renderer);
  window->SetSize(opt.width, opt.height);
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->Update();
  const auto tmp = temporary_sibling(path);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(tmp.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (!std::filesystem::exists(tmp)) throw IOError(path + ": could not write the PNG");
  commit_path(tmp, path);
}

}  // namespace fairshape
