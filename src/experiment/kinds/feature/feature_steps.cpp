#include "fairshape/experiment/kinds/feature/feature_steps.h"

#include <algorithm>
#include <filesystem>
#include <utility>

#include "fairshape/core/error.h"
#include "fairshape/core/timer.h"
#include "fairshape/experiment/metric_format.h"
#include "fairshape/io/vtk_io.h"

namespace fairshape {
namespace fs = std::filesystem;

const TableSchema& feature_step_table() {
  static const TableSchema t{"steps",
                             {"step", "features", "added", "moved", "changed", "removed", "vertices_changed", "evaluation",
                              "apply_s", "vertices_recomputed", "max_change"}};
  return t;
}

int feature_step_count(const FeatureRunSpec& spec) {
  int last = 0;
  for (const FeatureSpec& f : spec.features) {
    last = std::max({last, f.step, f.until});
    for (const PointMove& m : f.moves) last = std::max(last, m.step);
    for (const FeatureChange& c : f.changes) last = std::max(last, c.step);
  }
  return last + 1;
}

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : " ") + n;
  return out;
}

// The feature as it is at `step`: its world points moved by every move so far, the parameters
// of its latest change.
FeatureSpec at_step(const FeatureSpec& f, int step) {
  FeatureSpec g = f;
  Vec3 offset = Vec3::Zero();
  for (const PointMove& m : f.moves)
    if (m.step <= step) offset += m.by;
  for (Vec3& p : g.world_points) p += offset;
  for (const FeatureChange& c : f.changes)
    if (c.step <= step) g.curve.params = c.params;
  return g;
}

}  // namespace

double run_feature_steps(FeatureRunSpec& spec, feature::FeaturedSurface& surface, const RunOutputs& out) {
  const int steps = feature_step_count(spec);
  MatrixX3 before;
  double apply_s = 0;
  for (int step = 0; step < steps; ++step) {
    std::vector<std::string> added, moved, changed, removed;
    for (FeatureSpec& f : spec.features) {
      const std::string& name = f.curve.name;
      if (step > 0 && f.until == step && f.id >= 0) {
        surface.remove(f.id);
        f.id = -1;
        removed.push_back(name);
        continue;
      }
      const bool moves_now = std::any_of(f.moves.begin(), f.moves.end(), [&](const PointMove& m) { return m.step == step; });
      const bool changes_now = std::any_of(f.changes.begin(), f.changes.end(), [&](const FeatureChange& c) { return c.step == step; });
      const bool adds_now = step > 0 && f.step == step;
      if (!adds_now && !(f.id >= 0 && (moves_now || changes_now))) continue;
      FeatureSpec now = at_step(f, step);
      try {
        place_feature(spec, surface, now);
      } catch (const InvalidInput& e) {
        throw InvalidInput("step " + std::to_string(step) + ": " + e.what());
      }
      if (adds_now) {
        f.id = surface.add(now.curve);
        added.push_back(name);
      } else {
        surface.replace(f.id, now.curve);
        (moves_now ? moved : changed).push_back(name);
      }
    }
    const Timer timer;
    const MultiresSurface* evaluated = nullptr;
    try {
      evaluated = &surface.result();
    } catch (const InvalidInput& e) {
      throw InvalidInput("step " + std::to_string(step) + ": " + e.what());
    }
    const MultiresSurface& result = *evaluated;
    apply_s = timer.seconds();
    const MatrixX3& now = result.mesh(spec.levels).positions();
    const Eigen::VectorXd change = before.size() ? Eigen::VectorXd((now - before).rowwise().norm()) : Eigen::VectorXd();
    const double diag = (now.colwise().maxCoeff() - now.colwise().minCoeff()).norm();
    const int active = static_cast<int>(std::count_if(spec.features.begin(), spec.features.end(), [](const FeatureSpec& f) { return f.id >= 0; }));
    const feature::EvaluationReport& how = surface.last_evaluation();
    out.add_row("steps", {std::to_string(step), std::to_string(active), joined(added), joined(moved), joined(changed), joined(removed),
                          change.size() ? std::to_string((change.array() > 1e-12 * diag).count()) : "",
                          how.region ? "region" : "whole", num(apply_s), std::to_string(how.vertices_recomputed),
                          change.size() ? num(change.maxCoeff()) : ""});
    before = now;
    if (spec.vtk_every_step && steps > 1) {
      SurfaceMesh m = result.mesh(spec.levels);
      m.vertex_data["displacement"] = m.positions() - std::as_const(surface).original().mesh(spec.levels).positions();
      write_vtp(m, (fs::path(out.dir) / "vtk" / (out.run_id + "_step" + std::to_string(step) + ".vtp")).string());
    }
  }
  return apply_s;
}

}  // namespace fairshape
