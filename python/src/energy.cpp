// Energies as matrices: Boier-Martin's stretch+bend H (the `fairshape energy` command's
// matrix) and every registered energy by name; the registries' names, docs and options.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "checks.h"
#include "convert.h"
#include "fairshape/energy/local_quadratic.h"
#include "fairshape/experiment/components.h"

namespace py = pybind11;

namespace fairshape::python {
namespace {

template <class R>
py::dict describe(const R& registry) {
  py::dict out;
  for (const auto& name : registry.names()) {
    py::dict entry;
    py::list backends;
    const typename R::Entry* first = nullptr;
    for (const auto& e : registry.entries())
      if (e.name == name) {
        backends.append(std::string(to_string(e.backend)));
        if (!first) {
          first = &e;
          entry["doc"] = e.doc;
        }
      }
    entry["backends"] = backends;
    py::dict options;
    for (const auto& o : registry.options(*first)) options[py::str(o.key)] = py::make_tuple(o.default_value, o.doc);
    entry["options"] = options;
    out[py::str(name)] = entry;
  }
  return out;
}

}  // namespace

void bind_energy(py::module_& m) {
  m.def(
      "stretch_bend_hessian",
      [](const SurfaceMesh& mesh, double alpha, double beta, const std::string& implementation) {
        if (alpha == 0 && beta == 0) throw InvalidInput("stretch_bend_hessian: alpha and beta are both zero");
        if (!(alpha >= 0) || !(beta >= 0) || !std::isfinite(alpha) || !std::isfinite(beta))
          throw InvalidInput("stretch_bend_hessian: alpha and beta must be finite and >= 0");
        const Backend b = backend_arg(implementation);
        SparseMatrix H;
        {
          py::gil_scoped_release release;
          H = stretch_bend_hessian(mesh, {alpha, beta}, b);
        }
        return checked(RowSparseMatrix(H), "stretch_bend_hessian");
      },
      py::arg("mesh"), py::arg("alpha") = 0.1, py::arg("beta") = 1.0, py::arg("implementation") = "optimized",
      "Boier-Martin et al.'s stretch+bend matrix H (§3.4), E(P) = ½ Pᵀ H P per coordinate: a "
      "scipy.sparse.csr_matrix n×n, symmetric positive semi-definite, the matrix `fairshape energy MESH "
      "--alpha A --beta B` writes. alpha weighs first derivatives (stretch), beta second ones (bend).");
  m.def(
      "energy_hessian",
      [](const SurfaceMesh& mesh, const std::string& type, double weight, const std::string& implementation,
         const py::kwargs& options) {
        finite_arg(weight, "energy_hessian: weight");
        const Backend b = backend_arg(implementation);
        Config cfg = to_config(options, "energy." + type);
        const auto energy = components().energies.create(type, b, cfg);
        cfg.check_no_unknown_keys();
        energy->check_applicable(mesh);
        SparseMatrix H;
        {
          py::gil_scoped_release release;
          H = energy->hessian(mesh, weight);
        }
        return checked(RowSparseMatrix(H), "energy_hessian");
      },
      py::arg("mesh"), py::arg("type"), py::arg("weight") = 1.0, py::arg("implementation") = "optimized",
      "weight × H of a registered energy (fairshape.components()['energies'], `fairshape list`) on `mesh`, "
      "its options as keyword arguments (an unknown one raises InvalidConfig naming the valid ones): a "
      "scipy.sparse.csr_matrix n×n. Energies of positions (surface_thin_plate) and of the deformation "
      "(detail_preserving, membrane, umbrella_thin_plate) alike.");
  m.def(
      "components",
      [] {
        const Components& c = components();
        py::dict out;
        out["energies"] = describe(c.energies);
        out["constraints"] = describe(c.constraints);
        out["solvers"] = describe(c.solvers);
        return out;
      },
      "Every registered energy, constraint and solver: {kind: {name: {doc, backends, options: {key: (default, doc)}}}}"
      " (what `fairshape list` prints).");
}

}  // namespace fairshape::python
