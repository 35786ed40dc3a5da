#include "fairshape/design/orientation_check.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "fairshape/design/multires_constraints.h"

namespace fairshape {

std::string OrientationCheck::describe() const {
  std::ostringstream os;
  os.precision(4);
  if (!folds.flipped.empty()) os << "folded: " << folds.describe();
  if (!reversed.empty()) {
    os << (folds.flipped.empty() ? "folded: " : "; ") << "normal constraint" << (reversed.size() > 1 ? "s " : " ");
    for (std::size_t i = 0; i < reversed.size(); ++i) os << (i ? ", " : "") << reversed[i];
    os << " met by the reverse of the target (" << normal_error_deg << " degrees from it)";
  }
  return os.str();
}

namespace {

// The achieved normal of every normal constraint against its target, into c.
void check_normals(const MultiresSurface& rest, const MultiresSurface& edited, const DesignConstraints& placed,
                   OrientationCheck& c) {
  for (const NormalConstraint& nc : placed.normals) {
    const Vec3 n = achieved_normal(rest.mesh(nc.level), edited.mesh(nc.level).positions(), nc);
    const double cosine = n.dot(nc.normal.normalized());
    const double deg = std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi;
    c.normal_error_deg = std::max(c.normal_error_deg, deg);
    if (cosine >= 0) continue;
    c.reversed_auto |= nc.rows == NormalRows::Auto;
    if (std::find(c.reversed.begin(), c.reversed.end(), nc.label) == c.reversed.end()) c.reversed.push_back(nc.label);
  }
}

}  // namespace

OrientationCheck check_orientation(const MultiresSurface& rest, const MultiresSurface& edited,
                                   const DesignConstraints& placed) {
  OrientationCheck c;
  const int finest = rest.levels();
  c.folds = flipped_faces(rest.mesh(finest), edited.mesh(finest).positions());
  check_normals(rest, edited, placed, c);
  return c;
}

StepOrientationCheck::StepOrientationCheck(const MultiresSurface& rest, int level, const DesignConstraints& placed)
    : rest_(rest), level_(level), placed_(placed), edited_(rest), rest_faces_(rest.mesh(rest.levels())) {}

OrientationCheck StepOrientationCheck::operator()(const Eigen::MatrixXd& delta) {
  edited_.set_level_positions(level_, rest_.mesh(level_).positions() + MatrixX3(delta));
  edited_.synthesize_from(level_, DetailSpace::Local);
  OrientationCheck c;
  c.folds = rest_faces_.compare(edited_.mesh(rest_.levels()).positions());
  check_normals(rest_, edited_, placed_, c);
  return c;
}

std::string solve_orienting_normals(const std::function<OrientationCheck(bool frame_rows)>& solve) {
  const OrientationCheck with_tangent_rows = solve(false);
  if (!with_tangent_rows.reversed_auto) return "";
  solve(true);
  return "tangent rows " + with_tangent_rows.describe() + ", so solved again with frame rows";
}

std::string noted(const std::string& note, const std::string& message) {
  return note.empty() || message.empty() ? note + message : note + "; " + message;
}

}  // namespace fairshape
