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
#include "fairshape/io/text_scanner.h"
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

void check_rows(const std::string& path, const std::string& name, Eigen::Index rows, Eigen::Index expected) {
  if (rows != expected)
    throw InvalidInput(path + ": data array '" + name + "' has " + std::to_string(rows) +
                       " rows, expected " + std::to_string(expected));
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
    check_rows(path, name, m.rows(), mesh.n_vertices());
    pd->GetPointData()->AddArray(to_vtk_array(name, m));
  }
  for (const auto& [name, m] : mesh.face_data) {
    check_rows(path, name, m.rows(), mesh.n_faces());
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

// The element counts a VTK XML file declares (NumberOfPoints="...", NumberOfPolys="...")
// checked before VTK allocates for them: an absurd count is a refusal, not std::bad_alloc.
// Compressed payloads can be far smaller than what they hold, so the bound is absolute.
constexpr long long kMaxVtkElements = 100'000'000;


constexpr unsigned long long kMaxCompressionBlock = 1ULL << 26;  // 64 MiB

// Standard base64 (VTK's encoding of appended data); stops at the first character outside it.
std::string decode_base64(std::string_view text) {
  static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  unsigned value = 0;
  int bits = 0;
  for (char c : text) {
    const std::size_t k = alphabet.find(c);
    if (k == std::string::npos) break;
    value = (value << 6) | static_cast<unsigned>(k);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<char>((value >> bits) & 0xFF));
    }
  }
  return out;
}

// Appended data: every array's header (its byte count, or for compressed data the block count
// and sizes) must describe bytes the file holds — zlib expands at most 1032:1 — or VTK
// allocates what a corrupted header claims (found by fuzz_read_vtp: 2.7 GB from a 3 KB file).
// Raw data is read as is; base64 data is decoded header by header (VTK encodes each header
// on its own), offsets then counting encoded characters.
void check_appended_headers(const std::string& bytes, const std::string& path) {
  const std::size_t tag = bytes.find("<AppendedData");
  if (tag == std::string::npos) return;
  const std::size_t close = bytes.find('>', tag);
  if (close == std::string::npos) throw IOError(path + ": AppendedData tag without its end");
  const bool base64 = bytes.substr(tag, close - tag).find("encoding=\"base64\"") != std::string::npos;
  const std::size_t marker = bytes.find('_', close);
  if (marker == std::string::npos) throw IOError(path + ": AppendedData without its '_' marker");
  const std::size_t base = marker + 1;
  const std::string xml = bytes.substr(0, tag);
  const bool big_endian = xml.find("byte_order=\"BigEndian\"") != std::string::npos;
  const std::size_t word = xml.find("header_type=\"UInt64\"") != std::string::npos ? 8 : 4;
  const bool compressed = xml.find("compressor=\"") != std::string::npos;
  const auto fail = [&](const std::string& what) { throw IOError(path + ": an appended array's header " + what + " (corrupt file?)"); };
  // `count` header words at `at` (raw bytes, or the base64 unit holding `total` words).
  const auto words = [&](std::size_t at, std::size_t count, std::size_t total) {
    std::string raw;
    if (base64) {
      const std::size_t chars = (total * word + 2) / 3 * 4;
      if (at + chars > bytes.size()) fail("lies past the end of the file");
      raw = decode_base64(std::string_view(bytes).substr(at, chars));
    } else {
      if (at + count * word > bytes.size()) fail("lies past the end of the file");
      raw = bytes.substr(at, count * word);
    }
    if (raw.size() < count * word) fail("is cut short");
    std::vector<unsigned long long> out(count, 0);
    for (std::size_t k = 0; k < count; ++k)
      for (std::size_t b = 0; b < word; ++b) {  // most significant byte first, in the file's byte order
        const auto byte = static_cast<unsigned char>(raw[k * word + (big_endian ? b : word - 1 - b)]);
        out[k] = (out[k] << 8) | byte;
      }
    return out;
  };
  for (std::size_t pos = xml.find(" offset=\""); pos != std::string::npos; pos = xml.find(" offset=\"", pos + 1)) {
    const std::size_t end = xml.find('"', pos + 9);
    const std::string value = xml.substr(pos + 9, end == std::string::npos ? 0 : end - pos - 9);
    if (value.empty() || value.size() > 15 || value.find_first_not_of("0123456789") != std::string::npos)
      throw IOError(path + ": appended-data offset '" + value.substr(0, 24) + "' is not a byte offset");
    const std::size_t at = base + std::stoull(value);
    if (at > bytes.size()) fail("starts past the end of the file");
    // What the file holds after the header, as decoded bytes.
    const long double held = base64 ? (bytes.size() - at) * 0.75L : static_cast<long double>(bytes.size() - at);
    if (!compressed) {
      if (words(at, 1, 1)[0] > held) fail("claims more bytes than the file holds");
      continue;
    }
    const auto head = words(at, 3, 3);
    const unsigned long long blocks = head[0], block = head[1], last = head[2];
    if (blocks > held / word) fail("claims more compressed blocks than the file holds");
    const auto all = words(at, 3 + static_cast<std::size_t>(blocks), 3 + static_cast<std::size_t>(blocks));
    long double stored = 0;
    for (std::size_t b = 0; b < blocks; ++b) stored += all[3 + b];
    const long double expanded = blocks == 0 ? 0.0L : (blocks - 1.0L) * block + (last ? last : block);
    // VTK allocates one block-sized buffer whatever the blocks hold: its writers use 32 KiB.
    if (stored > held || expanded > 1032.0L * stored + 4096.0L || block > kMaxCompressionBlock)
      fail("is inconsistent with the compressed data that follows");
  }
}

