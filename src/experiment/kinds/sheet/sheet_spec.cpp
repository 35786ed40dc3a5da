// Reading a sheet config into a SheetRunSpec (sheet_run.h), one function per block of the
// config: the sheets, the refinement, the space curves, the constraints (constraint_kinds.h),
// the energy, the rest-shape actions, the solver and the output.
#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "fairshape/core/config.h"
#include "fairshape/experiment/kinds/sheet/constraint_kinds.h"
#include "fairshape/experiment/kinds/sheet/curve_forms.h"
#include "fairshape/experiment/kinds/sheet/free_curves.h"
#include "fairshape/experiment/kinds/sheet/sheet_files.h"
#include "fairshape/experiment/kinds/sheet/sheet_run.h"
#include "fairshape/experiment/metric_format.h"

namespace fairshape {
using bspline::SheetConstraint;

namespace {

// A number (times `isotropic`) or a symmetric 2 × 2 matrix [[w11, w12], [w21, w22]].
Eigen::Matrix2d read_weights(Config& c, const std::string& key, double fallback, const Eigen::Matrix2d& isotropic,
                             const std::string& doc) {
  if (!c.has(key)) {
    c.get<double>(key, fallback, doc);
    return fallback * isotropic;
  }
  if (c.node()[key].IsScalar()) return c.get_number(key, fallback, 0, 1e12, doc) * isotropic;
  const auto m = c.get<std::vector<std::vector<double>>>(key, {}, doc);
  if (m.size() != 2 || m[0].size() != 2 || m[1].size() != 2)
    throw InvalidConfig(c.key_path(key) + ": expected a number or [[w11, w12], [w21, w22]]");
  Eigen::Matrix2d w;
  w << m[0][0], m[0][1], m[1][0], m[1][1];
  return w;
}

SheetSpec read_sheet(Config& c, const std::vector<std::string>& search_dirs) {
  if (c.has("file")) return read_sheet_from_file(c, search_dirs);
  SheetSpec s;
  s.name = c.get<std::string>("name", "sheet", "name constraints and curves refer to");
  (void)c.get<std::string>("file", "", "a saved sheet (sheets/<run>_<sheet>.sheet) to start from, instead of the shape keys");
  const std::vector<int> spans = c.get<std::vector<int>>("spans", {4, 4}, "base spans [u, v]");
  if (spans.size() != 2) throw InvalidConfig(c.key_path("spans") + ": expected [spans_u, spans_v]");
  s.shape.spans_u = spans[0];
  s.shape.spans_v = spans[1];
  if (spans[0] < 1 || spans[1] < 1 ||
      static_cast<long long>(spans[0]) * spans[1] > bspline::HierarchicalSurface::kMaxBaseSpans)
    throw InvalidConfig(c.key_path("spans") + ": " + std::to_string(spans[0]) + " x " + std::to_string(spans[1]) +
                        " base spans: each at least 1, at most " + std::to_string(bspline::HierarchicalSurface::kMaxBaseSpans) +
                        " in all");
  s.shape.degree = c.get_int("degree", 3, bspline::kMinDegree, bspline::kMaxDegree, "B-spline degree r");
  using bspline::SheetGeometry;
  bspline::SheetPlacement& p = s.placement;
  static const NameTable<SheetGeometry> geometries{{SheetGeometry::Plane, "plane"}, {SheetGeometry::Cylinder, "cylinder"}};
  p.geometry = c.get_enum("geometry", SheetGeometry::Plane, geometries, "initial shape (a cylinder is periodic in u)");
  s.shape.periodic_u = p.geometry == SheetGeometry::Cylinder;
  p.origin = read_vec3(c, "origin", p.origin, "plane: corner at (0, 0); cylinder: center of the base circle");
  p.u_axis = read_vec3(c, "u_axis", p.u_axis, "world direction of u (plane) / first radial axis (cylinder)");
  p.v_axis = read_vec3(c, "v_axis", p.v_axis, "world direction of v (plane and cylinder axis)");
  const std::vector<double> size = c.get<std::vector<double>>("size", {1, 1}, "plane: extent [u, v]; cylinder: [radius, height]");
  if (size.size() != 2 || !(size[0] > 0) || !(size[1] > 0)) throw InvalidConfig(c.key_path("size") + ": expected two positive numbers");
  p.size_u = size[0];
  p.size_v = size[1];
  // Design units: (u, v), energies and tangents are measured in the world lengths of the
  // initial sheet (a cylinder's u along its circumference), whatever the resolution.
  const double extent_u = p.geometry == SheetGeometry::Cylinder ? 2 * M_PI * p.size_u : p.size_u;
  s.shape.span_size = {extent_u / spans[0], p.size_v / spans[1]};
  if (p.u_axis.norm() == 0 || p.v_axis.norm() == 0 || p.u_axis.cross(p.v_axis).norm() < 1e-9 * p.u_axis.norm() * p.v_axis.norm())
    throw InvalidConfig(c.key_path("u_axis") + ", " + c.key_path("v_axis") + ": must be nonzero and not parallel");
  for (const auto& r : c.get<std::vector<std::vector<int>>>("refine", {}, "spans refined up front: [[level, i, j], ...]")) {
    if (r.size() != 3) throw InvalidConfig(c.key_path("refine") + ": expected [level, i, j] entries");
    s.refine.push_back({r[0], r[1], r[2]});
  }
  c.check_no_unknown_keys();
  bspline::HierarchicalSurface probe = [&] {
    try {
      return bspline::HierarchicalSurface(s.shape);
    } catch (const InvalidInput& e) {
      throw InvalidConfig(c.key_path("spans") + ": " + e.what());
    }
  }();
  try {  // the run's own refinement, on a trial sheet (as sheet_files.cpp checks a file's)
    bspline::VariationalSheet trial(s.shape, Eigen::MatrixXd::Zero(probe.dof_count(), 3));
    (void)trial.refine(s.refine);
  } catch (const InvalidInput& e) {
    throw InvalidConfig(c.key_path("refine") + ": " + e.what());
  }
  return s;
}

SpaceCurveSpec read_curve(Config& c, double chord_tolerance) {
  SpaceCurveSpec s;
  s.name = c.require<std::string>("name", "name curve constraints refer to");
  const bool documenting = c.documenting();  // both ways of giving a curve are read
  if (c.has("from_surface") || documenting) {
    for (const char* form : {"points", "arc", "bspline", "closed"})
      if (c.has(form))
        throw InvalidConfig(c.key_path(form) + (std::string(form) == "closed"
                                                    ? ": a traced curve is closed when its uv curve is (from_surface.uv: {..., closed: true})"
                                                    : ": give either from_surface or a curve form, not both"));
    s.samples = c.get_int("samples", s.samples, 2, kMaxCurveSamples, "points of the space curve (equally spaced in t)");
    Config fs_ = c.child("from_surface", "trace the curve on a sheet's surface: {sheet, uv, surface}");
    s.from_sheet = fs_.require<std::string>("sheet", "sheet name");
    s.trace_current = fs_.get_choice("surface", "initial", {"initial", "current"},
                                     "initial: the sheet before any step; current: the sheet as the steps before the curve's "
                                     "first use left it (the paper's operation: adding the curve moves nothing), its exact "
                                     "surface the target") == "current";
    const SampledCurve<2> uv = read_uv_curve(fs_, "uv", "(u, v) curve on that sheet", chord_tolerance);
    if (uv.points.empty() && !documenting) throw InvalidConfig(fs_.key_path("uv") + ": required key is missing");
    s.uv = uv.points;
    s.closed = uv.closed;
    fs_.check_no_unknown_keys();
  }
  if (!c.has("from_surface") || documenting) {  // points, arc or bspline (curve_forms.h), sampled already
    if (!has_curve_form_key(c) && !documenting) throw InvalidConfig(c.path() + ": give from_surface or a curve: points, arc or bspline");
    const SampledCurve<3> curve = read_curve_form<3>(c, chord_tolerance);
    s.points = curve.points;
    s.closed = curve.closed;
    s.samples = static_cast<int>(s.points.size());
  }
  for (Config e : c.child_list("edits", "smooth displacements [{step, t, radius, by: [x, y, z]}] (cosine bump in t)")) {
    SpaceCurveEdit ed;
    ed.step = e.get_int("step", 1, 0, 1000, "design step from which the edit applies");
    ed.t = e.get_number("t", 0.5, 0, 1, "center of the bump along the curve");
    ed.radius = e.get_number("radius", 0.25, 1e-6, 2, "half-width of the bump in t");
    ed.by = read_vec3(e, "by", ed.by, "displacement at the center");
    e.check_no_unknown_keys();
    s.edits.push_back(ed);
  }
  read_variational(c, s);
  // A variational curve starts from its traced shape before any step (the run's joint program
  // is built with it up front).
  if (s.variational && s.trace_current)
    throw InvalidConfig(c.key_path("from_surface") + ".surface: 'current' is for fixed curves; a variational curve is traced "
                        "on the initial surface (valid here: initial)");
  c.check_no_unknown_keys();
  return s;
}


void read_refinement(Config& root, SheetRunSpec& s) {
  Config rc = root.child("refinement", "automatic refinement (§4.4) and the curve check: {tolerance, max_level, max_rounds, curve_error_factor, curve_limit_share, curve_conflict_tolerance, curve_slope_tolerance, curve_probe, estimate_objective_error}");
  s.refinement.tolerance = rc.get_number("tolerance", 0, 0, 1e12, "constraint error per leaf cell above which it is refined (0: off)");
  s.refinement.max_level = rc.get_int("max_level", 4, 1, bspline::HierarchicalSurface::kMaxLevel, "deepest layer");
  s.refinement.max_rounds = rc.get_int("max_rounds", 8, 1, 100, "refine-and-solve rounds at most");
  s.refinement.curve_error_factor = rc.get_number(
      "curve_error_factor", 2, 1, 1e12,
      "a curve constraint whose pointwise error somewhere is above this multiple of its error alone on the sheet at that place is checked under refinement");
  s.refinement.curve_limit_share = rc.get_number(
      "curve_limit_share", 0.5, 0, 1,
      "such a curve constraint whose error, refined twice along the curve, tends to a limit above this share of what is left "
      "is unresolved: a warning, or constraints_unmet where another constraint meets the curve there; 0: no check");
  s.refinement.curve_conflict_tolerance = rc.get_number(
      "curve_conflict_tolerance", 1e-3, 0, 1,
      "a point or curve on a curve constraint's path asking a position more than this share of the surface's size (the "
      "diagonal of its extent over the domain) away is a conflict (constraints_unmet); also the floor of the unresolved check");
  s.refinement.curve_slope_tolerance = rc.get_number(
      "curve_slope_tolerance", 1e-3, 0, 1e6,
      "a tangent or normal on a curve constraint's path whose derivative differs from the curve's slope there by more "
      "than this (world length per design length) is a conflict (constraints_unmet)");
  s.probe_every_step = rc.get_choice("curve_probe", "last_step", {"last_step", "every_step"},
                                     "when the curve resolution probe runs: after the last step only (a drag's intermediate "
                                     "steps keep the exact conflict checks, which cost geometry only) or after every step") ==
                       "every_step";
  s.estimate_objective_error = rc.get<bool>("estimate_objective_error", false,
                                            "after the last step, solve once more with every cell refined and report the change");
  rc.check_no_unknown_keys();
}

template <class Named>
void check_distinct_names(const std::vector<Named>& items, const std::string& list) {
  std::vector<std::pair<std::string, std::string>> names;
  for (std::size_t i = 0; i < items.size(); ++i) {
    std::ostringstream key;
    key << list << "[" << i << "].name";
    names.emplace_back(key.str(), items[i].name);
  }
  check_distinct_file_names(names);
}

void read_sheets(Config& root, const std::vector<std::string>& search_dirs, SheetRunSpec& s) {
  for (Config c : root.child_list("sheets", "hierarchical B-spline sheets")) s.sheets.push_back(read_sheet(c, search_dirs));
  if (s.sheets.empty()) throw InvalidConfig("sheets: at least one sheet");
}

void read_curves(Config& root, SheetRunSpec& s) {
  int k = 0;
  for (Config c : root.child_list("curves", "space curves [{name, from_surface | points | arc | bspline, closed, samples, edits}]")) {
    s.curves.push_back(read_curve(c, s.refinement.tolerance));
    std::ostringstream key;
    key << "curves[" << k++ << "].from_surface.sheet";
    if (!s.curves.back().from_sheet.empty()) (void)sheet_config_index(s, s.curves.back().from_sheet, key.str());
  }
  check_distinct_names(s.curves, "curves");
}

// Every curve traced on a sheet: its (u, v) checked in the domain and in base spans.
void curves_to_spans(SheetRunSpec& s) {
  for (std::size_t i = 0; i < s.curves.size(); ++i) {
    std::ostringstream what;
    what << "curves[" << i << "].from_surface.uv";
    if (!s.curves[i].from_sheet.empty()) uv_to_spans(s, s.curves[i].from_sheet, s.curves[i].uv, what.str());
  }
}

void read_constraints(Config& root, SheetRunSpec& s) {
  int k = 0;
  for (Config c : root.child_list("constraints", "[{type: point|tangent|normal|curve|ribbon|offset|region|curve_point|curve_tangent|tangent_continuity, sheet, uv, ...}] (fairshape list: every type's keys)")) {
    std::ostringstream label;
    label << "constraints[" << k++ << "]";
    SheetConfigConstraint read = read_sheet_config_constraint(c, {label.str(), s.sheets.front().name, s.refinement.tolerance});
    if (auto* own = std::get_if<CurveConstraintSpec>(&read.spec)) {  // a variational curve's own (free_curves.h)
      s.curve_constraints.push_back(std::move(*own));
    } else if (auto* tc = std::get_if<TangentContinuitySpec>(&read.spec)) {
      for (int side = 0; side < 2; ++side) (void)sheet_config_index(s, tc->sheets[side], label.str() + ".sheets");
      s.tangent_continuity.push_back(std::move(*tc));
    } else {
      SheetConstraintSpec& cs = std::get<SheetConstraintSpec>(read.spec);
      prepare_sheet_constraint(s, cs);
      s.constraints.push_back(std::move(cs));
    }
  }
}

void read_energy(Config& root, SheetRunSpec& s) {
  Config ec = root.child("energy", "objective (§4.1): {metric, alpha, beta, rest_shape}");
  static const NameTable<bspline::ShapeMetric> metrics{{bspline::ShapeMetric::ThinPlate, "thin_plate"},
                                                       {bspline::ShapeMetric::Displacement, "displacement"}};
  s.energy.metric = ec.get_enum("metric", bspline::ShapeMetric::ThinPlate, metrics,
                                "thin plate under tension (eq. 4/6) or control-point displacement |p - p0|^2");
  s.energy.weights.alpha = read_weights(ec, "alpha", 0.0, Eigen::Matrix2d::Identity(),
                                           "stretching weights alpha_ij: a number a (a·I: membrane) or a 2x2 matrix");
  s.energy.weights.beta = read_weights(ec, "beta", 1.0, Eigen::Matrix2d::Ones(),
                                          "bending weights beta_ij: a number b (all b: thin plate) or a 2x2 matrix");
  s.energy.rest_shape = ec.get<bool>("rest_shape", false, "eq. 6: deform away from the initial shape instead of eq. 4");
  ec.check_no_unknown_keys();
  try {
    bspline::validate(s.energy.weights);
  } catch (const InvalidInput& e) {
    throw InvalidConfig(ec.key_path("alpha") + "/" + ec.key_path("beta") + ": " + e.what());
  }
}

void read_actions(Config& root, SheetRunSpec& s) {
  static const NameTable<RestShapeAction::Kind> action_kinds{{RestShapeAction::Kind::Install, "install_rest_shape"},
                                                             {RestShapeAction::Kind::Melt, "melt_rest_shape"}};
  int k = 0;
  for (Config a : root.child_list("actions", "§5 session actions: [{step, do: install_rest_shape | melt_rest_shape, sheet}]")) {
    std::ostringstream label;
    label << "actions[" << k++ << "]";
    RestShapeAction act;
    act.kind = a.get_enum("do", RestShapeAction::Kind::Install, action_kinds,
                          "install the sheet's current shape as its rest shape (eq. 6 about it), or melt the rest shape (eq. 4)");
    act.step = a.get_int("step", 1, 0, 1000, "design step at whose start the action applies");
    act.sheet = a.get<std::string>("sheet", "", "the sheet (default: every sheet)");
    a.check_no_unknown_keys();
    if (!act.sheet.empty()) (void)sheet_config_index(s, act.sheet, label.str() + ".sheet");
    if (s.energy.metric == bspline::ShapeMetric::Displacement)
      throw InvalidConfig(label.str() + ".do: the displacement metric always measures from the rest shape; "
                          "installing or melting applies to energy.metric: thin_plate");
    s.actions.push_back(act);
  }
}

void read_solver(Config& root, SheetRunSpec& s) {
  Config sc = root.child("solver", "constrained solver: {type, <type>: {...}}");
  const auto& reg = qp::qp_solver_registry();
  s.solver_type = sc.get_choice("type", "kkt", reg.names(), "kkt (eq. 9), qr_penalty (eq. 10) or range_space (CHOLMOD)");
  // Every solver's block is validated against its schema whichever is chosen (a sweep over
  // solver.type carries them all); the blocks of solvers not chosen are recorded as unused.
  for (const auto& name : reg.names())
    if (name != s.solver_type && sc.has(name)) {
      Config sub = sc.child(name, "options of " + name);
      (void)reg.create(name, reg.has(name, s.implementation) ? s.implementation : Backend::Optimized, sub);
      sub.check_no_unknown_keys();
      s.note_unused(sub);
    }
  {
    Config sub = sc.child(s.solver_type, "options of the chosen solver");
    s.solver = reg.create(s.solver_type, s.implementation, sub);
    sub.check_no_unknown_keys();
  }
  sc.check_no_unknown_keys();
}

void read_output(Config& root, SheetRunSpec& s) {
  Config oc = root.child("output", "what each run writes");
  s.samples_per_span = oc.get_int("samples_per_span", 6, 1, 64, "tessellation of final.obj and the VTK per base span");
  s.vtk = read_vtk_policy(oc, "vtk/<run>_step<k>.vtp of all sheets after every step");
  oc.check_no_unknown_keys();
}

// Every key of the run read from `root` (parse_config: unknown keys reported together).
SheetRunSpec read_sheet_run(const std::vector<std::string>& search_dirs, Config& root) {
  SheetRunSpec s;
  static_cast<RunBasics&>(s) = read_run_basics(root);
  read_sheets(root, search_dirs, s);
  read_refinement(root, s);  // before the curves: arcs and B-splines are sampled for its tolerance (curve_forms.h)
  check_distinct_names(s.sheets, "sheets");
  read_curves(root, s);
  curves_to_spans(s);
  read_constraints(root, s);
  read_energy(root, s);
  read_actions(root, s);
  read_solver(root, s);
  read_output(root, s);
  root.check_no_unknown_keys();
  check_free_curves(s);
  return s;
}

}  // namespace

bool is_sheet_config(const YAML::Node& c) { return c.IsMap() && c["sheets"].IsDefined(); }

int sheet_config_index(const SheetRunSpec& s, const std::string& name, const std::string& key) {
  for (std::size_t k = 0; k < s.sheets.size(); ++k)
    if (s.sheets[k].name == name) return static_cast<int>(k);
  std::string names;
  for (const auto& sh : s.sheets) names += (names.empty() ? "" : ", ") + sh.name;
  throw InvalidConfig(key + ": no sheet named '" + name + "' (sheets: " + names + ")");
}

// Every (u, v) inside its sheet's domain, checked in design units, then converted to the
// surface's base-span units.
void uv_to_spans(const SheetRunSpec& s, const std::string& sheet, std::vector<Eigen::Vector2d>& uv, const std::string& what) {
  const bspline::SheetShape& shape = s.sheets[static_cast<std::size_t>(sheet_config_index(s, sheet, what))].shape;
  const bspline::HierarchicalSurface domain(shape);
  for (std::size_t i = 0; i < uv.size(); ++i) {
    const Eigen::Vector2d spans = uv[i].cwiseQuotient(shape.span_size);
    if (!domain.in_domain(spans.x(), spans.y())) {
      std::ostringstream m;
      m << (uv.size() > 1 ? what + ", (u, v) point " + std::to_string(i) : what) << ": (u, v) = (" << uv[i].x() << ", " << uv[i].y()
        << ") is outside the sheet's domain " << (shape.periodic_u ? "(periodic in u) x" : "[0, " + num(shape.spans_u * shape.span_size.x()) + "] x")
        << " [0, " << num(shape.spans_v * shape.span_size.y()) << "] (design units: the sheet's size)";
      throw InvalidConfig(m.str());
    }
    uv[i] = spans;
  }
  // A (u, v) path is straight in the parameter domain, so on a periodic sheet a segment from
  // u = 2.36 to u = 0 runs back across the whole circumference rather than across the seam
  // (a closed ring given by its vertices did so silently): refused, with the way to write it.
  if (!shape.periodic_u) return;
  for (std::size_t i = 0; i + 1 < uv.size(); ++i)
    if (std::abs(uv[i + 1].x() - uv[i].x()) > 0.5 * shape.spans_u)
      throw InvalidConfig(what + ": the (u, v) segment from point " + std::to_string(i) + " to " + std::to_string(i + 1) +
                          " runs more than half way round the periodic sheet (u from " + num(uv[i].x() * shape.span_size.x()) +
                          " to " + num(uv[i + 1].x() * shape.span_size.x()) + "; the circumference is " +
                          num(shape.spans_u * shape.span_size.x()) +
                          "): paths are straight in (u, v); to cross the seam write u past it (u is periodic), e.g. " +
                          num((uv[i + 1].x() + (uv[i + 1].x() < uv[i].x() ? 1 : -1) * shape.spans_u) * shape.span_size.x()) +
                          ", and give a closed ring as an open path whose last point repeats the first one circumference on");
}

void prepare_sheet_constraint(const SheetRunSpec& s, SheetConstraintSpec& cs) {
  (void)sheet_config_index(s, cs.sheet, cs.label + ".sheet");
  SheetConstraint& k = cs.constraint;
  if (!cs.curve.empty()) {
    const auto it = std::find_if(s.curves.begin(), s.curves.end(), [&](const auto& cv) { return cv.name == cs.curve; });
    if (it == s.curves.end()) throw InvalidConfig(cs.label + ".curve: no space curve named '" + cs.curve + "'");
    if (k.curve.uv.empty()) {
      if (it->from_sheet != cs.sheet) throw InvalidConfig(cs.label + ".uv: required (the curve is not traced on this sheet)");
      k.curve.uv = it->uv;  // in base spans already (curves_to_spans)
      return;
    }
    if (k.curve.uv.size() < 2) throw InvalidConfig(cs.label + ".uv: at least two [u, v] points");
    uv_to_spans(s, cs.sheet, k.curve.uv, cs.label);
    return;
  }
  const bool offset = k.kind == SheetConstraint::Kind::Offset, region = k.kind == SheetConstraint::Kind::Region;
  std::vector<Eigen::Vector2d> at{{k.u, k.v}};
  uv_to_spans(s, cs.sheet, at, cs.label + (offset ? ".uv" : region ? ".corners[0]" : ""));
  k.u = at[0].x();
  k.v = at[0].y();
  if (!offset && !region) return;
  std::vector<Eigen::Vector2d> other{k.other};
  uv_to_spans(s, cs.sheet, other, cs.label + (offset ? ".from" : ".corners[1]"));
  k.other = other[0];
}

int SheetRunSpec::steps() const {
  int n = 1;
  for (const auto& c : constraints) {
    n = std::max({n, c.step + 1, c.until + 1});
    for (const auto& m : c.moves) n = std::max(n, m.step + 1);
  }
  for (const auto& c : curve_constraints) {
    n = std::max({n, c.step + 1, c.until + 1});
    for (const auto& m : c.moves) n = std::max(n, m.step + 1);
  }
  for (const auto& a : actions) n = std::max(n, a.step + 1);
  for (const auto& c : curves)
    for (const auto& e : c.edits) n = std::max(n, e.step + 1);
  return n;
}

std::vector<OptionDoc> SheetRunSpec::keys() {
  return document_keys([](Config& root) { (void)read_sheet_run({}, root); });
}

SheetRunSpec SheetRunSpec::from_config(const YAML::Node& run_config, const std::vector<std::string>& search_dirs) {
  return parse_config(run_config, [&](Config& root) { return read_sheet_run(search_dirs, root); });
}

}  // namespace fairshape
