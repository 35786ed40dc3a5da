// A rigid motion as a designer gives it in a config: a rotation by `angle_deg` about an
// `axis` through a `center` (by default the centroid of what moves), then a translation.
//   rotation: {axis: [0, 0, 1], angle_deg: 90, center: [0, 0, 0]}
//   translation: [0, 0, 0.5]
#pragma once

#include <optional>

#include "fairshape/core/config.h"
#include "fairshape/core/types.h"

namespace fairshape {

class RigidMotion {
 public:
  //! Reads `rotation` and `translation` from `cfg`. \throw InvalidConfig (zero axis, non-finite values).
  static RigidMotion from_config(Config& cfg);
  //! Where `p` goes; `centroid` is the center used when the config names none.
  Vec3 apply(const Vec3& p, const Vec3& centroid) const;

 private:
  Eigen::Matrix3d rotation_ = Eigen::Matrix3d::Identity();
  std::optional<Vec3> center_;
  Vec3 translation_ = Vec3::Zero();
};

//! Reads a 3-vector key (absent: `fallback`). \throw InvalidConfig for a wrong length or non-finite value.
Vec3 get_vec3(Config& cfg, const std::string& key, const Vec3& fallback, const std::string& doc);

}  // namespace fairshape
