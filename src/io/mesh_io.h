// Reading and writing polygon meshes and polylines: OBJ, OFF, PLY (ASCII and binary).
//
// Readers never crash on malformed input: they raise ParseError("file:line: problem").
// Writers use full double precision (%.17g) and write atomically (temporary + rename).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "fairshape/core/error.h"
#include "fairshape/mesh/polyline.h"
#include "fairshape/mesh/surface_mesh.h"

namespace fairshape {

// One sharpness tag of OpenSubdiv's OBJ extension, `t crease 2/1/0 a b s` (edge a-b) or
// `t corner 1/1/0 v s` (vertex v), 0-based ids; checked against the mesh once it is built.
struct SharpnessTag {
  bool corner = false;
  int a = -1, b = -1;  // b unused for a corner
  double sharpness = 0;
  long line = 0;       // where it was read, for error messages
};

// The raw content of a mesh file, before topology is checked.
struct MeshFile {
  MatrixX3 vertices;
  PolygonList faces;
  std::vector<std::vector<int>> lines;  // OBJ `l` statements (polylines), 0-based
  std::vector<SharpnessTag> sharpness;  // OBJ `t crease` / `t corner` tags
  std::vector<std::string> warnings;    // statements that were skipped, with counts
};

enum class MeshFormat { Obj, Off, Ply };
MeshFormat format_from_path(const std::string& path);  // by extension; throws IOError listing choices

// Parse from memory; `name` is used in error messages (fuzzers and tests call these).
MeshFile parse_obj(std::string_view text, const std::string& name);
MeshFile parse_off(std::string_view text, const std::string& name);
MeshFile parse_ply(std::string_view bytes, const std::string& name);
MeshFile read_mesh_file(const std::string& path);

//! Reads and validates a surface mesh, crease/corner tags applied (SurfaceMesh sharpness).
//! \throw IOError, ParseError (also a tag naming a missing edge or a bad sharpness: file and
//! line), InvalidInput, TopologyError (the latter two prefixed with the path).
SurfaceMesh read_mesh(const std::string& path);
//! The same from a file's content already read (`path` names it in errors).
SurfaceMesh mesh_from_file(const MeshFile& data, const std::string& path);

struct WriteOptions {
  bool binary = false;  // PLY only: binary little endian
};
void write_mesh(const SurfaceMesh& mesh, const std::string& path, const WriteOptions& opt = {});
void write_mesh_file(const MeshFile& data, const std::string& path, const WriteOptions& opt = {});

//! The polyline of an OBJ file (`v` and `l` lines; several `l` statements are joined when each
//! continues the curve before it, and refused otherwise); closed when it ends where it began.
Polyline read_polyline(const std::string& path);
void write_polyline(const Polyline& curve, const std::string& path);

}  // namespace fairshape
