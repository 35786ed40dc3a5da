#include "fairshape/experiment/kinds/sheet/sheet_run.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include <Eigen/Geometry>

#include "fairshape/core/summary.h"
#include "fairshape/core/config.h"
#include "fairshape/core/memory.h"
#include "fairshape/core/timer.h"
#include "fairshape/experiment/kinds/sheet/constraint_schedule.h"
#include "fairshape/experiment/kinds/sheet/curve_forms.h"
#include "fairshape/experiment/kinds/sheet/free_curves.h"
#include "fairshape/experiment/kinds/sheet/sheet_files.h"
#include "fairshape/experiment/metric_format.h"
#include "fairshape/io/constraint_overlay.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/experiment/vtk_policy.h"
#include "fairshape/io/vtk_io.h"
#include "fairshape/mesh/disjoint_union.h"
#include "fairshape/mesh/polyline.h"
#include "fairshape/mesh/surface_mesh.h"
#include "fairshape/qp/range_space_solver.h"

namespace fairshape {
namespace fs = std::filesystem;
using bspline::SheetConstraint;

namespace {

Eigen::Vector2d read_uv(Config& c, const std::string& key, const std::string& doc) {
  const std::vector<double> v = c.require<std::vector<double>>(key, doc);
  if (c.documenting()) return Eigen::Vector2d::Zero();
  if (v.size() != 2) throw InvalidConfig(c.key_path(key) + ": expected [u, v]");
  return {v[0], v[1]};
}

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

const std::vector<std::string> kConstraintTypes{"point", "tangent", "normal", "curve", "ribbon", "offset", "region", "curve_point", "curve_tangent"};

// A vector key that may instead name a surface to take it from: [x, y, z], or one of `words`
// (returned; empty for a vector, read into v).
std::string read_vec3_or_word(Config& c, const std::string& key, const std::vector<std::string>& words, const std::string& fallback,
                              Vec3& v, const std::string& doc) {
  if (c.has(key) && c.node()[key].IsScalar()) return c.get_choice(key, fallback, words, doc);
  if (!c.has(key)) {
    (void)c.get_choice(key, fallback, words, doc);
    return fallback;
  }
  v = read_vec3(c, key, Vec3::Zero(), doc);
  return "";
}

SheetConstraintSpec::Held held_surface(const std::string& word) {
  return word == "initial" ? SheetConstraintSpec::Held::Initial : SheetConstraintSpec::Held::Current;
}

// The curve keys of a curve or ribbon constraint.
void read_curve_keys(Config& c, SheetConstraintSpec& s, double chord_tolerance) {
  SheetConstraint& k = s.constraint;
  k.kind = SheetConstraint::Kind::Curve;
  s.curve = c.require<std::string>("curve", "space curve name");
  k.curve.uv = read_uv_curve(c, "uv", "(u, v) curve on the sheet (default: the curve's from_surface uv)", chord_tolerance).points;
  static const NameTable<bspline::CurveFormulation> formulations{{bspline::CurveFormulation::Mortar, "mortar"},
                                                                 {bspline::CurveFormulation::Paper, "paper"}};
  k.formulation = c.get_enum("formulation", bspline::CurveFormulation::Mortar, formulations,
                             "mortar: weak rows against multipliers along the curve (no locking); paper: eq. 7, one row "
                             "per control point reached (locks; the rank tolerance picks the answer)");
  static const NameTable<bspline::CurveQuadrature> quadratures{{bspline::CurveQuadrature::Exact, "exact"},
                                                               {bspline::CurveQuadrature::Reduced, "reduced"}};
  if (c.has("quadrature") && k.formulation != bspline::CurveFormulation::Paper)
    throw InvalidConfig(c.key_path("quadrature") + ": applies to formulation: paper only (the mortar rows are integrated exactly)");
  k.quadrature = c.get_enum("quadrature", bspline::CurveQuadrature::Exact, quadratures,
                            "formulation paper: eq. 7 integration, exact or reduced (§4.2.2, against locking)");
}

SheetConstraintSpec read_constraint(Config& c, const std::string& label, const std::string& first_sheet, double chord_tolerance) {
  SheetConstraintSpec s;
  s.label = label;
  s.constraint.label = label;
  const std::string type = c.get_choice("type", "point", kConstraintTypes, "constraint kind (Welch & Witkin §4.2)");
  s.sheet = c.get<std::string>("sheet", first_sheet, "sheet it acts on (default: the first)");
  read_schedule(c, s.step, s.until);
  SheetConstraint& k = s.constraint;
  if (type == "curve" || type == "ribbon") {
    read_curve_keys(c, s, chord_tolerance);
    if (type == "ribbon") {
      // The cross slope along the curve (ribbon_constraint.h): the sheet's own, or a fixed vector.
      k.ribbon = true;
      const std::string word = read_vec3_or_word(
          c, "cross_tangent", {"initial", "current"}, "initial", k.cross,
          "the derivative across the curve (to the left of its direction, per design length): initial | current (the "
          "sheet's, before any step or at the ribbon's first step) | [x, y, z]");
      if (!word.empty()) s.held = held_surface(word);
    }
  } else if (type == "region") {
    k.kind = SheetConstraint::Kind::Region;
    const auto corners = c.require<std::vector<std::vector<double>>>("corners", "the (u, v) rectangle: [[u0, v0], [u1, v1]]");
    if (!c.documenting()) {
      if (corners.size() != 2 || corners[0].size() != 2 || corners[1].size() != 2)
        throw InvalidConfig(c.key_path("corners") + ": expected [[u0, v0], [u1, v1]]");
      k.u = std::min(corners[0][0], corners[1][0]);
      k.v = std::min(corners[0][1], corners[1][1]);
      k.other = {std::max(corners[0][0], corners[1][0]), std::max(corners[0][1], corners[1][1])};
      if (!(k.other.x() > k.u) || !(k.other.y() > k.v)) throw InvalidConfig(c.key_path("corners") + ": the rectangle is empty");
    }
    s.held = held_surface(c.get_choice("surface", "current", {"initial", "current"},
                                       "the surface the region holds: the sheet before any step, or as it is at the "
                                       "region's first step"));
    k.target = read_vec3(c, "by", Vec3::Zero(), "the region moved rigidly by this from that surface");
    s.moves = read_moves(c, s.step);
  } else {
    const Eigen::Vector2d uv = read_uv(c, "uv", "parameter point [u, v]");
    k.u = uv.x();
    k.v = uv.y();
    if (type == "offset") {
      k.kind = SheetConstraint::Kind::Offset;
      k.other = read_uv(c, "from", "the point [u, v] it is offset from");
      const std::string word = read_vec3_or_word(c, "offset", {"initial"}, "initial", k.target,
                                                 "w(uv) - w(from): [x, y, z], or initial (as on the initial sheet)");
      s.relative = !word.empty();
      s.moves = read_moves(c, s.step);
    } else if (type == "point") {
      k.kind = SheetConstraint::Kind::Point;
      s.relative = c.has("by");
      if (s.relative && c.has("target")) throw InvalidConfig(c.key_path("by") + ": give target or by, not both");
      // Neither would pin the point to the world origin without a word.
      if (!s.relative && !c.has("target") && !c.documenting())
        throw InvalidConfig(c.path() + ": give `by` (an offset from the initial surface point, e.g. [0, 0, 0] to hold it) or "
                            "`target` (a world position)");
      k.target = s.relative ? read_vec3(c, "by", Vec3::Zero(), "offset from the initial surface point")
                            : read_vec3(c, "target", Vec3::Zero(), "world position (or give `by`: offset from the initial point)");
      if (!s.relative) (void)c.get<std::vector<double>>("by", {0, 0, 0}, "offset from the initial surface point");
      s.moves = read_moves(c, s.step);
    } else if (type == "tangent") {
      k.kind = SheetConstraint::Kind::Tangent;
      static const NameTable<int> directions{{0, "u"}, {1, "v"}};
      k.direction = c.get_enum("direction", 0, directions, "parametric derivative D_u or D_v");
      k.target = read_vec3(c, "target", Vec3::UnitX(), "the derivative vector");
    } else {
      k.kind = SheetConstraint::Kind::Normal;
      k.target = read_vec3(c, "normal", Vec3::UnitZ(), "normal direction");
      if (!(k.target.norm() > 0)) throw InvalidConfig(c.key_path("normal") + ": the zero vector has no direction");
    }
  }
  c.check_no_unknown_keys();
  return s;
}

}  // namespace

bool is_sheet_config(const YAML::Node& c) { return c.IsMap() && c["sheets"].IsDefined(); }

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

// Every key of the run read from `root` (parse_config: unknown keys reported together).
static SheetRunSpec read_sheet_run(const std::vector<std::string>& search_dirs, Config& root) {
  SheetRunSpec s;
  static_cast<RunBasics&>(s) = read_run_basics(root);
  for (Config c : root.child_list("sheets", "hierarchical B-spline sheets")) s.sheets.push_back(read_sheet(c, search_dirs));
  if (s.sheets.empty()) throw InvalidConfig("sheets: at least one sheet");
  // Before the curves: arcs and B-splines are sampled finely enough for the tolerance (curve_forms.h).
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
  std::vector<std::pair<std::string, std::string>> sheet_names;
  for (std::size_t k = 0; k < s.sheets.size(); ++k) sheet_names.emplace_back("sheets[" + std::to_string(k) + "].name", s.sheets[k].name);
  check_distinct_file_names(sheet_names);
  const auto sheet_index = [&](const std::string& name, const std::string& key) {
    for (std::size_t k = 0; k < s.sheets.size(); ++k)
      if (s.sheets[k].name == name) return static_cast<int>(k);
    std::string names;
    for (const auto& sh : s.sheets) names += (names.empty() ? "" : ", ") + sh.name;
    throw InvalidConfig(key + ": no sheet named '" + name + "' (sheets: " + names + ")");
  };
  int k = 0;
  for (Config c : root.child_list("curves", "space curves [{name, from_surface | points | arc | bspline, closed, samples, edits}]")) {
    s.curves.push_back(read_curve(c, s.refinement.tolerance));
    if (!s.curves.back().from_sheet.empty()) sheet_index(s.curves.back().from_sheet, "curves[" + std::to_string(k) + "].from_surface.sheet");
    ++k;
  }
  std::vector<std::pair<std::string, std::string>> curve_names;
  for (std::size_t i = 0; i < s.curves.size(); ++i) curve_names.emplace_back("curves[" + std::to_string(i) + "].name", s.curves[i].name);
  check_distinct_file_names(curve_names);
  k = 0;
  for (Config c : root.child_list("constraints", "[{type: point|tangent|normal|curve|ribbon|offset|region|curve_point|curve_tangent|tangent_continuity, sheet, uv, ...}]")) {
    const std::string label = "constraints[" + std::to_string(k++) + "]";
    if (is_curve_constraint(c)) {  // a variational curve's own (free_curves.h)
      s.curve_constraints.push_back(read_curve_constraint(c, label));
      continue;
    }
    if (is_tangent_continuity(c)) {
      s.tangent_continuity.push_back(read_tangent_continuity(c, label));
      for (int side = 0; side < 2; ++side) sheet_index(s.tangent_continuity.back().sheets[side], label + ".sheets");
      continue;
    }
    SheetConstraintSpec cs = read_constraint(c, label, s.sheets.front().name, s.refinement.tolerance);
    sheet_index(cs.sheet, label + ".sheet");
    if (!cs.curve.empty()) {
      const auto it = std::find_if(s.curves.begin(), s.curves.end(), [&](const auto& cv) { return cv.name == cs.curve; });
      if (it == s.curves.end()) throw InvalidConfig(label + ".curve: no space curve named '" + cs.curve + "'");
      if (cs.constraint.curve.uv.empty()) {
        if (it->from_sheet != cs.sheet) throw InvalidConfig(label + ".uv: required (the curve is not traced on this sheet)");
        cs.constraint.curve.uv = it->uv;
      }
      if (cs.constraint.curve.uv.size() < 2) throw InvalidConfig(label + ".uv: at least two [u, v] points");
    }
    s.constraints.push_back(std::move(cs));
  }
  // Every (u, v) inside its sheet's domain, checked in design units before anything runs, then
  // converted to the surface's base-span units.
  const auto to_spans = [&](const std::string& sheet, std::vector<Eigen::Vector2d>& uv, const std::string& what) {
    const bspline::SheetShape& shape = s.sheets[sheet_index(sheet, what)].shape;
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
  };
  for (std::size_t i = 0; i < s.curves.size(); ++i)
    if (!s.curves[i].from_sheet.empty()) to_spans(s.curves[i].from_sheet, s.curves[i].uv, "curves[" + std::to_string(i) + "].from_surface.uv");
  for (SheetConstraintSpec& cs : s.constraints) {
    if (!cs.curve.empty()) {
      to_spans(cs.sheet, cs.constraint.curve.uv, cs.label);
      continue;
    }
    const bool two_points = cs.constraint.kind == SheetConstraint::Kind::Offset || cs.constraint.kind == SheetConstraint::Kind::Region;
    std::vector<Eigen::Vector2d> at{{cs.constraint.u, cs.constraint.v}};
    to_spans(cs.sheet, at, cs.label + (two_points ? (cs.constraint.kind == SheetConstraint::Kind::Offset ? ".uv" : ".corners[0]") : ""));
    cs.constraint.u = at[0].x();
    cs.constraint.v = at[0].y();
    if (!two_points) continue;
    std::vector<Eigen::Vector2d> other{cs.constraint.other};
    to_spans(cs.sheet, other, cs.label + (cs.constraint.kind == SheetConstraint::Kind::Offset ? ".from" : ".corners[1]"));
    cs.constraint.other = other[0];
  }
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
  static const NameTable<RestShapeAction::Kind> action_kinds{{RestShapeAction::Kind::Install, "install_rest_shape"},
                                                             {RestShapeAction::Kind::Melt, "melt_rest_shape"}};
  k = 0;
  for (Config a : root.child_list("actions", "§5 session actions: [{step, do: install_rest_shape | melt_rest_shape, sheet}]")) {
    RestShapeAction act;
    act.kind = a.get_enum("do", RestShapeAction::Kind::Install, action_kinds,
                          "install the sheet's current shape as its rest shape (eq. 6 about it), or melt the rest shape (eq. 4)");
    act.step = a.get_int("step", 1, 0, 1000, "design step at whose start the action applies");
    act.sheet = a.get<std::string>("sheet", "", "the sheet (default: every sheet)");
    a.check_no_unknown_keys();
    if (!act.sheet.empty()) sheet_index(act.sheet, "actions[" + std::to_string(k) + "].sheet");
    if (s.energy.metric == bspline::ShapeMetric::Displacement)
      throw InvalidConfig("actions[" + std::to_string(k) + "].do: the displacement metric always measures from the rest shape; "
                          "installing or melting applies to energy.metric: thin_plate");
    s.actions.push_back(act);
    ++k;
  }
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
  Config oc = root.child("output", "what each run writes");
  s.samples_per_span = oc.get_int("samples_per_span", 6, 1, 64, "tessellation of final.obj and the VTK per base span");
  s.vtk = read_vtk_policy(oc, "vtk/<run>_step<k>.vtp of all sheets after every step");
  oc.check_no_unknown_keys();
  root.check_no_unknown_keys();
  check_free_curves(s);
  return s;
}

std::vector<OptionDoc> SheetRunSpec::keys() {
  return document_keys([](Config& root) { (void)read_sheet_run({}, root); });
}

SheetRunSpec SheetRunSpec::from_config(const YAML::Node& run_config, const std::vector<std::string>& search_dirs) {
  return parse_config(run_config, [&](Config& root) { return read_sheet_run(search_dirs, root); });
}

const std::vector<std::string>& sheet_metric_columns() {
  static const std::vector<std::string> cols{
      "sheets", "steps", "dofs", "levels", "constraint_rows", "dropped_rows", "constraint_residual", "max_constraint_error",
      "energy", "spans_refined", "refinement_rounds", "objective_error_estimate", "surface_change_estimate",
      "condition_estimate", "analyze_s", "solve_s", "time_s", "peak_rss_mb", "unused_keys", "termination", "message"};
  return cols;
}

const std::vector<std::string>& sheet_cell_columns() {
  static const std::vector<std::string> cols{"sheet", "when", "round", "level", "u0", "v0", "size_u", "size_v", "error"};
  return cols;
}

const std::vector<std::string>& sheet_step_columns() {
  static const std::vector<std::string> cols{"step", "sheet", "dofs", "levels", "constraint_rows", "dropped_rows",
                                             "constraint_residual", "max_constraint_error", "energy", "spans_refined",
                                             "refinement_rounds", "analyze_s", "solve_s", "factorization", "curve_error",
                                             "curve_alone_error", "curve_error_refined", "curve_error_limit"};
  return cols;
}

namespace {

std::vector<Vec3> curve_at_step(const SpaceCurveSpec& c, const std::vector<Vec3>& base, int step) {
  std::vector<Vec3> pts = base;
  for (const SpaceCurveEdit& e : c.edits) {
    if (e.step > step) continue;
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const double t = static_cast<double>(k) / (pts.size() - 1);
      // A closed curve's bump wraps round its start (t = 0 and 1 are one point, moved alike).
      const double d = (c.closed ? std::min(std::abs(t - e.t), 1 - std::abs(t - e.t)) : std::abs(t - e.t)) / e.radius;
      if (d < 1) pts[k] += 0.5 * (1 + std::cos(M_PI * d)) * e.by;
    }
  }
  return pts;
}

// The constraints of sheet k active at `step`, with the space curves as they are then and
// relative point targets resolved on the initial surface; not its joints to variational curves
// (solved with them, free_curves.h).
std::vector<SheetConstraint> active_constraints(const SheetRunSpec& spec, std::size_t k, int step,
                                                const std::map<std::string, std::vector<Vec3>>& curves_now,
                                                const std::map<std::string, std::shared_ptr<const bspline::SurfaceTrace>>& traced_on,
                                                const std::map<std::string, std::shared_ptr<const bspline::SurfaceTrace>>& held,
                                                const bspline::HierarchicalSurface& initial_surface, const Eigen::MatrixXd& initial_P) {
  std::vector<SheetConstraint> active;
  for (const SheetConstraintSpec& cs : spec.constraints) {
    if (!cs.active_at(step) || cs.sheet != spec.sheets[k].name || cs.joins_free_curve) continue;  // joints: free_curves.h
    SheetConstraint c = cs.constraint;
    if (!cs.curve.empty()) {
      c.curve.space = curves_now.at(cs.curve);
      if (const auto t = traced_on.find(cs.curve); t != traced_on.end()) c.curve.traced = t->second;
    }
    if (cs.relative) c.target += initial_surface.position(initial_P, c.u, c.v);
    if (cs.relative && c.kind == SheetConstraint::Kind::Offset) c.target -= initial_surface.position(initial_P, c.other.x(), c.other.y());
    if (cs.held != SheetConstraintSpec::Held::None) c.surface = held.at(cs.label);
    for (const PointMove& m : cs.moves)
      if (m.step <= step) c.target += m.by;
    active.push_back(std::move(c));
  }
  return active;
}

// What a figure draws over a step (vtk/<run>_step<k>_constraints.vtp, read by fairshape
// render beside the step's .vtp): point targets as handles with the offset from where the
// initial sheet was at their (u, v), normal targets where the initial sheet was, and the space
// curves of the active curve constraints.
void add_to_overlay(const std::vector<SheetConstraint>& active, const bspline::HierarchicalSurface& initial,
                    const Eigen::MatrixXd& initial_P, ConstraintOverlay& overlay) {
  for (const SheetConstraint& c : active) {
    if (c.kind == SheetConstraint::Kind::Point) overlay.add_handle(c.target, c.target - initial.position(initial_P, c.u, c.v));
    if (c.kind == SheetConstraint::Kind::Normal) overlay.add_normal(initial.position(initial_P, c.u, c.v), c.target);
    if (c.kind == SheetConstraint::Kind::Curve) overlay.add_curve(c.curve.space);
  }
}

// The sheets at their current shape as one mesh (separate components) with displacement_norm.
SurfaceMesh sheets_mesh(const std::vector<bspline::VariationalSheet>& sheets, int per_span,
                        const std::vector<bspline::HierarchicalSurface>& initial_surfaces,
                        const std::vector<Eigen::MatrixXd>& initial_P) {
  std::vector<SurfaceMesh> meshes;
  for (std::size_t k = 0; k < sheets.size(); ++k)
    meshes.push_back(bspline::tessellate(sheets[k].surface(), sheets[k].coefficients(), per_span, initial_surfaces[k], initial_P[k]));
  return disjoint_union(meshes);
}

}  // namespace

