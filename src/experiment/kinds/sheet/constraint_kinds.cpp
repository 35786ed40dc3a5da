#include "fairshape/experiment/kinds/sheet/constraint_kinds.h"

#include <algorithm>

#include "fairshape/core/name_table.h"
#include "fairshape/experiment/kinds/sheet/constraint_schedule.h"
#include "fairshape/experiment/kinds/sheet/curve_forms.h"
#include "fairshape/experiment/kinds/sheet/free_curves.h"
#include "fairshape/experiment/run_basics.h"

namespace fairshape {
namespace {

using bspline::SheetConstraint;
using Kind = SheetConstraint::Kind;

Eigen::Vector2d read_uv(Config& c, const std::string& key, const std::string& doc) {
  const std::vector<double> v = c.require<std::vector<double>>(key, doc);
  if (c.documenting()) return Eigen::Vector2d::Zero();
  if (v.size() != 2) throw InvalidConfig(c.key_path(key) + ": expected [u, v]");
  return {v[0], v[1]};
}

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

// The keys every constraint on a sheet has: its sheet and when it acts.
SheetConstraintSpec sheet_constraint(Config& c, const SheetConstraintContext& ctx, Kind kind) {
  SheetConstraintSpec s;
  s.label = s.constraint.label = ctx.label;
  s.constraint.kind = kind;
  s.sheet = c.get<std::string>("sheet", ctx.first_sheet, "sheet it acts on (default: the first)");
  read_schedule(c, s.step, s.until);
  return s;
}

// The curve keys of a curve or ribbon constraint.
void read_curve_keys(Config& c, SheetConstraintSpec& s, double chord_tolerance) {
  SheetConstraint& k = s.constraint;
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

SheetConstraintSpec read_curve(Config& c, const SheetConstraintContext& ctx) {
  SheetConstraintSpec s = sheet_constraint(c, ctx, Kind::Curve);
  read_curve_keys(c, s, ctx.chord_tolerance);
  return s;
}

// §5: the curve's position and the cross slope along it (ribbon_constraint.h): the sheet's own,
// or a fixed vector.
SheetConstraintSpec read_ribbon(Config& c, const SheetConstraintContext& ctx) {
  SheetConstraintSpec s = read_curve(c, ctx);
  s.constraint.ribbon = true;
  const std::string word = read_vec3_or_word(
      c, "cross_tangent", {"initial", "current"}, "initial", s.constraint.cross,
      "the derivative across the curve (to the left of its direction, per design length): initial | current (the "
      "sheet's, before any step or at the ribbon's first step) | [x, y, z]");
  if (!word.empty()) s.held = held_surface(word);
  return s;
}

SheetConstraintSpec read_region(Config& c, const SheetConstraintContext& ctx) {
  SheetConstraintSpec s = sheet_constraint(c, ctx, Kind::Region);
  SheetConstraint& k = s.constraint;
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
  return s;
}

// A constraint at one (u, v) point.
SheetConstraintSpec at_point(Config& c, const SheetConstraintContext& ctx, Kind kind) {
  SheetConstraintSpec s = sheet_constraint(c, ctx, kind);
  const Eigen::Vector2d uv = read_uv(c, "uv", "parameter point [u, v]");
  s.constraint.u = uv.x();
  s.constraint.v = uv.y();
  return s;
}

SheetConstraintSpec read_offset(Config& c, const SheetConstraintContext& ctx) {
  SheetConstraintSpec s = at_point(c, ctx, Kind::Offset);
  s.constraint.other = read_uv(c, "from", "the point [u, v] it is offset from");
  const std::string word = read_vec3_or_word(c, "offset", {"initial"}, "initial", s.constraint.target,
                                             "w(uv) - w(from): [x, y, z], or initial (as on the initial sheet)");
  s.relative = !word.empty();
  s.moves = read_moves(c, s.step);
  return s;
}

SheetConstraintSpec read_point(Config& c, const SheetConstraintContext& ctx) {
  SheetConstraintSpec s = at_point(c, ctx, Kind::Point);
  s.relative = c.has("by");
  if (s.relative && c.has("target")) throw InvalidConfig(c.key_path("by") + ": give target or by, not both");
  // Neither would pin the point to the world origin without a word.
  if (!s.relative && !c.has("target") && !c.documenting())
    throw InvalidConfig(c.path() + ": give `by` (an offset from the initial surface point, e.g. [0, 0, 0] to hold it) or "
                        "`target` (a world position)");
  s.constraint.target = s.relative ? read_vec3(c, "by", Vec3::Zero(), "offset from the initial surface point")
                                   : read_vec3(c, "target", Vec3::Zero(), "world position (or give `by`: offset from the initial point)");
  if (!s.relative) (void)c.get<std::vector<double>>("by", {0, 0, 0}, "offset from the initial surface point");
  s.moves = read_moves(c, s.step);
  return s;
}

SheetConstraintSpec read_tangent(Config& c, const SheetConstraintContext& ctx) {
  SheetConstraintSpec s = at_point(c, ctx, Kind::Tangent);
  static const NameTable<int> directions{{0, "u"}, {1, "v"}};
  s.constraint.direction = c.get_enum("direction", 0, directions, "parametric derivative D_u or D_v");
  s.constraint.target = read_vec3(c, "target", Vec3::UnitX(), "the derivative vector");
  return s;
}

SheetConstraintSpec read_normal(Config& c, const SheetConstraintContext& ctx) {
  SheetConstraintSpec s = at_point(c, ctx, Kind::Normal);
  s.constraint.target = read_vec3(c, "normal", Vec3::UnitZ(), "normal direction");
  if (!(s.constraint.target.norm() > 0) && !c.documenting())
    throw InvalidConfig(c.key_path("normal") + ": the zero vector has no direction");
  return s;
}

using Reader = SheetConstraintSpec (*)(Config&, const SheetConstraintContext&);

// A factory: the kind's reader, then no key left unread.
template <class Read>
SheetConstraintRegistry::Factory factory(Read read) {
  return [read](Config& c) {
    auto out = std::make_unique<SheetConfigConstraint>(SheetConfigConstraint{read(c)});
    c.check_no_unknown_keys();
    return out;
  };
}

}  // namespace

SheetConstraintRegistry sheet_constraint_registry(const SheetConstraintContext& ctx) {
  SheetConstraintRegistry r("sheet constraint");
  const std::pair<const char*, std::pair<const char*, Reader>> sheet_kinds[] = {
      {"point", {"§4.2.1: w(u, v) = target (or the initial point + by), dragged by moves", read_point}},
      {"tangent", {"§4.2.1: the parametric derivative D_u or D_v at (u, v) = target", read_tangent}},
      {"normal", {"§4.2.1: the tangent plane at (u, v) perpendicular to normal (n·D_u w = n·D_v w = 0)", read_normal}},
      {"curve", {"eq. 7: the sheet along a (u, v) curve follows a space curve (weak mortar rows or the paper's)", read_curve}},
      {"ribbon", {"§5: a curve constraint and the slope across it (initial, current or a vector)", read_ribbon}},
      {"offset", {"§4.2.1: w(uv) − w(from) = offset, one row shared by x, y and z", read_offset}},
      {"region", {"§4.2.2: a (u, v) rectangle holds a surface, moved rigidly by `by`", read_region}},
  };
  // Reading has no back end: each kind is registered once, under the build's fastest.
  const Backend b = kFastestBackend;
  for (const auto& [name, entry] : sheet_kinds) {
    const Reader read = entry.second;
    r.add(name, b, entry.first, factory([read, ctx](Config& c) { return read(c, ctx); }));
  }
  r.add("curve_point", b, "§5: a variational curve's point X(t) = target (or its initial point + by), dragged by moves",
        factory([ctx](Config& c) { return read_curve_constraint(c, ctx.label); }));
  r.add("curve_tangent", b, "§5: a variational curve's derivative dX/ds at t = target",
        factory([ctx](Config& c) { return read_curve_constraint(c, ctx.label); }));
  r.add("tangent_continuity", b, "§5: two sheets joined to one variational curve made tangent-continuous across it",
        factory([ctx](Config& c) { return read_tangent_continuity(c, ctx.label); }));
  return r;
}

SheetConfigConstraint read_sheet_config_constraint(Config& c, const SheetConstraintContext& ctx) {
  const SheetConstraintRegistry reg = sheet_constraint_registry(ctx);
  const std::string type = c.get_choice("type", "point", reg.names(), "constraint kind (Welch & Witkin §4.2, §5)");
  return std::move(*reg.create(type, kFastestBackend, c));
}

}  // namespace fairshape
