#include "fairshape/constraint/rigid_motion.h"

#include <numbers>

#include <Eigen/Geometry>

namespace fairshape {

Vec3 get_vec3(Config& cfg, const std::string& key, const Vec3& fallback, const std::string& doc) {
  const auto v = cfg.get<std::vector<double>>(key, {fallback.x(), fallback.y(), fallback.z()}, doc);
  if (v.size() != 3) throw InvalidConfig(cfg.key_path(key) + ": expected 3 numbers [x, y, z]");
  const Vec3 out(v[0], v[1], v[2]);
  if (!out.allFinite()) throw InvalidConfig(cfg.key_path(key) + ": not finite");
  return out;
}

RigidMotion RigidMotion::from_config(Config& cfg) {
  RigidMotion m;
  Config rot = cfg.child("rotation", "rotation {axis, angle_deg, center} applied before the translation");
  const Vec3 axis = get_vec3(rot, "axis", Vec3::UnitZ(), "rotation axis direction");
  const double angle = rot.get<double>("angle_deg", 0.0, "rotation angle in degrees (right-hand rule)");
  const auto center = rot.get<std::vector<double>>("center", {}, "a point on the axis (default: the centroid)");
  if (!center.empty()) m.center_ = get_vec3(rot, "center", Vec3::Zero(), "");
  rot.check_no_unknown_keys();
  if (axis.norm() == 0) throw InvalidConfig(rot.key_path("axis") + ": must not be zero");
  if (!std::isfinite(angle)) throw InvalidConfig(rot.key_path("angle_deg") + ": not finite");
  m.rotation_ = Eigen::AngleAxisd(angle * std::numbers::pi / 180.0, axis.normalized()).toRotationMatrix();
  m.translation_ = get_vec3(cfg, "translation", Vec3::Zero(), "translation [dx, dy, dz]");
  return m;
}

Vec3 RigidMotion::apply(const Vec3& p, const Vec3& centroid) const {
  const Vec3 c = center_.value_or(centroid);
  return rotation_ * (p - c) + c + translation_;
}

}  // namespace fairshape
