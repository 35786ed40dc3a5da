#include "fairshape/io/vtk_io.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCompositeDataSet.h>
#include <vtkDoubleArray.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLMultiBlockDataReader.h>
#include <vtkXMLMultiBlockDataWriter.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include "fairshape/core/atomic_file.h"
#include "fairshape/core/error.h"
#include "fairshape/io/finite_output.h"
#include "fairshape/io/vtk_checks.h"
#include "fairshape/io/vtk_convert.h"

namespace fairshape {
namespace fs = std::filesystem;
namespace {
// VTK prints its own errors ("ERROR: In vtkXMLParser.cxx, line ...") on stderr; fairshape
// reports every failure itself, with the file named, so VTK's output window stays silent.
void quiet_vtk() { vtkObject::GlobalWarningDisplayOff(); }

// Reserved array names for SurfaceMesh's crease and corner sharpness.
constexpr const char* kVertexSharpnessArray = "crease_vertex_sharpness";
constexpr const char* kCreaseEdgesArray = "crease_edges";


vtkSmartPointer<vtkDoubleArray> to_vtk_array(const std::string& name, const Eigen::MatrixXd& m) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name.c_str());
  a->SetNumberOfComponents(static_cast<int>(m.cols()));
  a->SetNumberOfTuples(m.rows());
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) a->SetComponent(r, static_cast<int>(c), m(r, c));
  return a;
}

// Every data array written has a row per point (or cell), finite values only.
void check_rows(const std::string& path, const std::string& name, const Eigen::MatrixXd& m, Eigen::Index expected) {
  if (m.rows() != expected)
    throw InvalidInput(path + ": data array '" + name + "' has " + std::to_string(m.rows()) +
                       " rows, expected " + std::to_string(expected));
  io::internal::require_finite(m, path, "data array '" + name + "' row");
}

vtkSmartPointer<vtkPoints> to_vtk_points(const MatrixX3& P) {
  auto pts = vtkSmartPointer<vtkPoints>::New();
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(P.rows());
  for (Eigen::Index i = 0; i < P.rows(); ++i) pts->SetPoint(i, P(i, 0), P(i, 1), P(i, 2));
  return pts;
}

}  // namespace

vtkSmartPointer<vtkPolyData> io::internal::to_polydata(const SurfaceMesh& mesh, const std::string& path) {
  io::internal::require_finite(mesh.positions(), path, "vertex");
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(to_vtk_points(mesh.positions()));
  vtkNew<vtkCellArray> polys;
  for (int f = 0; f < mesh.n_faces(); ++f) {
    const auto ids = mesh.face_vertices(f);
    polys->InsertNextCell(static_cast<vtkIdType>(ids.size()));
    for (int id : ids) polys->InsertCellPoint(id);
  }
  pd->SetPolys(polys);
  for (const auto& [name, m] : mesh.vertex_data) {
    check_rows(path, name, m, mesh.n_vertices());
    pd->GetPointData()->AddArray(to_vtk_array(name, m));
  }
  for (const auto& [name, m] : mesh.face_data) {
    check_rows(path, name, m, mesh.n_faces());
    pd->GetCellData()->AddArray(to_vtk_array(name, m));
  }
  // Crease and corner sharpness: edges are not cells of the file, so the sharp ones go into
  // field data as (a, b, sharpness) rows; vertex sharpness is a point array.
  if (!mesh.vertex_sharpness_array().empty()) {
    Eigen::MatrixXd vs(mesh.n_vertices(), 1);
    for (int v = 0; v < mesh.n_vertices(); ++v) vs(v, 0) = mesh.vertex_sharpness(v);
    pd->GetPointData()->AddArray(to_vtk_array(kVertexSharpnessArray, vs));
  }
  if (!mesh.edge_sharpness_array().empty()) {
    std::vector<int> sharp;
    for (int e = 0; e < mesh.n_edges(); ++e)
      if (mesh.edge_sharpness(e) > 0) sharp.push_back(e);
    Eigen::MatrixXd rows(static_cast<Eigen::Index>(sharp.size()), 3);
    for (std::size_t i = 0; i < sharp.size(); ++i)
      rows.row(static_cast<Eigen::Index>(i)) << mesh.from_vertex(2 * sharp[i]), mesh.to_vertex(2 * sharp[i]),
          mesh.edge_sharpness(sharp[i]);
    pd->GetFieldData()->AddArray(to_vtk_array(kCreaseEdgesArray, rows));
  }
  return pd;
}