MetricRow execute_sheet_run(SheetRunSpec& spec, const RunOutputs& out) {
  MetricRow row;
  for (const auto& c : sheet_metric_columns()) row[c] = "";
  row["implementation"] = std::string(to_string(spec.implementation));
  row["unused_keys"] = spec.unused_keys_cell();
  row["solver.type"] = spec.solver_type;
  row["sheets"] = std::to_string(spec.sheets.size());
  row["steps"] = std::to_string(spec.steps());
  row["termination"] = std::string(to_string(Termination::Converged));
  const Timer wall;
  reset_peak_rss();  // this run's own peak, not an earlier run's of the sweep
  int step = 0;
  try {
    // Sheets, refined up front; curves traced on the initial surfaces.
    std::vector<bspline::VariationalSheet> sheets;
    std::vector<bspline::HierarchicalSurface> initial_surfaces;
    std::vector<Eigen::MatrixXd> initial_P;
    for (const SheetSpec& ss : spec.sheets) {
      sheets.push_back(initial_sheet(ss));
      if (!ss.refine.empty()) sheets.back().refine(ss.refine);
      initial_surfaces.push_back(sheets.back().surface());
      initial_P.push_back(sheets.back().coefficients());
    }
    const auto sheet_of = [&](const std::string& name) {
      for (std::size_t k = 0; k < spec.sheets.size(); ++k)
        if (spec.sheets[k].name == name) return k;
      return std::size_t{0};
    };
    std::map<std::string, std::vector<Vec3>> base_curves;
    const auto trace = [&](const SpaceCurveSpec& c) {
      const std::size_t k = sheet_of(c.from_sheet);
      base_curves[c.name] = bspline::surface_curve(sheets[k].surface(), sheets[k].coefficients(), c.uv, c.samples);
    };
    for (const SpaceCurveSpec& c : spec.curves) {
      if (c.from_sheet.empty()) base_curves[c.name] = c.points;
      else trace(c);
    }
    // Curves traced on the current surface: traced again at their first step, before it is
    // solved, and that surface kept as their target.
    std::map<std::string, std::shared_ptr<const bspline::SurfaceTrace>> traced_on;
    // The surfaces regions and ribbons hold, by constraint label: the initial sheet's now, the
    // current ones at the constraint's first step (before it is solved: adding it moves nothing).
    std::map<std::string, std::shared_ptr<const bspline::SurfaceTrace>> held;
    const auto hold = [&](const SheetConstraintSpec& cs) {
      const std::size_t k = sheet_of(cs.sheet);
      held[cs.label] = std::make_shared<const bspline::SurfaceTrace>(bspline::SurfaceTrace{sheets[k].surface(), sheets[k].coefficients()});
    };
    for (const SheetConstraintSpec& cs : spec.constraints)
      if (cs.held == SheetConstraintSpec::Held::Initial) hold(cs);
    const auto first_use = [&](const SpaceCurveSpec& c) {
      int first = -1;
      for (const SheetConstraintSpec& cs : spec.constraints)
        if (cs.curve == c.name && (first < 0 || cs.step < first)) first = cs.step;
      return std::max(first, 0);
    };
    FreeCurves free_curves(spec, base_curves);
    std::map<std::string, std::vector<Vec3>> final_curves;  // the space curves at the last step
    double analyze_s = 0, solve_s = 0, energy = 0, residual = 0, max_err = 0, cond = 0;
    int dofs = 0, rows = 0, dropped = 0, refined = 0, rounds = 0, levels = 0;
    bool solved_any = false;  // a sheet or a free curve had something acting on it
    // Per sheet, the last step's constraint error per leaf cell after every solve (Figure 3).
    std::vector<std::vector<std::vector<bspline::CellError>>> cell_errors(sheets.size());
    bool failed = false;
    // Each sheet's objective: eq. 4, or eq. 6 about a rest shape the session installed.
    std::vector<bspline::SheetEnergy> energies(sheets.size(), spec.energy);
    for (step = 0; step < spec.steps() && !failed; ++step) {
      std::vector<std::shared_ptr<const bspline::VariationalSheet>> unrefined(sheets.size());
      for (const RestShapeAction& a : spec.actions) {
        if (a.step != step) continue;
        for (std::size_t k = 0; k < sheets.size(); ++k) {
          if (!a.sheet.empty() && a.sheet != spec.sheets[k].name) continue;
          if (a.kind == RestShapeAction::Kind::Install) sheets[k].install_rest_shape();
          energies[k].rest_shape = a.kind == RestShapeAction::Kind::Install;
        }
      }
      for (const SpaceCurveSpec& c : spec.curves) {
        if (!c.trace_current || first_use(c) != step) continue;
        trace(c);
        const std::size_t k = sheet_of(c.from_sheet);
        traced_on[c.name] = std::make_shared<const bspline::SurfaceTrace>(
            bspline::SurfaceTrace{sheets[k].surface(), sheets[k].coefficients()});
      }
      for (const SheetConstraintSpec& cs : spec.constraints)
        if (cs.held == SheetConstraintSpec::Held::Current && cs.step == step) hold(cs);
      std::map<std::string, std::vector<Vec3>> curves_now;
      for (const SpaceCurveSpec& c : spec.curves) curves_now[c.name] = curve_at_step(c, base_curves.at(c.name), step);
      ConstraintOverlay overlay;
      std::vector<std::vector<SheetConstraint>> actives;
      for (std::size_t k = 0; k < sheets.size(); ++k)
        actives.push_back(active_constraints(spec, k, step, curves_now, traced_on, held, initial_surfaces[k], initial_P[k]));
      // Sheets joined to variational curves first, with them (their curves' shapes into curves_now).
      const JoinedStep joined = free_curves.solve_step(spec, step, sheets, energies, actives, curves_now, overlay);
      final_curves = curves_now;
      // The resolution probe costs many solves: on the last step only unless asked for every step.
      bspline::RefinementOptions refinement_now = spec.refinement;
      refinement_now.curve_probe = spec.probe_every_step || step + 1 == spec.steps();
      for (std::size_t k = 0; k < sheets.size(); ++k) {
        const std::vector<SheetConstraint>& active = actives[k];
        const auto joint = joined.sheets.find(k);
        if (active.empty() && joint == joined.sheets.end()) continue;  // nothing acts on this sheet yet: it keeps its shape
        // After a failure only the sheets solved with the failed group are still reported (they
        // share its answer); nothing else is solved.
        if (failed && joint == joined.sheets.end()) continue;
        add_to_overlay(active, initial_surfaces[k], initial_P[k], overlay);
        const bspline::DesignReport r = joint != joined.sheets.end()
                                            ? joint->second.report
                                            : bspline::solve_sheet(sheets[k], energies[k], active, *spec.solver, refinement_now, spec.implementation);
        const auto& s = sheets[k].surface();
        out.add_row("steps", {std::to_string(step), spec.sheets[k].name, std::to_string(s.dof_count()),
                      std::to_string(s.level_count()), std::to_string(r.constraint_rows), std::to_string(r.qp.dropped_rows),
                      num(r.qp.constraint_residual), num(r.max_constraint_error), num(r.energy),
                      std::to_string(r.spans_refined), std::to_string(r.rounds), num(r.analyze_s), num(r.solve_s),
                      joint != joined.sheets.end() ? joint->second.factorization : qp::factorization_note(*spec.solver),
                      num(r.curve_error), num(r.curve_alone_error), num(r.curve_error_refined),
                      num(r.curve_error_limit)});
        const bool this_failed = !is_success(r.qp.summary.termination);
        if (this_failed && !failed) {  // the first failure names the row
          row["termination"] = std::string(to_string(r.qp.summary.termination));
          row["message"] = "step " + std::to_string(step) + ", sheet " + spec.sheets[k].name + ": " + r.message;
        } else if (!failed && !r.message.empty()) {
          row["message"] = spec.sheets[k].name + ": " + r.message;
        }
        if (spec.solver_type == "paper")  // a different answer, said where the numbers are
          row["message"] += std::string(row["message"].empty() ? "" : "; ") +
                            "paper split: the constrained control points are the minimum-norm least-squares solution of "
                            "their rows, not optimized (energy above the minimizer's)";
        failed = failed || this_failed;
        cell_errors[k] = r.errors_per_round;  // the last step's solve wins (Figure 3: every refinement round)
        unrefined[k] = r.unrefined;
        analyze_s += r.analyze_s;
        solve_s += r.solve_s;
        refined += r.spans_refined;
        rounds += r.rounds;
        solved_any = true;
        if (step + 1 == spec.steps() || failed) {  // the row: the last step, or the one that failed
          energy += r.energy;
          residual = std::hypot(residual, r.qp.constraint_residual);
          max_err = std::max(max_err, r.max_constraint_error);
          rows += static_cast<int>(r.constraint_rows);
          dropped += r.qp.dropped_rows;
          if (!std::isnan(r.qp.condition_estimate)) cond = std::max(cond, r.qp.condition_estimate);
        }
      }
      for (const FreeCurveStep& c : joined.curves) {  // a row per free curve (its group's termination)
        solved_any = true;
        out.add_row("steps", free_curve_step_row(step, c));
        if (!failed && !is_success(c.termination)) {
          failed = true;
          row["termination"] = std::string(to_string(c.termination));
          row["message"] = "step " + std::to_string(step) + ", curve " + c.name + ": " + c.message;
        }
        if (step + 1 == spec.steps() || failed) {
          energy += c.energy;
          residual = std::hypot(residual, c.residual);
          max_err = std::max(max_err, c.max_error);
          dofs += c.dofs;
          rows += c.rows;
        }
      }
      // Per step: all sheets in one polydata (point array displacement_norm) and the space curves
      // (a failed step's too: what it achieved, under its termination).
      {
        if (spec.vtk == VtkPolicy::All || (spec.vtk == VtkPolicy::Final && (step + 1 == spec.steps() || failed))) {
          const std::string stem = (fs::path(out.dir) / "vtk" / (out.run_id + "_step" + std::to_string(step))).string();
          write_vtp(sheets_mesh(sheets, spec.samples_per_span, initial_surfaces, initial_P), stem + ".vtp");
          overlay.write(stem + "_constraints.vtp");
          // The step's first solve, before automatic refinement changed it (no "_step" in the
          // name: figure scripts glob the steps).
          if (std::any_of(unrefined.begin(), unrefined.end(), [](const auto& u) { return u != nullptr; })) {
            std::vector<bspline::VariationalSheet> first;
            for (std::size_t k = 0; k < sheets.size(); ++k) first.push_back(unrefined[k] ? *unrefined[k] : sheets[k]);
            const std::string before = (fs::path(out.dir) / "vtk" / (out.run_id + "_unrefined" + std::to_string(step))).string();
            write_vtp(sheets_mesh(first, spec.samples_per_span, initial_surfaces, initial_P), before + ".vtp");
            overlay.write(before + "_constraints.vtp");
          }
        }
        if (spec.vtk == VtkPolicy::All) write_sheet_files(out, spec.sheets, sheets, step);
        fs::create_directories(fs::path(out.dir) / "curves");
        for (const auto& [name, pts] : curves_now) {
          MatrixX3 X(static_cast<Eigen::Index>(pts.size()), 3);
          for (std::size_t i = 0; i < pts.size(); ++i) X.row(static_cast<Eigen::Index>(i)) = pts[i].transpose();
          write_polyline(Polyline{X, false}, (fs::path(out.dir) / "curves" / (out.run_id + "_step" + std::to_string(step) + "_" + file_name_part(name) + ".obj")).string());
        }
      }
    }
    if (spec.estimate_objective_error && row["termination"] == to_string(Termination::Converged)) {
      double energy_change = 0, surface_change = 0;
      for (std::size_t k = 0; k < sheets.size(); ++k) {
        const auto active = active_constraints(spec, k, spec.steps() - 1, final_curves, traced_on, held, initial_surfaces[k], initial_P[k]);
        if (active.empty()) continue;
        const bspline::ObjectiveErrorEstimate e =
            bspline::estimate_objective_error(sheets[k], energies[k], active, *spec.solver, spec.implementation);
        if (!e.message.empty()) row["message"] = e.message;
        energy_change = std::max(energy_change, e.energy_change);
        surface_change = std::max(surface_change, e.surface_change);
      }
      row["objective_error_estimate"] = num(energy_change);
      row["surface_change_estimate"] = num(surface_change);
    }
    // Constraint error per leaf cell after every solve of the last step (Figure 3): `when` is
    // before (the first solve), after (the last; a single solve is both) or between.
    for (std::size_t k = 0; k < sheets.size(); ++k)
      for (std::size_t n = 0; n < cell_errors[k].size(); ++n) {
        std::vector<std::string> whens;
        if (n == 0) whens.push_back("before");
        if (n + 1 == cell_errors[k].size()) whens.push_back("after");
        if (whens.empty()) whens.push_back("between");
        for (const std::string& when : whens)
          for (const bspline::CellError& e : cell_errors[k][n]) {
            const Eigen::Vector2d h = std::ldexp(1.0, -e.cell.level) * spec.sheets[k].shape.span_size;  // design units
            out.add_row("cells", {spec.sheets[k].name, when, std::to_string(n + 1), std::to_string(e.cell.level), num(e.cell.i * h.x()),
                                  num(e.cell.j * h.y()), num(h.x()), num(h.y()), num(e.error)});
          }
      }
    write_mesh(sheets_mesh(sheets, spec.samples_per_span, initial_surfaces, initial_P), out.final_path());
    write_sheet_files(out, spec.sheets, sheets, -1);
    // Every sheet's unknowns and layers, whether or not something acted on it.
    for (const bspline::VariationalSheet& sh : sheets) dofs += sh.surface().dof_count(), levels = std::max(levels, sh.surface().level_count());
    if (!solved_any && !failed && row["message"].empty())
      row["message"] = "no constraint acts on any sheet at any step: nothing was solved (the sheets keep their shapes)";
    row["dofs"] = std::to_string(dofs);
    row["levels"] = std::to_string(levels);
    row["constraint_rows"] = std::to_string(rows);
    row["dropped_rows"] = std::to_string(dropped);
    row["constraint_residual"] = num(residual);
    row["max_constraint_error"] = num(max_err);
    row["energy"] = num(energy);
    row["spans_refined"] = std::to_string(refined);
    row["refinement_rounds"] = std::to_string(rounds);
    if (cond > 0) row["condition_estimate"] = num(cond);
    row["analyze_s"] = num(analyze_s);
    row["solve_s"] = num(solve_s);
  } catch (const OutputError& e) {  // results incomplete: not a finished run
    row["termination"] = std::string(to_string(Termination::OutputFailed));
    row["message"] = e.what();
  } catch (const Error& e) {
    row["termination"] = std::string(to_string(Termination::InvalidInput));
    row["message"] = "step " + std::to_string(step) + ": " + e.what();
  }
  row["time_s"] = num(wall.seconds());
  row["peak_rss_mb"] = num(peak_rss_mb());
  return row;
}

}  // namespace fairshape
