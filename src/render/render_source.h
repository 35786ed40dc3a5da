// What a panel shows, resolved from what a user names: a mesh or curve file (.vtp, .obj,
// .off, .ply), one level of a .vtm, one step of a .pvd, or one run of a result folder.
#pragma once

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>

namespace fairshape::render {

//! Which block, step or run when a source holds several; -1 / empty: the only one, or for
//! blocks and steps the last (the finest level, the final step).
struct SourceChoice {
  int block = -1;
  int step = -1;
  std::string run;
};

struct RenderSource {
  std::string path;                    // the file the geometry came from
  vtkSmartPointer<vtkPolyData> data;   // polygons, or lines for a curve
  std::string levels_path;             // the hierarchy it belongs to (.vtm), when there is one
  std::string overlay_path;            // <stem>_constraints.vtp beside a .vtp (a run's, a step's), if any
  std::string parameters;              // a run's swept parameters, "key=value, ..." (its default label)
  bool curve() const { return data->GetNumberOfPolys() == 0 && data->GetNumberOfLines() > 0; }
};

//! `spec` is a path, optionally followed by "@" and a block or step number (.vtm, .pvd) or a run
//! id (a result folder); without one, `choice` applies. A folder holding several runs needs a run
//! id: it is refused, listing them, rather than one guessed.
//! \throw IOError / InvalidInput naming the file and the valid choices.
RenderSource load_render_source(const std::string& spec, const SourceChoice& choice);

//! An overlay: a .vtp (a run's constraints) or an OBJ of polylines or points.
vtkSmartPointer<vtkPolyData> load_overlay(const std::string& path);

//! Level `level` of the hierarchy `levels_path` (.vtm), for drawing a control mesh.
vtkSmartPointer<vtkPolyData> load_level(const std::string& levels_path, int level);

}  // namespace fairshape::render
