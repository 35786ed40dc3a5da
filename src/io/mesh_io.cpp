#include "fairshape/io/mesh_io.h"

#include <algorithm>
#include <bit>
#include <cinttypes>
#include <cstdio>
#include <filesystem>

#include "fairshape/core/atomic_file.h"
#include "fairshape/io/finite_output.h"
#include "fairshape/io/text_scanner.h"

namespace fairshape {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (auto& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// %.17g round-trips every double exactly.
void put_point(std::ostream& os, const char* prefix, const Eigen::Ref<const Eigen::RowVector3d>& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%s%.17g %.17g %.17g\n", prefix, p[0], p[1], p[2]);
  os << buf;
}

void write_obj(std::ostream& os, const MeshFile& d) {
  os << "# written by fairshape\n";
  for (Eigen::Index v = 0; v < d.vertices.rows(); ++v) put_point(os, "v ", d.vertices.row(v));
  for (const auto& f : d.faces) {
    os << 'f';
    for (int id : f) os << ' ' << id + 1;
    os << '\n';
  }
  for (const auto& l : d.lines) {
    os << 'l';
    for (int id : l) os << ' ' << id + 1;
    os << '\n';
  }
  char buf[32];
  for (const auto& t : d.sharpness) {  // OpenSubdiv's tag syntax, 0-based ids
    std::snprintf(buf, sizeof buf, "%.17g", t.sharpness);
    if (t.corner) os << "t corner 1/1/0 " << t.a << ' ' << buf << '\n';
    else os << "t crease 2/1/0 " << t.a << ' ' << t.b << ' ' << buf << '\n';
  }
}

void write_off(std::ostream& os, const MeshFile& d) {
  os << "OFF\n" << d.vertices.rows() << ' ' << d.faces.size() << " 0\n";
  for (Eigen::Index v = 0; v < d.vertices.rows(); ++v) put_point(os, "", d.vertices.row(v));
  for (const auto& f : d.faces) {
    os << f.size();
    for (int id : f) os << ' ' << id;
    os << '\n';
  }
}

template <class T>
void put_le(std::ostream& os, T v) {
  static_assert(std::endian::native == std::endian::little, "big-endian hosts: add byte swapping");
  os.write(reinterpret_cast<const char*>(&v), sizeof v);
}

void write_ply(std::ostream& os, const MeshFile& d, bool binary) {
  std::size_t max_face = 0;
  for (const auto& f : d.faces) max_face = std::max(max_face, f.size());
  const char* count_type = max_face <= 255 ? "uchar" : "int";
  os << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\n"
     << "comment written by fairshape\nelement vertex " << d.vertices.rows()
     << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << d.faces.size()
     << "\nproperty list " << count_type << " int vertex_indices\nend_header\n";
  if (!binary) {
    for (Eigen::Index v = 0; v < d.vertices.rows(); ++v) put_point(os, "", d.vertices.row(v));
    for (const auto& f : d.faces) {
      os << f.size();
      for (int id : f) os << ' ' << id;
      os << '\n';
    }
    return;
  }
  for (Eigen::Index v = 0; v < d.vertices.rows(); ++v)
    for (int k = 0; k < 3; ++k) put_le<double>(os, d.vertices(v, k));
  for (const auto& f : d.faces) {
    if (max_face <= 255) put_le<std::uint8_t>(os, static_cast<std::uint8_t>(f.size()));
    else put_le<std::int32_t>(os, static_cast<std::int32_t>(f.size()));
    for (int id : f) put_le<std::int32_t>(os, id);
  }
}

}  // namespace

MeshFormat format_from_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj") return MeshFormat::Obj;
  if (ext == ".off") return MeshFormat::Off;
  if (ext == ".ply") return MeshFormat::Ply;
  throw IOError(path + ": unknown mesh format '" + ext + "' (valid: .obj, .off, .ply)");
}

MeshFile read_mesh_file(const std::string& path) {
  const MeshFormat fmt = format_from_path(path);
  const std::string bytes = io::internal::read_whole_file(path);
  switch (fmt) {
    case MeshFormat::Obj: return parse_obj(bytes, path);
    case MeshFormat::Off: return parse_off(bytes, path);
    case MeshFormat::Ply: return parse_ply(bytes, path);
  }
  throw IOError(path + ": unreachable format");
}

SurfaceMesh read_mesh(const std::string& path) { return mesh_from_file(read_mesh_file(path), path); }

SurfaceMesh mesh_from_file(const MeshFile& data, const std::string& path) {
  SurfaceMesh mesh;
  try {
    mesh = SurfaceMesh::from_polygons(data.vertices, data.faces);
  } catch (const InvalidInput& e) {
    throw InvalidInput(path + ": " + e.what());
  } catch (const TopologyError& e) {
    throw TopologyError(path + ": " + e.what());
  }
  // Tags refer to edges, which exist only now: a tag on a missing edge is reported at its line.
  for (const SharpnessTag& t : data.sharpness) {
    try {
      if (t.corner) mesh.set_vertex_sharpness(t.a, t.sharpness);
      else mesh.set_edge_sharpness(t.a, t.b, t.sharpness);
    } catch (const InvalidInput& e) {
      throw ParseError(path, t.line, e.what());
    }
  }
  return mesh;
}

