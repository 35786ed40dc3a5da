// Variational sheets of Welch & Witkin, "Variational surface modeling" (src/bspline): a
// hierarchical B-spline sheet placed as a plane, the objective of §4.1 (stretching α and
// bending β), point constraints (u, v, target) and curve constraints ((u, v) polyline onto a
// space polyline, the mortar rows of a sheet config's `{type: curve}`), solved by a named QP
// solver with the automatic refinement of §4.4, as one step of a SheetSession
// (src/bspline/sheet_session.h), the step a sheet run takes. (u, v) are in design units (the sheet's size),
// as in a config.
// Copies: coefficients and evaluations come back as new arrays; a solve returns a new Sheet.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <sstream>

#include <Eigen/Geometry>

#include "bindings.h"
#include "checks.h"
#include "convert.h"
#include "sheet_object.h"
#include "fairshape/bspline/sheet_geometry.h"
#include "fairshape/bspline/sheet_session.h"
#include "fairshape/bspline/variational_sheet.h"
#include "fairshape/qp/qp_solver.h"

namespace py = pybind11;

namespace fairshape::python {
namespace {

Sheet make_sheet(const std::array<int, 2>& spans, int degree, const std::array<double, 2>& size, const Vec3& origin,
                 const Vec3& u_axis, const Vec3& v_axis) {
  finite_arg(size[0], "Sheet: size[0]");
  finite_arg(size[1], "Sheet: size[1]");
  finite_arg(origin.transpose(), "Sheet: origin");
  finite_arg(u_axis.transpose(), "Sheet: u_axis");
  finite_arg(v_axis.transpose(), "Sheet: v_axis");
  if (spans[0] < 1 || spans[1] < 1 ||
      static_cast<long long>(spans[0]) * spans[1] > bspline::HierarchicalSurface::kMaxBaseSpans)
    throw InvalidInput("Sheet: spans " + std::to_string(spans[0]) + " x " + std::to_string(spans[1]) +
                       ": each at least 1, at most " + std::to_string(bspline::HierarchicalSurface::kMaxBaseSpans) + " in all");
  if (!(size[0] > 0) || !(size[1] > 0)) throw InvalidInput("Sheet: size must be two positive numbers");
  if (u_axis.norm() == 0 || v_axis.norm() == 0 || u_axis.cross(v_axis).norm() < 1e-9 * u_axis.norm() * v_axis.norm())
    throw InvalidInput("Sheet: u_axis and v_axis must be nonzero and not parallel");
  bspline::SheetShape shape;
  shape.spans_u = spans[0];
  shape.spans_v = spans[1];
  shape.degree = degree;
  shape.span_size = {size[0] / spans[0], size[1] / spans[1]};
  bspline::SheetPlacement p;
  p.origin = origin;
  p.u_axis = u_axis;
  p.v_axis = v_axis;
  p.size_u = size[0];
  p.size_v = size[1];
  const bspline::HierarchicalSurface surface(shape);
  return Sheet{shape, bspline::VariationalSheet(shape, bspline::initial_coefficients(p, surface))};
}

Eigen::MatrixXd evaluate(const Sheet& s, const Eigen::Ref<const Eigen::MatrixXd>& uv) {
  if (uv.cols() != 2) throw InvalidInput("Sheet.evaluate: expected a k×2 array of (u, v), got " + std::to_string(uv.cols()) + " columns");
  finite_arg(uv, "Sheet.evaluate: uv");
  Eigen::MatrixXd X(uv.rows(), 3);
  for (Eigen::Index i = 0; i < uv.rows(); ++i) {
    const Eigen::Vector2d p = s.spans(uv(i, 0), uv(i, 1), "Sheet.evaluate, point " + std::to_string(i));
    X.row(i) = s.sheet.surface().position(s.sheet.coefficients(), p.x(), p.y()).transpose();
  }
  return checked(std::move(X), "Sheet.evaluate");
}

// The tessellation grid of final.obj: (spans_u·n + 1) × (spans_v·n + 1) points, u first.
py::array_t<double> grid(const Sheet& s, int per_span) {
  if (per_span < 1 || per_span > 64) throw InvalidInput("Sheet.grid: samples_per_span must be in [1, 64]");
  finite_result(s.sheet.coefficients(), "Sheet.grid: the control points");
  const int cols = s.shape.spans_u * per_span + 1, rows = s.shape.spans_v * per_span + 1;
  py::array_t<double> out({cols, rows, 3});
  auto o = out.mutable_unchecked<3>();
  {
    py::gil_scoped_release release;
    for (int i = 0; i < cols; ++i)
      for (int j = 0; j < rows; ++j) {
        const Vec3 x = s.sheet.surface().position(s.sheet.coefficients(), static_cast<double>(i) / per_span,
                                                  static_cast<double>(j) / per_span);
        for (int c = 0; c < 3; ++c) o(i, j, c) = x[c];
      }
  }
  return out;
}

// A surface curve promoted to a space curve (Figure 1): a sheet config's `from_surface` curve.
Eigen::MatrixXd trace(const Sheet& s, const Eigen::Ref<const Eigen::MatrixXd>& uv, int samples) {
  if (uv.cols() != 2 || uv.rows() < 2) throw InvalidInput("Sheet.trace: expected an m×2 array of (u, v), m ≥ 2");
  if (samples < 2 || samples > 100000) throw InvalidInput("Sheet.trace: samples must be in [2, 100000]");
  finite_arg(uv, "Sheet.trace: uv");
  std::vector<Eigen::Vector2d> at;
  for (Eigen::Index i = 0; i < uv.rows(); ++i) at.push_back(s.spans(uv(i, 0), uv(i, 1), "Sheet.trace, point " + std::to_string(i)));
  const std::vector<Vec3> pts = bspline::surface_curve(s.sheet.surface(), s.sheet.coefficients(), at, samples);
  Eigen::MatrixXd X(static_cast<Eigen::Index>(pts.size()), 3);
  for (std::size_t i = 0; i < pts.size(); ++i) X.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
  return checked(std::move(X), "Sheet.trace");
}

Eigen::Matrix2d weights_arg(py::handle w, const Eigen::Matrix2d& isotropic, const char* name) {
  if (py::isinstance<py::float_>(w) || py::isinstance<py::int_>(w)) return finite_arg(w.cast<double>(), name) * isotropic;
  const auto m = py::cast<Eigen::MatrixXd>(py::module_::import("numpy").attr("asarray")(w, "float64"));
  if (m.rows() != 2 || m.cols() != 2) throw InvalidConfig(std::string(name) + ": expected a number or a 2×2 matrix");
  finite_arg(m, name);
  return m;
}

py::dict design_sheet(const Sheet& rest, const Eigen::Ref<const Eigen::MatrixXd>& points_uv,
                      const Eigen::Ref<const Eigen::MatrixXd>& targets, bool relative, const py::list& curves,
                      py::handle alpha, py::handle beta, const std::string& metric, const std::string& formulation,
                      const std::string& solver_type, const py::dict& solver_options, double tolerance, int max_level,
                      int max_rounds, const std::string& implementation) {
  const Backend backend = backend_arg(implementation);
  bspline::SheetEnergy energy;
  energy.weights.alpha = weights_arg(alpha, Eigen::Matrix2d::Identity(), "alpha");
  energy.weights.beta = weights_arg(beta, Eigen::Matrix2d::Ones(), "beta");
  bspline::validate(energy.weights);
  if (metric != "thin_plate" && metric != "displacement")
    throw InvalidConfig("metric '" + metric + "': expected 'thin_plate' or 'displacement'");
  energy.metric = metric == "thin_plate" ? bspline::ShapeMetric::ThinPlate : bspline::ShapeMetric::Displacement;
  if (formulation != "mortar" && formulation != "paper")
    throw InvalidConfig("formulation '" + formulation + "': expected 'mortar' or 'paper'");
  if (points_uv.cols() != 2 || targets.cols() != 3 || targets.rows() != points_uv.rows())
    throw InvalidInput("design_sheet: points_uv must be k×2 and targets k×3 (k = " + std::to_string(points_uv.rows()) +
                       "), got " + std::to_string(targets.rows()) + "×" + std::to_string(targets.cols()));
  finite_arg(points_uv, "design_sheet: points_uv");
  finite_arg(targets, "design_sheet: targets");
  finite_arg(tolerance, "design_sheet: refinement_tolerance");
  std::vector<bspline::SheetConstraint> active;
  for (Eigen::Index i = 0; i < points_uv.rows(); ++i) {
    bspline::SheetConstraint c;
    c.kind = bspline::SheetConstraint::Kind::Point;
    c.label = "points[" + std::to_string(i) + "]";
    const Eigen::Vector2d s = rest.spans(points_uv(i, 0), points_uv(i, 1), c.label);
    c.u = s.x();
    c.v = s.y();
    c.target = targets.row(i).transpose();
    if (relative) c.target += rest.sheet.surface().position(rest.sheet.coefficients(), c.u, c.v);
    active.push_back(c);
  }
  for (std::size_t k = 0; k < curves.size(); ++k) {
    bspline::SheetConstraint c;
    c.kind = bspline::SheetConstraint::Kind::Curve;
    c.label = "curves[" + std::to_string(k) + "]";
    c.formulation = formulation == "mortar" ? bspline::CurveFormulation::Mortar : bspline::CurveFormulation::Paper;
    const auto pair = curves[k].cast<py::sequence>();
    if (pair.size() != 2) throw InvalidInput(c.label + ": expected a pair (uv: m×2, space: p×3)");
    const auto uv = pair[0].cast<Eigen::MatrixXd>();
    const auto space = pair[1].cast<Eigen::MatrixXd>();
    if (uv.cols() != 2 || uv.rows() < 2) throw InvalidInput(c.label + ": the (u, v) polyline must be m×2 with m ≥ 2");
    if (space.cols() != 3 || space.rows() < 2) throw InvalidInput(c.label + ": the space polyline must be p×3 with p ≥ 2");
    finite_arg(uv, c.label + ": the (u, v) polyline");
    finite_arg(space, c.label + ": the space polyline");
    for (Eigen::Index i = 0; i < uv.rows(); ++i)
      c.curve.uv.push_back(rest.spans(uv(i, 0), uv(i, 1), c.label + ", (u, v) point " + std::to_string(i)));
    for (Eigen::Index i = 0; i < space.rows(); ++i) c.curve.space.push_back(space.row(i).transpose());
    active.push_back(std::move(c));
  }
  if (active.empty()) throw InvalidInput("design_sheet: no constraint (give points_uv/targets or curves)");
  const auto& reg = qp::qp_solver_registry();
  if (solver_options.contains("type")) throw InvalidConfig("solver options: give the solver by solver=NAME, not type=");
  Config sc = to_config(solver_options, "solver." + solver_type);
  std::unique_ptr<qp::QpSolver> solver = reg.create(solver_type, backend, sc);
  sc.check_no_unknown_keys();
  bspline::RefinementOptions refinement;
  if (!(tolerance >= 0)) throw InvalidConfig("refinement_tolerance: must be ≥ 0");
  if (max_level < 1 || max_level > bspline::HierarchicalSurface::kMaxLevel)
    throw InvalidConfig("max_level: must lie in [1, " + std::to_string(bspline::HierarchicalSurface::kMaxLevel) + "]");
  if (max_rounds < 1 || max_rounds > 100) throw InvalidConfig("max_rounds: must lie in [1, 100]");
  refinement.tolerance = tolerance;
  refinement.max_level = max_level;
  refinement.max_rounds = max_rounds;
  // One step of a session on a copy of the sheet (bspline/sheet_session.h): the same solve and
  // checks as a sheet run's step.
  SheetSession session({"sheet"}, {rest.sheet}, SheetSessionOptions{energy, refinement, backend}, std::move(solver));
  SheetEdits edits;
  for (bspline::SheetConstraint& c : active) edits.put.push_back({-1, {0, std::move(c)}});
  SheetStep step;
  {
    py::gil_scoped_release release;
    step = session.apply(edits);
  }
  const bspline::DesignReport& r = step.sheets.at(0).report;
  Sheet out_sheet{rest.shape, session.sheet(0)};
  finite_result(out_sheet.sheet.coefficients(), "design_sheet: the sheet's control points (" +
                                                   std::string(to_string(r.qp.summary.termination)) + ")");
  py::dict out;
  out["termination"] = std::string(to_string(r.qp.summary.termination));
  out["succeeded"] = is_success(r.qp.summary.termination);
  out["iterations"] = r.qp.summary.iterations;
  out["residual"] = r.qp.summary.residual;
  out["message"] = r.message.empty() ? r.qp.summary.message : r.message;
  out["max_constraint_error"] = r.max_constraint_error;
  out["constraint_residual"] = r.qp.constraint_residual;
  out["constraint_rows"] = static_cast<long long>(r.constraint_rows);
  out["dropped_rows"] = r.qp.dropped_rows;
  out["energy"] = r.energy;
  out["spans_refined"] = r.spans_refined;
  out["refinement_rounds"] = r.rounds;
  out["analyze_s"] = r.analyze_s;
  out["solve_s"] = r.solve_s;
  out["curve_error"] = r.curve_error;
  out["condition_estimate"] = std::isnan(r.qp.condition_estimate) ? py::object(py::none()) : py::cast(r.qp.condition_estimate);
  out["sheet"] = py::cast(std::move(out_sheet));
  return out;
}

}  // namespace

void bind_sheets(py::module_& m) {
  py::class_<Sheet>(m, "Sheet", "A variational sheet (Welch & Witkin): a hierarchical B-spline surface placed as a plane.")
      .def(py::init(&make_sheet), py::arg("spans") = std::array<int, 2>{4, 4}, py::arg("degree") = 3,
           py::arg("size") = std::array<double, 2>{1, 1}, py::arg("origin") = Vec3(Vec3::Zero()),
           py::arg("u_axis") = Vec3(Vec3::UnitX()), py::arg("v_axis") = Vec3(Vec3::UnitY()),
           "Sheet(spans=(su, sv), degree=3, size=(w, h), origin, u_axis, v_axis): the plane origin + u·u_axis + "
           "v·v_axis over (u, v) ∈ [0, w] × [0, h] (design units), su × sv base spans of degree `degree`; a "
           "sheet config's `sheets:` entry.")
      .def_property_readonly("spans", [](const Sheet& s) { return std::array<int, 2>{s.shape.spans_u, s.shape.spans_v}; })
      .def_property_readonly("degree", [](const Sheet& s) { return s.shape.degree; })
      .def_property_readonly("size", [](const Sheet& s) { return s.size(); }, "(w, h): the (u, v) domain's extent")
      .def_property_readonly("dofs", [](const Sheet& s) { return s.sheet.surface().dof_count(); }, "control points, every layer")
      .def_property_readonly("levels", [](const Sheet& s) { return s.sheet.surface().level_count(); }, "hierarchy layers")
      .def_property_readonly("coefficients",
                             [](const Sheet& s) { return checked(Eigen::MatrixXd(s.sheet.coefficients()), "Sheet.coefficients"); },
                             "dofs×3 control points (a copy)")
      .def("evaluate", &evaluate, py::arg("uv"), "Points of the surface at k (u, v) (a k×2 array, design units): k×3.")
      .def("trace", &trace, py::arg("uv"), py::arg("samples") = 65,
           "The space curve the surface traces along an m×2 (u, v) polyline (design units), at `samples` equally "
           "spaced t: samples×3 (a sheet config's `from_surface` curve; move it and hold the sheet to it with "
           "design_sheet(curves=[(uv, points)])).")
      .def("grid", &grid, py::arg("samples_per_span") = 6,
           "The surface at n samples per base span: a (su·n + 1)×(sv·n + 1)×3 array, G[i, j] = x(i·w/(su·n), "
           "j·h/(sv·n)); G.reshape(-1, 3) is the vertex list of a sheet run's final.obj.")
      .def("__repr__", [](const Sheet& s) {
        return "Sheet(" + std::to_string(s.shape.spans_u) + "×" + std::to_string(s.shape.spans_v) + " spans, degree " +
               std::to_string(s.shape.degree) + ", " + std::to_string(s.sheet.surface().dof_count()) + " dofs)";
      });
  m.def("_design_sheet", &design_sheet, py::arg("sheet"), py::arg("points_uv"), py::arg("targets"), py::arg("relative"),
        py::arg("curves"), py::arg("alpha"), py::arg("beta"), py::arg("metric"), py::arg("formulation"), py::arg("solver"),
        py::arg("solver_options"), py::arg("refinement_tolerance"), py::arg("max_level"), py::arg("max_rounds"),
        py::arg("implementation"), "The sheet solve's C++ half; call fairshape.design_sheet().");
  m.def("qp_solvers", [] { return qp::qp_solver_registry().names(); }, "Names of the registered constrained (QP) solvers.");
}

}  // namespace fairshape::python
