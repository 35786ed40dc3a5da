// VTK XML output for ParaView: PolyData (.vtp) with point and cell data arrays, multiblock
// (.vtm, one block per level) and time series (.pvd). All written atomically.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "fairshape/mesh/polyline.h"
#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

using DataArrays = std::map<std::string, Eigen::MatrixXd>;  // name -> rows x components

// mesh.vertex_data become point data, mesh.face_data cell data.
void write_vtp(const SurfaceMesh& mesh, const std::string& path);
void write_vtp(const Polyline& curve, const DataArrays& point_data, const std::string& path);

//! Points, with polylines through some of them (indices into `points`) and point arrays: what
//! overlays are made of (constraint points, curves). Each point on no polyline is a vertex
//! cell, so that ParaView's default representation draws it.
void write_vtp(const MatrixX3& points, const std::vector<std::vector<int>>& polylines, const DataArrays& point_data,
               const std::string& path);

//! Reads a .vtp written by any VTK program: polygons and their point/cell data arrays.
SurfaceMesh read_vtp(const std::string& path);

struct NamedMesh {
  std::string name;
  const SurfaceMesh* mesh;
};
//! Writes `stem.vtm` plus a folder `stem/` with one .vtp per block.
void write_vtm(const std::vector<NamedMesh>& blocks, const std::string& path);
std::vector<SurfaceMesh> read_vtm(const std::string& path);

//! ParaView collection: (time, file relative to the .pvd) pairs.
void write_pvd(const std::vector<std::pair<double, std::string>>& steps, const std::string& path);

}  // namespace fairshape
