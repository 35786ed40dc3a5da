// The config keys that place a feature curve (configs/README.md, "Feature-curve experiments"):
// `points`, `surface_points`, or one of the placement tools `geodesic`, `section`, `polyline`.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fairshape/core/config.h"
#include "fairshape/feature/curve_placement.h"
#include "fairshape/feature/feature_drawing.h"

namespace fairshape {

//! `key` as a list of [x, y, z]. \throw InvalidConfig naming the key and the entry.
std::vector<Vec3> read_point_list(Config& c, const std::string& key, const std::string& doc);
//! `key` as a list of [face, b0, b1, b2] (weights >= 0 summing to 1). \throw InvalidConfig.
std::vector<feature::SurfacePoint> read_surface_point_list(Config& c, const std::string& key, const std::string& doc);

//! The feature's placement tool, if it names one: `geodesic: {through | through_surface,
//! spacing, smooth}`, `section: {point, normal, nearest, from, to, arc, spacing}` or
//! `polyline: <file>` (resolved in `dirs`). \throw InvalidConfig naming the key: a value out of
//! range or not finite, an unknown key inside the block, too few waypoints.
std::optional<feature::CurvePlacement> read_curve_placement(Config& feature, const std::vector<std::string>& dirs);

//! How many of points, surface_points, geodesic, section, polyline the feature gives.
int curve_keys_given(const Config& feature);

//! The feature's curve keys (exactly one of the five, and `closed`) into `f`: world points,
//! surface points or a placement tool. `where` is the feature's key ("features[2]").
//! \throw InvalidConfig naming the key: none or several given, too few points for an open or
//! closed curve, `closed` with a section, a closed curve with end_height_ratio ≠ 1.
void read_curve_source(Config& feature, const std::string& where, const std::vector<std::string>& dirs,
                       feature::FeatureDrawing& f);

}  // namespace fairshape