void write_mesh_file(const MeshFile& data, const std::string& path, const WriteOptions& opt) {
  const MeshFormat fmt = format_from_path(path);
  if (fmt != MeshFormat::Obj && !data.lines.empty())
    throw IOError(path + ": polylines can only be written as .obj");
  io::internal::require_finite(data.vertices, path, "vertex");
  write_atomically(
      path,
      [&](std::ostream& os) {
        switch (fmt) {
          case MeshFormat::Obj: write_obj(os, data); break;
          case MeshFormat::Off: write_off(os, data); break;
          case MeshFormat::Ply: write_ply(os, data, opt.binary); break;
        }
      },
      opt.binary);
}

void write_mesh(const SurfaceMesh& mesh, const std::string& path, const WriteOptions& opt) {
  MeshFile d;
  d.vertices = mesh.positions();
  d.faces = mesh.polygons();
  if (mesh.has_sharpness() && format_from_path(path) == MeshFormat::Obj) {
    for (int e = 0; e < mesh.n_edges(); ++e)
      if (mesh.edge_sharpness(e) > 0)
        d.sharpness.push_back({false, mesh.from_vertex(2 * e), mesh.to_vertex(2 * e), mesh.edge_sharpness(e), 0});
    for (int v = 0; v < mesh.n_vertices(); ++v)
      if (mesh.vertex_sharpness(v) > 0) d.sharpness.push_back({true, v, -1, mesh.vertex_sharpness(v), 0});
  }
  write_mesh_file(d, path, opt);
}

namespace {

// The line numbers of a file's `l` statements, for naming them.
std::vector<long> polyline_statement_lines(std::string_view text, const std::string& path) {
  io::internal::TextScanner s(text, path);
  std::vector<long> out;
  while (s.next_line())
    if (s.tokens()[0] == "l") out.push_back(s.line());
  return out;
}

}  // namespace

// Exporters split one curve into several `l` statements that share their end vertices
// (`l 1 … 65`, `l 65 … 129`): the pieces are joined in file order, each starting where the
// curve so far ends (a piece written backwards is turned round; so is the first, when the
// second starts at its beginning). Pieces that do not chain so are several curves in one
// file: refused, naming the lines, rather than editing the first and dropping the others.
Polyline read_polyline(const std::string& path) {
  if (format_from_path(path) != MeshFormat::Obj)
    throw IOError(path + ": polylines are read from .obj files ('v' and 'l' lines)");
  const std::string bytes = io::internal::read_whole_file(path);
  const MeshFile d = parse_obj(bytes, path);
  if (d.lines.empty()) throw InvalidInput(path + ": no 'l' statement (polyline) in the file");
  // Pieces meet at a shared vertex, or at two vertices written twice at the same place.
  const auto meet = [&d](int a, int b) { return a == b || d.vertices.row(a) == d.vertices.row(b); };
  std::vector<int> ids = d.lines.front();
  for (std::size_t k = 1; k < d.lines.size(); ++k) {
    std::vector<int> piece = d.lines[k];
    const bool at_end = meet(ids.back(), piece.front()) || meet(ids.back(), piece.back());
    if (k == 1 && !at_end && (meet(ids.front(), piece.front()) || meet(ids.front(), piece.back())))
      std::reverse(ids.begin(), ids.end());
    if (!meet(ids.back(), piece.front()) && meet(ids.back(), piece.back())) std::reverse(piece.begin(), piece.end());
    if (!meet(ids.back(), piece.front())) {
      const std::vector<long> at = polyline_statement_lines(bytes, path);
      std::string before;
      for (std::size_t j = 0; j < k; ++j) before += (j ? ", " : "") + std::to_string(at[j]);
      throw ParseError(path, at[k],
                       "this polyline (vertices " + std::to_string(d.lines[k].front() + 1) + " to " +
                           std::to_string(d.lines[k].back() + 1) + ") does not continue the curve of line(s) " + before +
                           ", which ends at vertex " + std::to_string(ids.back() + 1) +
                           ": fairshape edits one curve per file (join the pieces end to start, or put each curve in its own file)");
    }
    ids.insert(ids.end(), piece.begin() + 1, piece.end());
  }
  Polyline c;
  c.closed = ids.size() > 2 && ids.front() == ids.back();
  if (c.closed) ids.pop_back();
  c.points.resize(static_cast<Eigen::Index>(ids.size()), 3);
  for (std::size_t i = 0; i < ids.size(); ++i) c.points.row(static_cast<Eigen::Index>(i)) = d.vertices.row(ids[i]);
  return c;
}

void write_polyline(const Polyline& curve, const std::string& path) {
  MeshFile d;
  d.vertices = curve.points;
  std::vector<int> ids(curve.n_points());
  for (int i = 0; i < curve.n_points(); ++i) ids[i] = i;
  if (curve.closed && !ids.empty()) ids.push_back(0);
  d.lines.push_back(std::move(ids));
  write_mesh_file(d, path);
}

}  // namespace fairshape
