// The constrained edit of Boier-Martin et al. §4.3 on one level of a hierarchy: energies and
// constraints given as dicts of the config schema ({"type": name, options...}; the Python
// helpers fairshape.fixed / position / constraint build them), so every registered energy and
// constraint is available and an unknown option is refused exactly as in a config.
// Copies: the deformation comes back as a new n×3 array (moved out of the solver's result, not
// copied again); the edited hierarchy is a new MultiresSurface.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "checks.h"
#include "convert.h"
#include "fairshape/design/edit_assembly.h"
#include "fairshape/design/edit_solve.h"
#include "fairshape/design/orientation_check.h"
#include "fairshape/experiment/components.h"
#include "fairshape/qp/qp_solver.h"

namespace py = pybind11;

namespace fairshape::python {
namespace {

struct OwnedTerms {
  std::vector<std::unique_ptr<Energy>> energies;
  std::vector<std::unique_ptr<Constraint>> constraints;
  EditTerms terms;
};

std::string type_of(Config& block, const char* what) {
  return block.require<std::string>("type", std::string(what) + " name (fairshape.components())");
}

OwnedTerms read_terms(const py::list& energies, const py::list& constraints, Backend backend) {
  const Components& c = components();
  OwnedTerms t;
  if (energies.empty()) throw InvalidConfig("energies: at least one energy term is required, e.g. "
                                            "[{'type': 'detail_preserving', 'alpha': 0.1, 'beta': 1.0}]");
  for (std::size_t i = 0; i < energies.size(); ++i) {
    const std::string where = "energies[" + std::to_string(i) + "]";
    if (!py::isinstance<py::dict>(energies[i])) throw InvalidConfig(where + ": expected a dict {'type': name, ...}");
    Config e = to_config(energies[i].cast<py::dict>(), where);
    const std::string type = type_of(e, "energy");
    const double weight = e.get_number("weight", 1.0, 0.0, 1e12, "weight of this term");
    t.energies.push_back(c.energies.create(type, backend, e));
    e.check_no_unknown_keys();
    t.terms.energies.push_back({t.energies.back().get(), weight});
  }
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const std::string where = "constraints[" + std::to_string(i) + "]";
    if (!py::isinstance<py::dict>(constraints[i])) throw InvalidConfig(where + ": expected a dict {'type': name, ...}");
    Config k = to_config(constraints[i].cast<py::dict>(), where);
    const std::string type = type_of(k, "constraint");
    t.constraints.push_back(c.constraints.create(type, backend, k));
    k.check_no_unknown_keys();
    t.terms.constraints.push_back(t.constraints.back().get());
  }
  return t;
}

// The free vertices' solver of the paper mode: the config's solver block, type included.
std::unique_ptr<Solver> make_solver(const std::string& type, const py::dict& options, Backend backend) {
  py::dict block(options);
  if (block.contains("type")) throw InvalidConfig("solver options: give the solver by solver=NAME, not type=");
  block["type"] = type;
  Config cfg = to_config(block, "solver");
  const Components& c = components();
  (void)cfg.get_choice("type", "cholesky", c.solvers.names(), "solver name");
  auto solver = c.solvers.create(type, backend, cfg);
  cfg.check_no_unknown_keys();
  return solver;
}

// A QP mode's options (problem.<mode> in a config), checked against its solver's schema now,
// before any work.
Config qp_options(const std::string& mode, const py::dict& options, Backend backend) {
  const auto& registry = qp::qp_solver_registry();
  Config cfg = to_config(options, "problem." + mode);
  (void)registry.create(mode, registry.has(mode, backend) ? backend : Backend::Optimized, cfg);
  cfg.check_no_unknown_keys();
  return to_config(options, "problem." + mode);
}

py::dict edit(const MultiresSurface& rest, const py::list& energies, const py::list& constraints, int level,
              const std::string& mode_name, const std::optional<std::string>& solver_name,
              const std::string& formulation, const std::string& implementation, const py::dict& options) {
  const Backend backend = backend_arg(implementation);
  const ConstraintMode mode = constraint_mode_names().value(mode_name, "mode");
  if (formulation != "displacement" && formulation != "position")
    throw InvalidConfig("formulation '" + formulation + "': expected 'displacement' or 'position'");
  const int l = level < 0 ? rest.levels() + 1 + level : level;
  if (l < 0 || l > rest.levels())
    throw InvalidIndex("edit: level " + std::to_string(level) + " is not in the hierarchy (levels 0.." +
                       std::to_string(rest.levels()) + ", or -1 for the finest)");
  OwnedTerms t = read_terms(energies, constraints, backend);
  t.terms.positions = formulation == "position";
  std::unique_ptr<Solver> solver;
  Config qp;
  if (mode == ConstraintMode::Paper) {
    solver = make_solver(solver_name.value_or("cholesky"), options, backend);
    t.terms.levels = solver->uses_levels();
  } else {
    if (solver_name)
      throw InvalidConfig("solver='" + *solver_name + "': mode '" + mode_name +
                          "' solves the whole constrained system itself; the solver is used by mode 'paper' only");
    qp = qp_options(mode_name, options, backend);
    solver = make_solver("cholesky", py::dict(), backend);  // not used by a QP mode
  }
  EditSolution sol;
  MultiresSurface edited = rest;
  OrientationCheck checked;
  int n_dofs = 0;
  {
    py::gil_scoped_release release;
    // Checked as a config run's result is, normals left to rows `auto` solved again with frame
    // rows when they come out reversed (design/orientation_check.h).
    const std::string note = solve_orienting_normals([&](bool frame_rows) {
      t.terms.frame_rows_for_auto_normals = frame_rows;
      DesignConstraints placed;
      const EditProblem p = assemble_edit_problem(t.terms, rest, l, placed);
      n_dofs = static_cast<int>(p.H.rows());
      sol = solve_edit(p, mode, *solver, backend, {}, nullptr, qp);
      edited = sol.delta.allFinite() ? with_deformation(rest, l, sol.delta) : rest;
      checked = sol.delta.allFinite() ? check_orientation(rest, edited, placed) : OrientationCheck{};
      return checked;
    });
    sol.summary.message = noted(note, sol.summary.message);
    if (checked.folded() && sol.summary.succeeded()) {
      sol.summary.termination = Termination::Folded;
      sol.summary.message = noted(sol.summary.message, checked.describe());
    }
  }
  const std::string outcome = std::string(to_string(sol.summary.termination)) + ": " + sol.summary.message;
  finite_result(sol.delta, "edit: the deformation (" + outcome + ")");
  finite_result(edited, "edit: the edited hierarchy (" + outcome + ")");
  py::dict out;
  out["level"] = l;
  out["n_dofs"] = n_dofs;
  out["termination"] = std::string(to_string(sol.summary.termination));
  out["succeeded"] = sol.summary.succeeded();
  out["iterations"] = sol.summary.iterations;
  out["residual"] = sol.summary.residual;
  out["message"] = sol.summary.message;
  out["analyze_s"] = sol.analyze_s;
  out["solve_s"] = sol.solve_s;
  out["constraint_residual"] = sol.constraint_residual;
  out["constrained_vertices"] = sol.constrained_vertices;
  out["flipped_faces"] = static_cast<int>(checked.folds.flipped.size());
  out["normal_error_deg"] = checked.normal_error_deg;
  out["delta"] = py::cast(std::move(sol.delta));  // moved into the array: no copy
  out["hierarchy"] = py::cast(std::move(edited));
  return out;
}

}  // namespace

void bind_edit(py::module_& m) {
  m.def("_edit", &edit, py::arg("hierarchy"), py::arg("energies"), py::arg("constraints"), py::arg("level"),
        py::arg("mode"), py::arg("solver"), py::arg("formulation"), py::arg("implementation"), py::arg("options"),
        "The edit's C++ half; call fairshape.edit().");
  m.def("constraint_modes", [] { return constraint_mode_names().names(); }, "Names of the edit's constraint modes.");
}

}  // namespace fairshape::python