namespace {
using io::internal::to_polydata;

// VTK's XML writers can report success after a failed write (ENOSPC, a file-size limit): a
// written file is complete only if it ends with the closing </VTKFile> tag.
bool complete_vtk_file(const fs::path& file) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in) return false;
  const std::streamoff size = in.tellg();
  const std::streamoff tail = std::min<std::streamoff>(size, 64);
  std::string end(static_cast<std::size_t>(tail), '\0');
  in.seekg(size - tail);
  in.read(end.data(), tail);
  return in.good() && end.find("</VTKFile>") != std::string::npos;
}

void write_polydata_atomically(vtkPolyData* pd, const std::string& path) {
  quiet_vtk();
  const fs::path tmp = temporary_sibling(path);
  vtkNew<vtkXMLPolyDataWriter> w;
  w->SetFileName(tmp.c_str());
  w->SetInputData(pd);
  w->SetDataModeToAppended();
  if (w->Write() != 1 || w->GetErrorCode() != 0 || !complete_vtk_file(tmp)) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw OutputError(path + ": VTK could not write the file completely (disk full, or a file-size limit?)");
  }
  commit_path(tmp, path);
}

void read_arrays(vtkFieldData* fd, std::map<std::string, Eigen::MatrixXd>& out) {
  for (int i = 0; i < fd->GetNumberOfArrays(); ++i) {
    vtkDataArray* a = vtkDataArray::SafeDownCast(fd->GetAbstractArray(i));
    if (!a || !a->GetName()) continue;
    Eigen::MatrixXd m(a->GetNumberOfTuples(), a->GetNumberOfComponents());
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      for (Eigen::Index c = 0; c < m.cols(); ++c) m(r, c) = a->GetComponent(r, static_cast<int>(c));
    out[a->GetName()] = std::move(m);
  }
}

// What VTK read, checked before it is used: points present, and every cell's ids in range,
// checked as 64-bit ids (4294967298 must not wrap to point 2).
void check_polydata(vtkPolyData* pd, const std::string& path) {
  if (!pd || pd->GetNumberOfPoints() == 0) throw IOError(path + ": no points in the VTK file");
  const char* kinds[] = {"vertex cell", "line", "polygon", "strip"};
  vtkCellArray* cells[] = {pd->GetVerts(), pd->GetLines(), pd->GetPolys(), pd->GetStrips()};
  vtkNew<vtkIdList> ids;
  for (int k = 0; k < 4; ++k) {
    vtkIdType cell = 0;
    for (cells[k]->InitTraversal(); cells[k]->GetNextCell(ids); ++cell)
      for (vtkIdType j = 0; j < ids->GetNumberOfIds(); ++j)
        if (ids->GetId(j) < 0 || ids->GetId(j) >= pd->GetNumberOfPoints())
          throw InvalidInput(path + ": " + kinds[k] + " " + std::to_string(cell) + " references point " +
                             std::to_string(ids->GetId(j)) + ", out of range [0, " + std::to_string(pd->GetNumberOfPoints()) +
                             ")");
  }
}

