#include "fairshape/experiment/kinds/feature/feature_steps.h"

#include <algorithm>
#include <filesystem>
#include <utility>

#include "fairshape/core/error.h"
#include "fairshape/experiment/kinds/feature/feature_width_check.h"
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

double run_feature_steps(FeatureRunSpec& spec, FeatureSession& session, const RunOutputs& out) {
  const int steps = feature_step_count(spec);
  double apply_s = 0;
  for (int step = 0; step < steps; ++step) {
    std::vector<std::string> added, moved, changed, removed;
    std::vector<FeatureEdit> edits;
    std::vector<FeatureSpec*> adding, placing;  // in the order of their edits
    for (FeatureSpec& f : spec.features) {
      const std::string& name = f.curve.name;
      if (step > 0 && f.until == step && f.id >= 0) {
        edits.push_back(FeatureEdit::remove(f.id));
        f.id = -1;
        removed.push_back(name);
        continue;
      }
      const bool moves_now = std::any_of(f.moves.begin(), f.moves.end(), [&](const PointMove& m) { return m.step == step; });
      const bool changes_now = std::any_of(f.changes.begin(), f.changes.end(), [&](const FeatureChange& c) { return c.step == step; });
      const bool adds_now = step > 0 && f.step == step;
      if (!adds_now && !(f.id >= 0 && (moves_now || changes_now))) continue;
      FeatureSpec now = at_step(f, step);
      if (adds_now) {
        edits.push_back(FeatureEdit::add(now));
        adding.push_back(&f), placing.push_back(&f);
        added.push_back(name);
      } else if (moves_now) {
        edits.push_back(FeatureEdit::replace(f.id, now));
        placing.push_back(&f);
        moved.push_back(name);
      } else {
        edits.push_back(FeatureEdit::set_params(f.id, now.curve.params));
        changed.push_back(name);
      }
    }
    FeatureStep r;
    try {
      r = session.apply(std::move(edits));
    } catch (const InvalidInput& e) {
      throw InvalidInput("step " + std::to_string(step) + ": " + e.what());
    }
    for (std::size_t k = 0; k < adding.size(); ++k) adding[k]->id = r.added[r.added.size() - adding.size() + k];
    // The widths the placed features take in later `changes` (their own: placing checked them).
    for (FeatureSpec* f : placing) {
      FeatureSpec g = *f;
      g.curve = session.features().at(f->id);
      check_feature_width(g, session.original().mesh(0), spec.levels);
    }
    apply_s = r.solve_s;
    const int active = static_cast<int>(session.features().size());
    out.add_row("steps", {std::to_string(step), std::to_string(active), joined(added), joined(moved), joined(changed), joined(removed),
                          r.vertices_changed >= 0 ? std::to_string(r.vertices_changed) : "",
                          r.evaluation.region ? "region" : "whole", num(apply_s), std::to_string(r.evaluation.vertices_recomputed),
                          r.vertices_changed >= 0 ? num(r.max_change) : ""});
    if (spec.vtk_every_step && steps > 1) {
      SurfaceMesh m = r.surface->mesh(spec.levels);
      m.vertex_data["displacement"] = m.positions() - session.original().mesh(spec.levels).positions();
      write_vtp(m, (fs::path(out.dir) / "vtk" / (out.run_id + "_step" + std::to_string(step) + ".vtp")).string());
    }
  }
  return apply_s;
}

}  // namespace fairshape
