#include "curve_design/curve_components.h"

#include <algorithm>

#include "core/config.h"

namespace fairshape {
namespace {

class SegmentLengthsKind final : public CurveConstraintKind {
 public:
  std::unique_ptr<CurveConstraint> build(const CurveEditContext& e) const override {
    return std::make_unique<SegmentLengths>(segment_lengths(e.reference.points, e.reference.closed), e.reference.closed);
  }
};

// Points held where the edit put them (C_D's positions).
class PinKind final : public CurveConstraintKind {
 public:
  explicit PinKind(Config& c) {
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
  std::unique_ptr<CurveConstraint> build(const CurveEditContext& e) const override {
    const int n = e.reference.n_points();
    std::vector<int> pts = indices_;
    if (mode_ == "edited") pts = e.moved_points;
    if (mode_ == "endpoints") {
      if (e.reference.closed) throw InvalidInput("pin: a closed curve has no endpoints");
      pts = {0, n - 1};
    }
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    MatrixX3 targets(static_cast<Eigen::Index>(pts.size()), 3);
    for (std::size_t k = 0; k < pts.size(); ++k) {
      if (pts[k] < 0 || pts[k] >= n)
        throw InvalidInput("pin: point " + std::to_string(pts[k]) + " is not on the curve (0.." + std::to_string(n - 1) + ")");
      targets.row(static_cast<Eigen::Index>(k)) = e.edited.row(pts[k]);
    }
    return std::make_unique<PinnedPoints>(std::move(pts), std::move(targets));
  }

 private:
  std::string mode_ = "edited";
  std::vector<int> indices_;
};

}  // namespace

void register_curve_constraints(CurveConstraintRegistry& r) {
  for (Backend b : {Backend::Reference, Backend::Optimized}) {
    r.add("segment_lengths", b, "Sauvage et al. §2: |c[i+1] - c[i]|² = l[i]² for every segment of the reference",
          [](Config&) { return std::make_unique<SegmentLengthsKind>(); });
    r.add("pin", b, "points held where the edit put them",
          [](Config& c) { return std::make_unique<PinKind>(c); });
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
