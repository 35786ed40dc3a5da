// Internal: SurfaceMesh <-> vtkPolyData, shared by the VTK readers, writers and the renderer.
#pragma once

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <string>

#include "fairshape/mesh/surface_mesh.h"

namespace fairshape::io::internal {

//! A .vtp read by VTK from bytes checked first (counts, appended headers), every cell's point
//! ids checked: polygons, lines, vertices and strips as the file has them.
//! \throw IOError / InvalidInput naming the file.
vtkSmartPointer<vtkPolyData> read_checked_polydata(const std::string& path);

//! vertex_data -> point data, face_data -> cell data; `path` names the file in errors.
vtkSmartPointer<vtkPolyData> to_polydata(const SurfaceMesh& mesh, const std::string& path);

}  // namespace fairshape::io::internal
