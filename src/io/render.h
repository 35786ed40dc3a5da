// Offscreen PNG rendering of a mesh with VTK (needs an X server: Debian's VTK has no EGL or
// OSMesa; the CLI re-runs itself under xvfb-run when DISPLAY is unset).
#pragma once

#include <string>

#include "mesh/surface_mesh.h"

namespace fairshape {

struct RenderOptions {
  std::string color_by;  // a vertex_data array (magnitude if it has several components); empty = plain
  int width = 1200, height = 900;
  double azimuth = 30, elevation = 20, zoom = 1.0;
  bool edges = false;
};

//! \throw InvalidInput for an unknown array name (listing the available ones), IOError when no
//! X display can be opened or writing fails.
void render_png(const SurfaceMesh& mesh, const RenderOptions& opt, const std::string& path);
bool display_available();

}  // namespace fairshape
