// fairshape.Mesh (the half-edge SurfaceMesh) and mesh files.
// Copies: Mesh(V, F) copies V and F into the mesh (it owns its storage); Mesh.V is a read-only
// view of the mesh's own positions, no copy: a writeable one would let NaN past the check that
// construction and the setter make, so positions change by assigning Mesh.V = array (checked,
// copied in). Mesh.F is built on each access (the mesh stores half-edges, not a face array).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <filesystem>

#include "bindings.h"
#include "checks.h"
#include "convert.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/io/vtk_io.h"
#include "fairshape/mesh/mesh_stats.h"

namespace py = pybind11;

namespace fairshape::python {
namespace {

bool is_vtp(const std::string& path) { return std::filesystem::path(path).extension() == ".vtp"; }

SurfaceMesh load(const std::string& path) {
  if (is_vtp(path)) return read_vtp(path);
  return read_mesh(path);
}

void save(const SurfaceMesh& mesh, const std::string& path, bool binary) {
  if (is_vtp(path)) {
    if (binary) throw InvalidConfig("write_mesh: binary=True: only PLY output has a binary form (output: " + path + ")");
    write_vtp(mesh, path);
    return;
  }
  if (binary && format_from_path(path) != MeshFormat::Ply)
    throw InvalidConfig("write_mesh: binary=True: only PLY output has a binary form (output: " + path + ")");
  write_mesh(mesh, path, {binary});
}

}  // namespace

void bind_mesh(py::module_& m) {
  py::class_<SurfaceMesh>(m, "Mesh",
                          "A manifold polygon mesh (half-edge connectivity, any face size, boundary, any genus).\n\n"
                          "Mesh(V, F): V is an n×3 float64 array of positions, F an m×k integer array (k corners "
                          "per face) or a list of vertex-id lists (polygons of any size). Both are copied.\n"
                          "Raises InvalidInput (bad ids, non-finite coordinates) or TopologyError (non-manifold).")
      .def(py::init([](const Eigen::Ref<const MatrixX3>& V, py::handle F) {
             PolygonList faces = faces_from_python(F);
             return SurfaceMesh::from_polygons(MatrixX3(V), faces);
           }),
           py::arg("V"), py::arg("F"))
      .def_property(
          "V",
          [](py::object self) {
            SurfaceMesh& mesh = self.cast<SurfaceMesh&>();
            return view(mesh.positions().data(), mesh.n_vertices(), 3, self, false);
          },
          [](SurfaceMesh& mesh, const Eigen::Ref<const MatrixX3>& V) {
            if (V.rows() != mesh.n_vertices())
              throw InvalidInput("Mesh.V: expected " + std::to_string(mesh.n_vertices()) + "×3 positions, got " +
                                 std::to_string(V.rows()) + "×3");
            if (!V.allFinite()) throw InvalidInput("Mesh.V: positions must be finite");
            mesh.positions() = V;
          },
          "n×3 float64: the vertex positions, a read-only view of the mesh's own array (no copy; "
          "the mesh must outlive it, which the view ensures). Assigning an n×3 array of finite values "
          "copies it in (mesh.V = V2); writing into the view is refused, since it would skip that check.")
      .def_property_readonly(
          "F", [](const SurfaceMesh& mesh) { return faces_to_python(mesh.polygons()); },
          "m×k int32 array when every face has k corners, else a list of vertex-id lists (a new copy each access).")
      .def_property_readonly("n_vertices", &SurfaceMesh::n_vertices)
      .def_property_readonly("n_faces", &SurfaceMesh::n_faces)
      .def_property_readonly("n_edges", &SurfaceMesh::n_edges)
      .def("boundary_loops", &SurfaceMesh::boundary_loops,
           "Boundary loops, each a list of vertex ids in the order of its boundary half-edges.")
      .def(
          "vertex_neighbors",
          [](const SurfaceMesh& mesh, long long v) {
            return mesh.vertex_neighbors(index_arg(v, mesh.n_vertices(), "Mesh.vertex_neighbors", "v", "vertices"));
          },
          py::arg("v"), "Edge neighbours of vertex v (0..n_vertices-1), counter-clockwise.")
      .def("stats", [](const SurfaceMesh& mesh) { return format_stats(compute_stats(mesh)); },
           "The summary `fairshape info` prints: counts, polygon sizes, boundary loops, genus, valences, bbox.")
      .def("copy", [](const SurfaceMesh& mesh) { return checked(SurfaceMesh(mesh), "Mesh.copy"); }, "A deep copy.")
      .def("__repr__", [](const SurfaceMesh& mesh) {
        return "<fairshape.Mesh " + std::to_string(mesh.n_vertices()) + " vertices, " + std::to_string(mesh.n_faces()) +
               " faces>";
      });

  m.def(
      "read_mesh", [](const std::string& path) { return checked(load(path), "read_mesh " + path); }, py::arg("path"),
      "Reads a mesh (.obj with OpenSubdiv crease/corner tags, .off, .ply, .vtp) and checks its topology.\n"
      "Returns a Mesh. Raises ParseError (file, line), MissingFileError (a FileNotFoundError), FileError, InvalidInput, TopologyError.");
  m.def(
      "write_mesh",
      [](const SurfaceMesh& mesh, const std::string& path, bool binary) { save(mesh, path, binary); },
      py::arg("mesh"), py::arg("path"), py::arg("binary") = false,
      "Writes a Mesh by extension (.obj .off .ply .vtp), full precision (%.17g), atomically. binary=True: PLY only.");
  m.def(
      "read_arrays",
      [](const std::string& path) {
        const SurfaceMesh mesh = checked(load(path), "read_arrays " + path);
        return py::make_tuple(MatrixX3(mesh.positions()), faces_to_python(mesh.polygons()));
      },
      py::arg("path"), "(V, F) of a mesh file, like igl.read_triangle_mesh: V n×3 float64 (a copy), F as Mesh.F.");
}

}  // namespace fairshape::python
