// fairshape.MultiresSurface and the subdivision functions: uniform refinement, the operators
// S_l, limit positions and normals.
// Copies: positions(level) and details(level) are read-only views of the hierarchy's arrays
// (no copy; change them with set_level_positions / set_details, which copy in); mesh(level)
// returns a copy (a Mesh is mutable, a hierarchy's level is not); sparse matrices are new
// scipy.sparse.csr_matrix objects.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "checks.h"
#include "convert.h"
#include "fairshape/subdivision/limit.h"
#include "fairshape/subdivision/multires_surface.h"
#include "fairshape/subdivision/subdivider.h"

namespace py = pybind11;
using namespace pybind11::literals;

namespace fairshape::python {
namespace {

DetailSpace space_arg(const std::string& s) {
  if (s == "world") return DetailSpace::World;
  if (s == "local") return DetailSpace::Local;
  throw InvalidConfig("space '" + s + "': expected 'world' or 'local'");
}

// The level of a hierarchy, -1 meaning the finest (as in configs).
int level_arg(const MultiresSurface& h, int level, const char* who) {
  const int l = level < 0 ? h.levels() + 1 + level : level;
  if (l < 0 || l > h.levels())
    throw InvalidIndex(std::string(who) + ": level " + std::to_string(level) + " is not in the hierarchy (levels 0.." +
                       std::to_string(h.levels()) + ", or -1 for the finest)");
  return l;
}

RowSparseMatrix csr(const SparseMatrix& S) { return RowSparseMatrix(S); }

#define FAIRSHAPE_SCHEME_ARGS                                                                        \
  py::arg("scheme") = "catmull-clark", py::arg("boundary") = "edge-only", py::arg("weights") = "loop", \
  py::arg("crease") = "uniform"

}  // namespace

void bind_hierarchy(py::module_& m) {
  py::class_<MultiresSurface>(
      m, "MultiresSurface",
      "A multiresolution subdivision surface (M^0..M^L): X_{l+1} = S_l X_l + D_{l+1} (details in world "
      "coordinates, or in the local frames of the predicted surface).\n\n"
      "MultiresSurface(base, levels, scheme=..., boundary=..., weights=..., crease=..., implementation='optimized'):"
      " zero details, every level the subdivision of the one below. Levels are 0..levels; -1 names the finest.")
      .def(py::init([](const SurfaceMesh& base, int levels, const std::string& scheme, const std::string& boundary,
                       const std::string& weights, const std::string& crease, const std::string& implementation) {
             const SubdivisionOptions opt = subdivision_arg(scheme, boundary, weights, crease);
             const Backend b = backend_arg(implementation);
             py::gil_scoped_release release;
             return MultiresSurface(base, opt, levels, b);
           }),
           py::arg("base"), py::arg("levels"), FAIRSHAPE_SCHEME_ARGS, py::arg("implementation") = "optimized")
      .def_static(
          "analyze",
          [](const SurfaceMesh& base, const Eigen::Ref<const MatrixX3>& finest, int levels, const std::string& scheme,
             const std::string& boundary, const std::string& weights, const std::string& crease,
             const std::string& implementation) {
            const SubdivisionOptions opt = subdivision_arg(scheme, boundary, weights, crease);
            const Backend b = backend_arg(implementation);
            finite_arg(finest, "MultiresSurface.analyze: finest");
            const MatrixX3 X(finest);
            py::gil_scoped_release release;
            return checked(MultiresSurface::analyze(base, X, opt, levels, b), "MultiresSurface.analyze");
          },
          py::arg("base"), py::arg("finest"), py::arg("levels"), FAIRSHAPE_SCHEME_ARGS,
          py::arg("implementation") = "optimized",
          "Analysis of a semi-regular mesh: finest is the n_L×3 float64 positions of base refined `levels` times "
          "(vertex ids as subdivide numbers them). Coarser levels are least-squares fits, details the residuals, so "
          "the finest level is reproduced.")
      .def_static(
          "load", [](const std::string& path, const std::string& implementation) {
            return checked(MultiresSurface::load(path, backend_arg(implementation)), "MultiresSurface.load " + path);
          },
          py::arg("path"), py::arg("implementation") = "optimized",
          "A hierarchy saved by save() or `fairshape remesh` (.vtm with its JSON sidecar).")
      .def("save", &MultiresSurface::save, py::arg("path"), "Every level as a block of a .vtm, plus a JSON sidecar.")
      .def_property_readonly("levels", &MultiresSurface::levels, "L: the finest level's index.")
      .def_property_readonly("scheme", [](const MultiresSurface& h) { return std::string(to_string(h.options().scheme)); })
      .def(
          "mesh",
          [](const MultiresSurface& h, int level) {
            return checked(SurfaceMesh(h.mesh(level_arg(h, level, "mesh"))), "MultiresSurface.mesh");
          },
          py::arg("level") = -1, "A copy of level `level`'s mesh.")
      .def(
          "positions",
          [](py::object self, int level) {
            const MultiresSurface& h = self.cast<const MultiresSurface&>();
            const SurfaceMesh& mesh = h.mesh(level_arg(h, level, "positions"));
            finite_result(mesh, "MultiresSurface.positions");
            return view(mesh.positions().data(), mesh.n_vertices(), 3, self, false);
          },
          py::arg("level") = -1, "n_l×3 float64: level `level`'s positions, a read-only view (no copy).")
      .def(
          "details",
          [](py::object self, int level, const std::string& space) {
            const MultiresSurface& h = self.cast<const MultiresSurface&>();
            const int l = level_arg(h, level, "details");
            if (l == 0) throw InvalidInput("details: level 0 (the base) has no details: levels 1.." + std::to_string(h.levels()));
            const MatrixX3& d = h.details(l, space_arg(space));
            finite_result(d, "MultiresSurface.details");
            return view(d.data(), d.rows(), 3, self, false);
          },
          py::arg("level") = -1, py::arg("space") = "local",
          "n_l×3 float64: the details D_l of level l ≥ 1, 'local' (frames of the predicted surface: t1, t2, n) or "
          "'world' coordinates; a read-only view (no copy).")
      .def(
          "set_level_positions",
          [](MultiresSurface& h, int level, const Eigen::Ref<const MatrixX3>& X) {
            finite_arg(X, "set_level_positions: X");
            h.set_level_positions(level_arg(h, level, "set_level_positions"), MatrixX3(X));
          },
          py::arg("level"), py::arg("X"), "Replaces level `level`'s positions (n_l×3, copied); then synthesize(from_level=level).")
      .def(
          "set_details",
          [](MultiresSurface& h, int level, const Eigen::Ref<const MatrixX3>& d, const std::string& space) {
            finite_arg(d, "set_details: details");
            h.set_details(level_arg(h, level, "set_details"), MatrixX3(d), space_arg(space));
          },
          py::arg("level"), py::arg("details"), py::arg("space") = "local", "Replaces level l's details (n_l×3, copied).")
      .def(
          "synthesize",
          [](MultiresSurface& h, int from_level, const std::string& keep) {
            const int l = level_arg(h, from_level, "synthesize");
            const DetailSpace s = space_arg(keep);
            py::gil_scoped_release release;
            h.synthesize_from(l, s);
          },
          py::arg("from_level") = 0, py::arg("keep") = "local",
          "Rebuilds the levels above from_level from it, keeping the details of `keep` ('local': they follow the "
          "surface; 'world': they translate).")
      .def(
          "subdivision_operator",
          [](const MultiresSurface& h, long long level) {
            const int l = index_arg(level, h.levels(), "subdivision_operator", "level", "operators S_0..S_{L-1}");
            return checked(csr(h.subdivision_operator(l)), "subdivision_operator");
          },
          py::arg("level"), "S_level (level 0..levels-1): scipy.sparse.csr_matrix n_{l+1}×n_l (a copy).")
      .def(
          "prolongation",
          [](const MultiresSurface& h, int from, int to) {
            return checked(csr(h.prolongation(level_arg(h, from, "prolongation"), level_arg(h, to, "prolongation"))),
                           "prolongation");
          },
          py::arg("from_level"), py::arg("to_level"), "S_{to-1}···S_from: csr_matrix n_to×n_from.")
      .def("copy", [](const MultiresSurface& h) { return checked(MultiresSurface(h), "MultiresSurface.copy"); },
           "A deep copy.")
      .def("__repr__", [](const MultiresSurface& h) {
        return "<fairshape.MultiresSurface " + std::string(to_string(h.options().scheme)) + ", levels 0.." +
               std::to_string(h.levels()) + ", " + std::to_string(h.mesh(h.levels()).n_vertices()) + " vertices at the finest>";
      });

  m.def("relative_detail_change", &relative_detail_change, py::arg("before"), py::arg("after"),
        "RMS change of the local detail vectors from `before` to `after`, relative to their RMS size before "
        "(NaN without details). runs.csv's detail_change is this with after = MultiresSurface.analyze(base, "
        "edited finest positions, levels): the edit analysed again.");

  m.def(
      "subdivide",
      [](const SurfaceMesh& mesh, int levels, const std::string& scheme, const std::string& boundary,
         const std::string& weights, const std::string& crease, const std::string& implementation,
         bool operators) -> py::object {
        const SubdivisionOptions opt = subdivision_arg(scheme, boundary, weights, crease);
        const Backend b = backend_arg(implementation);
        std::vector<SparseMatrix> S;
        std::vector<SurfaceMesh> out;
        {
          py::gil_scoped_release release;
          out = refine_uniform(mesh, opt, levels, b, {}, operators ? &S : nullptr);
        }
        for (std::size_t l = 0; l < out.size(); ++l) finite_result(out[l], "subdivide, level " + std::to_string(l));
        if (!operators) return py::cast(std::move(out));
        py::list ops;
        for (const auto& s : S) ops.append(checked(csr(s), "subdivide: S"));
        return py::make_tuple(std::move(out), ops);
      },
      py::arg("mesh"), py::arg("levels"), FAIRSHAPE_SCHEME_ARGS, py::arg("implementation") = "optimized",
      py::arg("operators") = false,
      (std::string("`levels` uniform subdivision steps: a list of levels + 1 Meshes, the input first. "
                   "operators=True returns (meshes, [S_0, ..., S_{levels-1}]), S_l a csr_matrix n_{l+1}×n_l whose "
                   "rows sum to 1. Without operators the positions are `fairshape subdivide`'s bit for bit (stencils "
                   "applied on the fly); with them they are S_l X_l, equal to rounding. ") +
       kSchemeArgsDoc).c_str());
  m.def(
      "limit_positions",
      [](const SurfaceMesh& mesh, const std::string& scheme, const std::string& boundary, const std::string& weights,
         const std::string& crease) {
        const SubdivisionOptions opt = subdivision_arg(scheme, boundary, weights, crease);
        MatrixX3 X;
        {
          py::gil_scoped_release release;
          X = limit_positions(mesh, opt);
        }
        return checked(std::move(X), "limit_positions");
      },
      py::arg("mesh"), FAIRSHAPE_SCHEME_ARGS, "n×3 float64: the limit position of each vertex (a new array).");
  m.def(
      "limit_normals",
      [](const SurfaceMesh& mesh, const std::string& scheme, const std::string& boundary, const std::string& weights,
         const std::string& crease) {
        const SubdivisionOptions opt = subdivision_arg(scheme, boundary, weights, crease);
        MatrixX3 N;
        {
          py::gil_scoped_release release;
          N = limit_normals(mesh, opt);
        }
        return checked(std::move(N), "limit_normals");
      },
      py::arg("mesh"), FAIRSHAPE_SCHEME_ARGS, "n×3 float64: unit limit normals, oriented with the faces.");
  m.def(
      "limit_matrix",
      [](const SurfaceMesh& mesh, const std::string& scheme, const std::string& boundary, const std::string& weights,
         const std::string& crease) {
        return checked(csr(limit_matrix(mesh, subdivision_arg(scheme, boundary, weights, crease))), "limit_matrix");
      },
      py::arg("mesh"), FAIRSHAPE_SCHEME_ARGS,
      "csr_matrix n×n: row v maps control points to vertex v's limit position (limit_positions = L @ V).");
}

}  // namespace fairshape::python
