// fairshape.SheetSession: Welch & Witkin's modelling session (bspline/sheet_session.h) from
// Python, one step at a time. Built from keyword arguments through the sheet config's own reader
// (SheetRunSpec::from_config: the keys of a sheet config, unknown ones refused naming the valid
// ones), it keeps its sheets, constraints and the solver's factorization between calls; a config's
// scheduled steps run with advance(), exactly as `fairshape run` runs them (kinds/sheet/sheet_steps.h).
// Constraints are added as a config's `constraints:` entries (keywords; (u, v) in design units).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <optional>

#include "bindings.h"
#include "checks.h"
#include "convert.h"
#include "sheet_object.h"
#include "fairshape/experiment/kinds/sheet/sheet_steps.h"

namespace py = pybind11;

namespace fairshape::python {
namespace {

std::unique_ptr<SheetConfigSteps> make_session(const py::kwargs& kwargs) {
  YAML::Node config = to_yaml(kwargs, "SheetSession");
  if (!config["name"]) config["name"] = "session";
  return std::make_unique<SheetConfigSteps>(SheetRunSpec::from_config(config));
}

SheetChecks checks_arg(bool curve_probe) {
  SheetChecks c;
  c.curve_probe = curve_probe;
  return c;
}

// A step with the GIL released, its sheets' control points checked finite.
template <class F>
SheetStep step(F&& f) {
  SheetStep s;
  {
    py::gil_scoped_release release;
    s = f();
  }
  for (const SheetSolve& sh : s.sheets) finite_result(sh.coefficients, "SheetSession: the sheet's control points");
  return s;
}

std::optional<std::size_t> sheet_arg(const SheetConfigSteps& s, const std::optional<std::string>& name) {
  if (!name) return std::nullopt;
  return s.session().sheet_index(*name);
}

Sheet sheet_copy(const SheetConfigSteps& s, const std::string& name) {
  const std::size_t k = name.empty() ? 0 : s.session().sheet_index(name);
  return Sheet{s.spec().sheets[k].shape, s.session().sheet(k)};
}

SheetStep add(SheetConfigSteps& s, const py::kwargs& keys) {
  py::dict entry;
  bool probe = true;
  for (const auto& [k, v] : keys) {
    if (k.cast<std::string>() == "curve_probe") probe = v.cast<bool>();
    else entry[k] = v;
  }
  SessionConstraint c = s.read_constraint(to_yaml(entry, "constraint"));
  return step([&] { return s.session().add(std::move(c), checks_arg(probe)); });
}

std::vector<Vec3> points_arg(const Eigen::Ref<const Eigen::MatrixXd>& X, const std::string& what) {
  if (X.cols() != 3 || X.rows() < 2) throw InvalidInput(what + ": expected a p×3 array, p ≥ 2");
  finite_arg(X, what);
  std::vector<Vec3> out;
  for (Eigen::Index i = 0; i < X.rows(); ++i) out.push_back(X.row(i).transpose());
  return out;
}

void bind_results(py::module_& m) {
  py::class_<SheetConstraintCheck>(m, "SheetConstraintCheck", "One constraint measured on the sheet after a step.")
      .def_readonly("handle", &SheetConstraintCheck::handle)
      .def_readonly("error", &SheetConstraintCheck::error, "its largest error over the leaf cells (§4.4's measure)")
      .def_readonly("asked", &SheetConstraintCheck::asked, "point / offset: the target (NaN otherwise)")
      .def_readonly("achieved", &SheetConstraintCheck::achieved, "point / offset: what the sheet has there (NaN otherwise)");
  py::class_<SheetSolve>(m, "SheetSolve", "One sheet's solve in a step.")
      .def_readonly("sheet", &SheetSolve::sheet, "its index in the session's sheets")
      .def_readonly("joint", &SheetSolve::joint, "solved with a variational curve it is joined to")
      .def_property_readonly("termination", [](const SheetSolve& s) { return std::string(to_string(s.report.qp.summary.termination)); })
      .def_property_readonly("message", [](const SheetSolve& s) { return s.report.message; })
      .def_property_readonly("energy", [](const SheetSolve& s) { return s.report.energy; })
      .def_property_readonly("max_constraint_error", [](const SheetSolve& s) { return s.report.max_constraint_error; })
      .def_property_readonly("constraint_residual", [](const SheetSolve& s) { return s.report.qp.constraint_residual; })
      .def_property_readonly("constraint_rows", [](const SheetSolve& s) { return static_cast<long long>(s.report.constraint_rows); })
      .def_property_readonly("dropped_rows", [](const SheetSolve& s) { return s.report.qp.dropped_rows; })
      .def_property_readonly("spans_refined", [](const SheetSolve& s) { return s.report.spans_refined; })
      .def_property_readonly("refinement_rounds", [](const SheetSolve& s) { return s.report.rounds; })
      .def_property_readonly("curve_error", [](const SheetSolve& s) { return s.report.curve_error; })
      .def_readonly("factorization", &SheetSolve::factorization)
      .def_readonly("coefficients", &SheetSolve::coefficients, "the sheet's control points after the step (dofs×3)");
  py::class_<SheetStep>(m, "SheetStep", "What one session step did and achieved, measured on the sheets.")
      .def_property_readonly("termination", [](const SheetStep& s) { return std::string(to_string(s.summary.termination)); })
      .def_property_readonly("succeeded", [](const SheetStep& s) { return s.summary.succeeded(); })
      .def_property_readonly("message", [](const SheetStep& s) { return s.summary.message; })
      .def_readonly("added", &SheetStep::added, "handles the step made")
      .def_readonly("sheets", &SheetStep::sheets, "every sheet solved")
      .def_readonly("checks", &SheetStep::checks, "every active constraint of a solved sheet, measured on it")
      .def_readonly("max_constraint_error", &SheetStep::max_constraint_error)
      .def_readonly("energy", &SheetStep::energy)
      .def_readonly("solve_s", &SheetStep::solve_s, "factorizations and solves")
      .def_readonly("check_s", &SheetStep::check_s, "the checks on the result")
      .def("__repr__", [](const SheetStep& s) {
        std::ostringstream r;
        r << "SheetStep(" << to_string(s.summary.termination) << ", max_constraint_error " << s.max_constraint_error << ", energy "
          << s.energy << ")";
        return r.str();
      });
  py::class_<FreeCurveStep>(m, "FreeCurveStep", "A variational curve after a config step.")
      .def_readonly("name", &FreeCurveStep::name)
      .def_property_readonly("termination", [](const FreeCurveStep& c) { return std::string(to_string(c.termination)); })
      .def_readonly("message", &FreeCurveStep::message)
      .def_readonly("energy", &FreeCurveStep::energy)
      .def_readonly("max_error", &FreeCurveStep::max_error);
  py::class_<SheetConfigStep>(m, "SheetConfigStep", "One scheduled step of the session's config.")
      .def_readonly("step", &SheetConfigStep::step)
      .def_readonly("result", &SheetConfigStep::result)
      .def_readonly("free_curves", &SheetConfigStep::free_curves)
      .def_property_readonly("succeeded", [](const SheetConfigStep& s) {
        return s.result.summary.succeeded() &&
               std::all_of(s.free_curves.begin(), s.free_curves.end(), [](const FreeCurveStep& c) { return is_success(c.termination); });
      });
}

}  // namespace

void bind_sheet_session(py::module_& m) {
  bind_results(m);
  py::class_<SheetConfigSteps, std::unique_ptr<SheetConfigSteps>>(
      m, "SheetSession",
      "SheetSession(**config): Welch & Witkin's modelling session. The keywords are a sheet config's keys (sheets, curves, "
      "constraints, actions, energy, refinement, solver; name optional), read by the config's own reader. Steps: add(**entry) "
      "(a `constraints:` entry: type, uv, target | by, curve, ...), move(handle, target), move_curve(handle, points), "
      "remove(handle), install_rest_shape(sheet), melt(sheet), refine(tolerance), and advance() for the config's next "
      "scheduled step; each returns what it achieved, measured on the sheet. The solver's factorization is kept between steps.")
      .def(py::init(&make_session))
      .def_property_readonly("steps", &SheetConfigSteps::steps, "the config's scheduled steps")
      .def_property_readonly("next_step", &SheetConfigSteps::next_step)
      .def_property_readonly("sheet_names", [](const SheetConfigSteps& s) { return s.session().names(); })
      .def_property_readonly("handles",
                             [](const SheetConfigSteps& s) {
                               std::vector<SheetHandle> h;
                               for (const auto& [id, c] : s.session().constraints()) h.push_back(id);
                               return h;
                             },
                             "the constraints acting now (a config's are numbered by their place in its list)")
      .def("advance", [](SheetConfigSteps& s) {
        py::gil_scoped_release release;
        return s.advance();
      }, "Runs the config's next scheduled step (as `fairshape run` does).")
      .def("add", &add, "Adds a constraint given as a config's `constraints:` entry (keywords; curve_probe=False skips the "
                        "curve resolution probe) and solves. The result's .added holds its handle.")
      .def("move", [](SheetConfigSteps& s, SheetHandle h, const Vec3& target, bool probe) {
        finite_arg(target.transpose(), "SheetSession.move: target");
        return step([&] { return s.session().move(h, target, checks_arg(probe)); });
      }, py::arg("handle"), py::arg("target"), py::arg("curve_probe") = true,
           "A drag: a point's world target, an offset, a region's shift, a tangent or normal vector.")
      .def("move_curve", [](SheetConfigSteps& s, SheetHandle h, const Eigen::Ref<const Eigen::MatrixXd>& X, bool probe) {
        std::vector<Vec3> pts = points_arg(X, "SheetSession.move_curve: points");
        return step([&] { return s.session().move_curve(h, std::move(pts), checks_arg(probe)); });
      }, py::arg("handle"), py::arg("points"), py::arg("curve_probe") = true, "A curve constraint's space curve moved (p×3 points).")
      .def("remove", [](SheetConfigSteps& s, SheetHandle h, bool probe) {
        return step([&] { return s.session().remove(h, checks_arg(probe)); });
      }, py::arg("handle"), py::arg("curve_probe") = true)
      .def("install_rest_shape", [](SheetConfigSteps& s, const std::optional<std::string>& sheet) {
        const auto k = sheet_arg(s, sheet);
        return step([&] { return s.session().install_rest_shape(k); });
      }, py::arg("sheet") = py::none(), "§5: the current shape becomes the rest shape (eq. 6 about it); default every sheet.")
      .def("melt", [](SheetConfigSteps& s, const std::optional<std::string>& sheet) {
        const auto k = sheet_arg(s, sheet);
        return step([&] { return s.session().melt(k); });
      }, py::arg("sheet") = py::none(), "§5: the rest shape melted (eq. 4 again).")
      .def("refine", [](SheetConfigSteps& s, double tolerance) {
        finite_arg(tolerance, "SheetSession.refine: tolerance");
        return step([&] { return s.session().refine(tolerance); });
      }, py::arg("tolerance"), "§4.4: solve again, refining where the constraint error is above tolerance.")
      .def("sheet", &sheet_copy, py::arg("name") = "", "The sheet as it is now (a fairshape.Sheet copy; default the first).")
      .def("coefficients", [](const SheetConfigSteps& s, const std::string& name) {
        return checked(Eigen::MatrixXd(sheet_copy(s, name).sheet.coefficients()), "SheetSession.coefficients");
      }, py::arg("sheet") = "", "dofs×3 control points (a copy).");
}

}  // namespace fairshape::python