// `pd` passed check_polydata.
SurfaceMesh from_polydata(vtkPolyData* pd, const std::string& path) {
  MatrixX3 V(pd->GetNumberOfPoints(), 3);
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i) {
    double p[3];
    pd->GetPoint(i, p);
    V.row(i) << p[0], p[1], p[2];
  }
  PolygonList faces;
  vtkNew<vtkIdList> ids;
  vtkCellArray* polys = pd->GetPolys();
  polys->InitTraversal();
  while (polys->GetNextCell(ids)) {
    std::vector<int> f(ids->GetNumberOfIds());
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k) f[k] = static_cast<int>(ids->GetId(k));
    faces.push_back(std::move(f));
  }
  SurfaceMesh m;
  try {
    m = SurfaceMesh::from_polygons(V, faces);
  } catch (const Error& e) {
    throw InvalidInput(path + ": " + e.what());
  }
  read_arrays(pd->GetPointData(), m.vertex_data);
  read_arrays(pd->GetCellData(), m.face_data);
  std::map<std::string, Eigen::MatrixXd> field;
  read_arrays(pd->GetFieldData(), field);
  try {  // sharpness written by to_polydata, validated like an OBJ tag
    if (auto it = m.vertex_data.find(kVertexSharpnessArray); it != m.vertex_data.end()) {
      if (it->second.cols() != 1) throw InvalidInput(std::string(kVertexSharpnessArray) + " needs 1 component");
      for (int v = 0; v < m.n_vertices(); ++v)
        if (it->second(v, 0) != 0) m.set_vertex_sharpness(v, it->second(v, 0));
      m.vertex_data.erase(it);
    }
    if (auto it = field.find(kCreaseEdgesArray); it != field.end()) {
      if (it->second.cols() != 3) throw InvalidInput(std::string(kCreaseEdgesArray) + " needs 3 components (a, b, sharpness)");
      for (Eigen::Index r = 0; r < it->second.rows(); ++r) {
        const double a = it->second(r, 0), b = it->second(r, 1);
        if (!(a >= 0 && b >= 0 && a < m.n_vertices() && b < m.n_vertices() && a == std::floor(a) && b == std::floor(b)))
          throw InvalidInput(std::string(kCreaseEdgesArray) + " row " + std::to_string(r) + ": vertex ids out of range");
        m.set_edge_sharpness(static_cast<int>(a), static_cast<int>(b), it->second(r, 2));
      }
    }
  } catch (const InvalidInput& e) {
    throw InvalidInput(path + ": " + e.what());
  }
  return m;
}

}  // namespace

namespace io::internal {

vtkSmartPointer<vtkPolyData> read_checked_polydata(const std::string& path) {
  quiet_vtk();
  const std::string text = io::internal::checked_vtk_text(path);
  vtkNew<vtkXMLPolyDataReader> r;
  if (!r->CanReadFile(path.c_str())) throw IOError(path + ": not a VTK XML PolyData file");
  // The bytes already read and checked, not the file again.
  r->ReadFromInputStringOn();
  r->SetInputString(text);
  r->Update();
  vtkSmartPointer<vtkPolyData> pd = r->GetOutput();
  check_polydata(pd, path);
  return pd;
}

}  // namespace io::internal

void write_vtp(const SurfaceMesh& mesh, const std::string& path) {
  write_polydata_atomically(to_polydata(mesh, path), path);
}

void write_vtp(const MatrixX3& points, const std::vector<std::vector<int>>& polylines, const DataArrays& point_data,
               const std::string& path) {
  io::internal::require_finite(points, path, "point");
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(to_vtk_points(points));
  vtkNew<vtkCellArray> lines;
  std::vector<bool> on_line(static_cast<std::size_t>(points.rows()), false);
  for (const auto& line : polylines) {
    lines->InsertNextCell(static_cast<vtkIdType>(line.size()));
    for (int i : line) {
      FAIRSHAPE_ASSERT(i >= 0 && i < points.rows(), "a polyline through a point that does not exist");
      lines->InsertCellPoint(i);
      on_line[static_cast<std::size_t>(i)] = true;
    }
  }
  pd->SetLines(lines);
  // ParaView draws cells, not bare points: every point on no polyline is a vertex cell.
  vtkNew<vtkCellArray> verts;
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    if (!on_line[static_cast<std::size_t>(i)]) {
      verts->InsertNextCell(1);
      verts->InsertCellPoint(i);
    }
  pd->SetVerts(verts);
  for (const auto& [name, m] : point_data) {
    check_rows(path, name, m, points.rows());
    pd->GetPointData()->AddArray(to_vtk_array(name, m));
  }
  write_polydata_atomically(pd, path);
}

void write_vtp(const Polyline& curve, const DataArrays& point_data, const std::string& path) {
  std::vector<int> line(static_cast<std::size_t>(curve.n_points()));
  for (int i = 0; i < curve.n_points(); ++i) line[static_cast<std::size_t>(i)] = i;
  if (curve.closed && curve.n_points() > 0) line.push_back(0);
  write_vtp(curve.points, {line}, point_data, path);
}

