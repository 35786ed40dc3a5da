#include "fairshape/curve_design/curve_components.h"

#include <algorithm>
#include <cmath>

#include "fairshape/core/config.h"

namespace fairshape {
namespace {

class SegmentLengthsKind final : public CurveConstraintKind {
 public:
  std::unique_ptr<CurveConstraint> build(const CurveEditContext& e) const override {
    return std::make_unique<SegmentLengths>(e.lengths, e.reference.closed);
  }
};

// The paper's alternative to per-segment lengths: the curve's total length kept (`value`
// omitted: the reference curve's length) while its segments may stretch.
class TotalLengthKind final : public CurveConstraintKind {
 public:
  explicit TotalLengthKind(Config& c) {
    const bool given = c.has("value");  // read either way, so `fairshape list` shows the option
    value_ = c.get<double>("value", 0, "the total length to keep, a positive length (omitted: the reference curve's length)");
    if (given && (!(value_ > 0) || !std::isfinite(value_)))
      throw InvalidConfig(c.key_path("value") + ": " + format_default(value_) +
                          " is not a length; give a positive finite number (or omit it: the reference curve's length)");
  }
  std::unique_ptr<CurveConstraint> build(const CurveEditContext& e) const override {
    return std::make_unique<TotalLength>(e.lengths, value_ > 0 ? value_ : e.lengths.sum(), e.reference.closed);
  }

 private:
  double value_ = 0;  // 0: the reference's length
};

// Which points a pin or tangent constraint holds: the edit's moved control points, the
// endpoints or a list of fine-level indices (sorted, without repeats).
class PointSelection {
 public:
  PointSelection(Config& c, const std::string& kind) : kind_(kind) {
    const std::string doc = "edited (the moved control points) | endpoints | [fine-level indices]";
    if (c.node()["points"] && c.node()["points"].IsSequence()) {
      indices_ = c.get<std::vector<int>>("points", {}, doc);
      mode_ = "list";
      return;
    }
    mode_ = c.get<std::string>("points", "edited", doc);
    if (mode_ != "edited" && mode_ != "endpoints")
      throw InvalidConfig(c.key_path("points") + ": '" + mode_ + "' is not one of edited, endpoints, [indices]");
  }
  std::vector<int> points(const CurveEditContext& e) const {
    const int n = e.reference.n_points();
    std::vector<int> pts = indices_;
    if (mode_ == "edited") pts = e.moved_points;
    if (mode_ == "endpoints") {
      if (e.reference.closed) throw InvalidInput(kind_ + ": a closed curve has no endpoints");
      pts = {0, n - 1};
    }
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    for (int p : pts)
      if (p < 0 || p >= n) throw InvalidInput(kind_ + ": point " + std::to_string(p) + " is not on the curve (0.." + std::to_string(n - 1) + ")");
    return pts;
  }

 private:
  std::string kind_, mode_ = "edited";
  std::vector<int> indices_;
};

// `at: edited` (C_D, where the edit put the point, the default) or `reference` (C_R, where it was).
const MatrixX3& held_curve(const std::string& at, const CurveEditContext& e) { return at == "reference" ? e.reference.points : e.edited; }

// Points held where the edit put them (C_D's positions), or where they were (C_R's).
class PinKind final : public CurveConstraintKind {
 public:
  explicit PinKind(Config& c) : points_(c, "pin") {
    at_ = c.get_choice("at", "edited", {"edited", "reference"}, "hold the points where the edit put them, or where they were");
  }
  std::unique_ptr<CurveConstraint> build(const CurveEditContext& e) const override {
    std::vector<int> pts = points_.points(e);
    const MatrixX3& from = held_curve(at_, e);
    MatrixX3 targets(static_cast<Eigen::Index>(pts.size()), 3);
    for (std::size_t k = 0; k < pts.size(); ++k) targets.row(static_cast<Eigen::Index>(k)) = from.row(pts[k]);
    return std::make_unique<PinnedPoints>(std::move(pts), std::move(targets));
  }

 private:
  PointSelection points_;
  std::string at_;
};

// Tangents held along their direction on C_D (`direction: edited`), on C_R (`reference`) or
// along a given [x, y, z].
class TangentKind final : public CurveConstraintKind {
 public:
  explicit TangentKind(Config& c) : points_(c, "tangent") {
    const std::string doc = "edited (the tangent where the edit put it) | reference (as it was) | [x, y, z]";
    if (c.node()["direction"] && c.node()["direction"].IsSequence()) {
      const auto d = c.get<std::vector<double>>("direction", {}, doc);
      if (d.size() != 3 || !(Vec3(d[0], d[1], d[2]).norm() > 0))
        throw InvalidConfig(c.key_path("direction") + ": expected a nonzero [x, y, z]");
      direction_ = Vec3(d[0], d[1], d[2]);
      mode_ = "given";
      return;
    }
    mode_ = c.get_choice("direction", "edited", {"edited", "reference"}, doc);
  }
  std::unique_ptr<CurveConstraint> build(const CurveEditContext& e) const override {
    std::vector<int> pts = points_.points(e);
    const int n = e.reference.n_points();
    const bool closed = e.reference.closed;
    MatrixX3 directions(static_cast<Eigen::Index>(pts.size()), 3);
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const auto [a, b] = FixedTangents::chord(pts[k], n, closed);
      const MatrixX3& from = held_curve(mode_ == "reference" ? "reference" : "edited", e);
      directions.row(static_cast<Eigen::Index>(k)) = mode_ == "given" ? direction_.transpose() : Eigen::RowVector3d(from.row(b) - from.row(a));
    }
    auto c = std::make_unique<FixedTangents>(std::move(pts), std::move(directions), n, closed);
    c->set_scales(e.reference.points);
    return c;
  }

 private:
  PointSelection points_;
  std::string mode_;
  Vec3 direction_ = Vec3::Zero();
};

}  // namespace

void register_curve_constraints(CurveConstraintRegistry& r) {
  for (Backend b : built_backends()) {
    r.add("segment_lengths", b, "Sauvage et al. §2: |c[i+1] - c[i]|² = l[i]² for every segment of the reference",
          [](Config&) { return std::make_unique<SegmentLengthsKind>(); });
    r.add("total_length", b,
          "the alternative Sauvage et al. discuss: the curve's total length kept ({value: L}, omitted: the reference's), "
          "segments free to stretch; replaces segment_lengths",
          [](Config& c) { return std::make_unique<TotalLengthKind>(c); });
    r.add("pin", b, "points held where the edit put them (at: edited) or where they were (at: reference)",
          [](Config& c) { return std::make_unique<PinKind>(c); });
    r.add("tangent", b, "tangents (the chord through a point's neighbours) held along a direction: edited | reference | [x, y, z]",
          [](Config& c) { return std::make_unique<TangentKind>(c); });
  }
}

const CurveComponents& curve_components() {
  static const CurveComponents instance = [] {
    CurveComponents c;
    register_curve_energies(c.energies);
    register_curve_constraints(c.constraints);
    register_length_solvers(c.solvers);
    return c;
  }();
  return instance;
}

}  // namespace fairshape
