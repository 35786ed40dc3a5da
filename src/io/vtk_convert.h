// Internal: SurfaceMesh -> vtkPolyData, shared by the VTK writers and the renderer.
#pragma once

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>

#include "mesh/surface_mesh.h"

namespace fairshape::io::internal {

//! vertex_data -> point data, face_data -> cell data; `path` names the file in errors.
vtkSmartPointer<vtkPolyData> to_polydata(const SurfaceMesh& mesh, const std::string& path);

}  // namespace fairshape::io::internal
