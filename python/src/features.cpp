// Feature curves of Khodakovsky & Schröder, "Fine level feature editing for subdivision
// surfaces" (src/feature): curves drawn on levels of a Loop hierarchy, given by (face,
// barycentric) points of their level or by 3-D points projected onto it, with the profile
// parameters of a feature config's `features:` entries (the same names, ranges and defaults;
// an unknown key is refused naming the valid ones), applied coarse to fine; the achieved
// profile of each measured as features.csv reports it (feature/profile_measure.h).
// Copies: the finest positions come back as a new n×3 array; the result is a new MultiresSurface.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "checks.h"
#include "convert.h"
#include "fairshape/mesh/orientation.h"
#include "fairshape/experiment/kinds/feature/feature_run.h"
#include "fairshape/feature/featured_surface.h"
#include "fairshape/feature/profile_measure.h"

namespace py = pybind11;

namespace fairshape::python {
namespace {

FeatureSpec read_feature(Config& c, const std::string& where, int levels) {
  FeatureSpec f;
  f.key = where;
  f.curve.name = c.get<std::string>("name", where, "name in messages and results");
  f.curve.level = c.get_int("level", 0, 0, levels, "the hierarchy level the curve is drawn on");
  f.curve.closed = c.get<bool>("closed", false, "the polygon returns to its first point");
  f.curve.params = read_feature_params(c, feature::FeatureParams{});
  f.max_distance = c.get_number("max_distance", 0.02, 0, 1, "× bounding-box diagonal: farther points leave the surface");
  const auto points = c.get<std::vector<std::vector<double>>>("points", {}, "k×3 world points, projected onto the level");
  const auto faces = c.get<std::vector<int>>("faces", {}, "k faces of the level (with bary)");
  const auto bary = c.get<std::vector<std::vector<double>>>("bary", {}, "k×3 barycentric coordinates in those faces");
  c.check_no_unknown_keys();
  if (points.empty() == faces.empty())
    throw InvalidConfig(where + ": give exactly one of points (k×3 world points) and faces + bary (surface points)");
  for (const auto& p : points) {
    if (p.size() != 3) throw InvalidConfig(c.key_path("points") + ": expected k×3");
    f.world_points.emplace_back(p[0], p[1], p[2]);
  }
  if (!faces.empty()) {
    if (bary.size() != faces.size()) throw InvalidConfig(c.key_path("bary") + ": one barycentric triple per face");
    for (std::size_t i = 0; i < faces.size(); ++i) {
      if (bary[i].size() != 3) throw InvalidConfig(c.key_path("bary") + ": expected k×3");
      f.curve.points.push_back({faces[i], Vec3(bary[i][0], bary[i][1], bary[i][2])});
    }
  }
  try {
    f.curve.params.validate(where);
  } catch (const InvalidInput& e) {
    throw InvalidConfig(e.what());
  }
  return f;
}

py::dict profile_dict(const feature::ProfileMeasure& m) {
  py::dict d;
  d["height_min"] = m.height_min;
  d["height_max"] = m.height_max;
  d["width_left"] = m.width_left;
  d["width_right"] = m.width_right;
  d["height_error"] = m.height_error;
  d["width_error"] = m.width_error;
  d["profile_error"] = m.profile_error;
  return d;
}

py::dict apply_features(const MultiresSurface& hierarchy, const py::list& features, const std::string& profile_on,
                        const std::string& implementation) {
  FeatureRunSpec spec;
  spec.implementation = backend_arg(implementation);
  spec.levels = hierarchy.levels();
  const auto& targets = feature::profile_target_names();
  spec.profile_target = targets.value(profile_on, "profile_on");
  if (features.empty()) throw InvalidConfig("features: at least one feature curve");
  for (std::size_t i = 0; i < features.size(); ++i) {
    const std::string where = "features[" + std::to_string(i) + "]";
    if (!py::isinstance<py::dict>(features[i])) throw InvalidConfig(where + ": expected a dict (fairshape.feature(...))");
    Config c = to_config(features[i].cast<py::dict>(), where);
    spec.features.push_back(read_feature(c, where, spec.levels));
  }
  py::dict out;
  std::vector<feature::FeatureMeasure> measured;
  std::vector<feature::FeatureParams> params;
  MultiresSurface result_copy = hierarchy;
  {
    py::gil_scoped_release release;
    feature::FeaturedSurface surface(hierarchy, spec.implementation, spec.profile_target);
    std::map<int, feature::TriangleSurface> drawn_on;
    for (FeatureSpec& f : spec.features) {
      place_feature(spec, surface, f, &drawn_on);
      f.id = surface.add(f.curve);
    }
    result_copy = surface.result();
    measured = feature::measure_features(surface);
    for (const auto& m : measured) params.push_back(surface.features().at(m.id).params);
  }
  py::list rows;
  bool all_within = true;
  for (std::size_t i = 0; i < measured.size(); ++i) {
    const auto& f = measured[i];
    const auto& q = params[i];
    py::dict d;
    d["name"] = f.name;
    d["level"] = f.level;
    d["height"] = q.height;
    d["radius_left"] = q.radius;
    d["radius_right"] = q.right_radius();
    d["fine"] = profile_dict(f.fine);
    d["limit"] = profile_dict(f.limit);
    d["within_tolerance"] = f.within_tolerance;
    d["why"] = f.why;
    all_within = all_within && f.within_tolerance;
    rows.append(d);
  }
  // Each feature's surface points as placed (projected world points), for reuse.
  py::list placed;
  for (const FeatureSpec& f : spec.features) {
    Eigen::VectorXi faces(static_cast<Eigen::Index>(f.curve.points.size()));
    Eigen::MatrixXd bary(static_cast<Eigen::Index>(f.curve.points.size()), 3);
    for (std::size_t k = 0; k < f.curve.points.size(); ++k) {
      faces[static_cast<Eigen::Index>(k)] = f.curve.points[k].face;
      bary.row(static_cast<Eigen::Index>(k)) = f.curve.points[k].bary.transpose();
    }
    placed.append(py::make_tuple(faces, bary));
  }
  finite_result(result_copy, "apply_features: the featured hierarchy");
  // Looked at as the command line's feature runs are (feature_folds.h): faces turned over.
  const int finest = result_copy.levels();
  const FoldReport folds = flipped_faces(hierarchy.mesh(finest), result_copy.mesh(finest).positions());
  out["flipped_faces"] = static_cast<int>(folds.flipped.size());
  out["folds"] = folds.describe();
  out["features"] = rows;
  out["placed"] = placed;
  out["within_tolerance"] = all_within;
  out["positions"] = py::cast(MatrixX3(result_copy.mesh(result_copy.levels()).positions()));
  out["hierarchy"] = py::cast(std::move(result_copy));
  return out;
}

}  // namespace

void bind_features(py::module_& m) {
  m.def("_apply_features", &apply_features, py::arg("hierarchy"), py::arg("features"), py::arg("profile_on"),
        py::arg("implementation"), "The features' C++ half; call fairshape.apply_features().");
}

}  // namespace fairshape::python