SurfaceMesh read_vtp(const std::string& path) { return from_polydata(io::internal::read_checked_polydata(path), path); }

void write_vtm(const std::vector<NamedMesh>& blocks, const std::string& path) {
  quiet_vtk();
  const fs::path target(path);
  // The blocks first: a block refused (non-finite, mismatched arrays) leaves no staging folder.
  vtkNew<vtkMultiBlockDataSet> mb;
  mb->SetNumberOfBlocks(static_cast<unsigned>(blocks.size()));
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    mb->SetBlock(static_cast<unsigned>(i), to_polydata(*blocks[i].mesh, path));
    mb->GetMetaData(static_cast<unsigned>(i))->Set(vtkCompositeDataSet::NAME(), blocks[i].name.c_str());
  }
  const fs::path staging = temporary_sibling(target);  // a folder holding the .vtm and its data folder
  fs::create_directories(staging);
  vtkNew<vtkXMLMultiBlockDataWriter> w;
  const fs::path staged_file = staging / target.filename();
  w->SetFileName(staged_file.c_str());
  w->SetInputData(mb);
  w->SetDataModeToAppended();
  bool complete = w->Write() == 1 && w->GetErrorCode() == 0 && complete_vtk_file(staged_file);
  const fs::path data_dir = staging / target.stem();
  std::error_code ec;
  if (complete && fs::exists(data_dir))
    for (const auto& piece : fs::recursive_directory_iterator(data_dir, ec))
      if (piece.is_regular_file() && !complete_vtk_file(piece.path())) complete = false;
  if (!complete) {
    fs::remove_all(staging);
    throw OutputError(path + ": VTK could not write the multiblock file completely (disk full, or a file-size limit?)");
  }
  if (fs::exists(data_dir)) commit_path(data_dir, target.parent_path() / target.stem());
  commit_path(staged_file, target);
  fs::remove_all(staging);
}

std::vector<SurfaceMesh> read_vtm(const std::string& path) {
  // The .vtm and every piece it names: VTK reads the pieces itself, so each is checked first.
  std::vector<std::string> pieces;
  (void)io::internal::checked_vtk_text(path, &pieces);
  for (const std::string& piece : pieces) (void)io::internal::checked_vtk_text((fs::path(path).parent_path() / piece).string());
  vtkNew<vtkXMLMultiBlockDataReader> r;
  r->SetFileName(path.c_str());
  r->Update();
  auto* mb = vtkMultiBlockDataSet::SafeDownCast(r->GetOutput());
  if (!mb) throw IOError(path + ": not a VTK multiblock file");
  std::vector<SurfaceMesh> out;
  for (unsigned i = 0; i < mb->GetNumberOfBlocks(); ++i) {
    vtkPolyData* block = vtkPolyData::SafeDownCast(mb->GetBlock(i));
    check_polydata(block, path);
    out.push_back(from_polydata(block, path));
  }
  return out;
}

void write_pvd(const std::vector<std::pair<double, std::string>>& steps, const std::string& path) {
  vtkNew<vtkXMLDataElement> root;
  root->SetName("VTKFile");
  root->SetAttribute("type", "Collection");
  root->SetAttribute("version", "0.1");
  root->SetAttribute("byte_order", "LittleEndian");
  vtkNew<vtkXMLDataElement> coll;
  coll->SetName("Collection");
  for (const auto& [t, file] : steps) {
    vtkNew<vtkXMLDataElement> ds;
    ds->SetName("DataSet");
    ds->SetDoubleAttribute("timestep", t);
    ds->SetAttribute("part", "0");
    ds->SetAttribute("file", file.c_str());
    coll->AddNestedElement(ds);
  }
  root->AddNestedElement(coll);
  std::ostringstream os;
  root->PrintXML(os, vtkIndent());
  write_atomically(path, [&](std::ostream& out) { out << "<?xml version=\"1.0\"?>\n" << os.str(); });
}

}  // namespace fairshape