// The file's bytes, its declared counts and appended headers checked (see above).
std::string checked_vtk_text(const std::string& path) {
  quiet_vtk();
  std::string text = io::internal::read_whole_file(path);
  check_appended_headers(text, path);
  // The declared counts live in the XML, not in the binary payload after <AppendedData>.
  const std::string head = text.substr(0, text.find("<AppendedData"));
  for (std::size_t pos = head.find("NumberOf"); pos != std::string::npos; pos = head.find("NumberOf", pos + 1)) {
    const std::size_t eq = head.find("=\"", pos);
    if (eq == std::string::npos || eq - pos > 32) continue;
    const std::size_t end = head.find('"', eq + 2);
    if (end == std::string::npos) continue;
    const std::string value = head.substr(eq + 2, end - eq - 2);
    const std::string name = head.substr(pos, eq - pos);
    if (value.empty() || value.find_first_not_of("0123456789") != std::string::npos || value.size() > 12 ||
        std::stoll(value) > kMaxVtkElements)
      throw IOError(path + ": " + name + "=\"" + value.substr(0, 24) + "\" is not a count up to " +
                    std::to_string(kMaxVtkElements) + " (the largest mesh fairshape reads)");
  }
  return text;
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
  const std::string text = checked_vtk_text(path);
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
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(to_vtk_points(points));
  vtkNew<vtkCellArray> lines;
  for (const auto& line : polylines) {
    lines->InsertNextCell(static_cast<vtkIdType>(line.size()));
    for (int i : line) {
      FAIRSHAPE_ASSERT(i >= 0 && i < points.rows(), "a polyline through a point that does not exist");
      lines->InsertCellPoint(i);
    }
  }
  pd->SetLines(lines);
  for (const auto& [name, m] : point_data) {
    check_rows(path, name, m.rows(), points.rows());
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
  const fs::path staging = temporary_sibling(target);  // a folder holding the .vtm and its data folder
  fs::create_directories(staging);
  vtkNew<vtkMultiBlockDataSet> mb;
  mb->SetNumberOfBlocks(static_cast<unsigned>(blocks.size()));
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    mb->SetBlock(static_cast<unsigned>(i), to_polydata(*blocks[i].mesh, path));
    mb->GetMetaData(static_cast<unsigned>(i))->Set(vtkCompositeDataSet::NAME(), blocks[i].name.c_str());
  }
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
  const std::string text = checked_vtk_text(path);
  for (std::size_t pos = text.find(" file=\""); pos != std::string::npos; pos = text.find(" file=\"", pos + 1)) {
    const std::size_t end = text.find('"', pos + 7);
    if (end == std::string::npos) break;
    (void)checked_vtk_text((fs::path(path).parent_path() / text.substr(pos + 7, end - pos - 7)).string());
  }
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
