// Region-limited re-evaluation of a FeaturedSurface between design steps:
// features are definitions re-applied to the surface (Khodakovsky & Schröder, "Fine level feature
// editing for subdivision surfaces", §2.6), so a step that adds, moves, edits or removes some of
// them changes the hierarchy only where they reach. What is recomputed, level by level from the
// coarsest changed one, is described in featured_surface.h (set_region_evaluation); why each part
// is enough:
//  - a feature moves only vertices within its reach of its curve (segment_offset's first test),
//    so its old and new neighbourhoods hold every vertex of its level it changes;
//  - a vertex of a finer level reads, through the subdivision stencil, the vertices of the level
//    above it, and through its local frame its own one-ring (MultiresSurface::synthesize_region_from);
//  - a feature of a finer level reads its level's positions and normals along its curve and on
//    the rays from it, all within its reach plus an edge: one whose neighbourhood holds no
//    recomputed vertex gives the same offsets as before;
//  - the finest level's visible targets displace each point by itself (displace_points), so
//    only the recomputed rows change; the limit fit separates into blocks (visible_profile.h).
#include "fairshape/feature/featured_surface.h"

#include <algorithm>

#include "fairshape/subdivision/limit.h"

namespace fairshape::feature {
namespace {

// The longest edge at vertex v.
double edge_at(const SurfaceMesh& m, int v) {
  double e = 0;
  m.for_each_outgoing(v, [&](int h) { e = std::max(e, (m.position(m.to_vertex(h)) - m.position(v)).norm()); });
  return e;
}

// The vertices of the level within `margin` + three of their own longest edges of the curve,
// walked from the corners of its faces (the region compute_perturbation's walk covers, widened
// by a one-ring of normals and the sag of finer levels and the limit against this one).
std::vector<int> near_curve(const TriangleSurface& s, const BaseCurve& c, double margin, std::vector<char>& seen) {
  const SurfaceMesh& m = s.mesh();
  std::vector<int> out, frontier, tested;
  for (const BaseSegment& seg : c.segments)
    for (int v : s.corners(seg.face))
      if (!seen[static_cast<std::size_t>(v)]) seen[static_cast<std::size_t>(v)] = 1, frontier.push_back(v);
  while (!frontier.empty()) {
    out.insert(out.end(), frontier.begin(), frontier.end());
    std::vector<int> next;
    for (int v : frontier)
      m.for_each_outgoing(v, [&](int h) {
        const int w = m.to_vertex(h);
        if (seen[static_cast<std::size_t>(w)]) return;
        seen[static_cast<std::size_t>(w)] = 1;
        tested.push_back(w);
        if (c.distance_to(s.vertex(w)) < margin + 3 * edge_at(m, w)) next.push_back(w);
      });
    frontier = std::move(next);
  }
  for (int v : out) seen[static_cast<std::size_t>(v)] = 0;
  for (int v : tested) seen[static_cast<std::size_t>(v)] = 0;  // `seen` is clear again for the next curve
  return out;
}

void append_unique(std::vector<int>& into, const std::vector<int>& add, std::vector<char>& mark) {
  for (int v : add)
    if (!mark[static_cast<std::size_t>(v)]) mark[static_cast<std::size_t>(v)] = 1, into.push_back(v);
}

}  // namespace

void FeaturedSurface::evaluate_region() {
  evaluated_ = false;  // until it has finished (a throw leaves the next evaluation whole)
  const int L = original_.levels();
  // Per level, the ids whose definition changed there (old level and new level).
  std::vector<std::set<int>> dirty(static_cast<std::size_t>(L + 1));
  std::map<int, int> old_level;
  for (const LevelOperator& op : operators_)
    for (int id : op.ids) old_level[id] = op.level;
  for (int id : pending_) {
    if (const auto it = old_level.find(id); it != old_level.end()) dirty[static_cast<std::size_t>(it->second)].insert(id);
    if (const auto it = features_.find(id); it != features_.end()) dirty[static_cast<std::size_t>(it->second.level)].insert(id);
  }
  // Margins: a feature's reach, the largest height (the finest points a feature displaces sit on
  // the surface the features before it raised, which differs from its level's by a fraction of
  // that) and three edges around the vertex (near_curve).
  double heights = 0;
  const auto tallest = [&](const FeatureParams& q) {
    heights = std::max({heights, std::abs(q.height), std::abs(q.height * q.end_height_ratio)});
  };
  for (const auto& [id, f] : features_) tallest(f.params);
  for (const LevelOperator& op : operators_)
    for (const BaseCurve& c : op.curves) tallest(c.params);

  report_ = {};
  report_.region = true;
  report_.vertices.assign(static_cast<std::size_t>(L + 1), {});
  std::vector<int> carried;  // vertices of the current level whose positions before its features changed
  int first = 0;
  while (first <= L && dirty[static_cast<std::size_t>(first)].empty()) ++first;
  for (int m = first; m <= L; ++m) {
    const auto lvl = static_cast<std::size_t>(m);
    if (carried.empty() && dirty[lvl].empty()) continue;  // nothing reaches this level
    const int nm = result_.mesh(m).n_vertices();
    std::vector<char> mark(static_cast<std::size_t>(nm), 0);
    for (int v : carried) mark[static_cast<std::size_t>(v)] = 1;
    const std::vector<int> ids_now = features_on(m);
    auto op_it = std::find_if(operators_.begin(), operators_.end(), [&](const LevelOperator& o) { return o.level == m; });
    std::vector<int> changed_here = carried;  // positions of level m to rewrite
    if (op_it == operators_.end() && !ids_now.empty()) {
      // The level's first feature: its surface as it is now (the features of coarser levels on it).
      LevelOperator op;
      op.level = m;
      op.mesh = std::make_shared<SurfaceMesh>(result_.mesh(m));
      op.surface = std::make_shared<TriangleSurface>(*op.mesh, loop_limit_normals(*op.mesh));
      op_it = operators_.insert(std::find_if(operators_.begin(), operators_.end(), [&](const LevelOperator& o) { return o.level > m; }),
                                std::move(op));
      const auto k = static_cast<std::size_t>(op_it - operators_.begin());
      if (!visible_.fine.empty()) {  // its targets start as the previous ones (it displaced nothing)
        MatrixX3 fine = visible_.fine[k], limit = visible_.limit[k];  // copies: inserted into their own vector
        visible_.fine.insert(visible_.fine.begin() + static_cast<std::ptrdiff_t>(k + 1), std::move(fine));
        visible_.limit.insert(visible_.limit.begin() + static_cast<std::ptrdiff_t>(k + 1), std::move(limit));
      }
    } else if (op_it != operators_.end()) {
      LevelOperator& op = *op_it;
      if (op.mesh.use_count() > 1) {  // shared with a copy of this surface: updated on its own
        op.mesh = std::make_shared<SurfaceMesh>(*op.mesh);
        op.surface = std::make_shared<TriangleSurface>(*op.surface);
        op.surface->rebind(*op.mesh);
      }
      // Features of this level the change below reaches (their rays and normals read it).
      std::set<int>& d = dirty[lvl];
      for (std::size_t j = 0; j < op.ids.size(); ++j) {
        if (d.count(op.ids[j])) continue;
        const BaseCurve& c = op.curves[j];
        for (int v : carried)
          if (const double margin = c.reach() + heights + 3 * std::max(edge_at(*op.mesh, v), edge_at(result_.mesh(m), v));
              c.distance_to(op.mesh->position(v)) < margin || c.distance_to(result_.mesh(m).position(v)) < margin) {
            d.insert(op.ids[j]);
            break;
          }
      }
      // Old neighbourhoods of the changed features, on the surface as it was.
      std::vector<char> seen(static_cast<std::size_t>(nm), 0);
      for (std::size_t j = 0; j < op.ids.size(); ++j)
        if (d.count(op.ids[j]))
          append_unique(changed_here, near_curve(*op.surface, op.curves[j], op.curves[j].reach() + heights, seen), mark);
      // The level's surface before its features, where it changed.
      for (int v : carried) op.mesh->positions().row(v) = result_.mesh(m).positions().row(v);
      op.surface->refresh(carried);
    }
    if (op_it != operators_.end()) {
      LevelOperator& op = *op_it;
      const std::set<int>& d = dirty[lvl];
      std::map<int, BaseCurve> kept;
      for (std::size_t j = 0; j < op.ids.size(); ++j)
        if (!d.count(op.ids[j])) kept.emplace(op.ids[j], std::move(op.curves[j]));
      op.ids = ids_now;
      op.curves.clear();
      std::vector<char> seen(static_cast<std::size_t>(nm), 0);
      for (int id : ids_now) {
        if (const auto it = kept.find(id); it != kept.end()) {
          op.curves.push_back(std::move(it->second));
          continue;
        }
        op.curves.push_back(build_base_curve(*op.surface, features_.at(id)));
        const BaseCurve& c = op.curves.back();
        append_unique(changed_here, near_curve(*op.surface, c, c.reach() + heights, seen), mark);
      }
      // The level's perturbation at the changed vertices, against all its features.
      const LevelPerturbation now = perturb_vertices(*op.surface, op.curves, changed_here, backend_);
      LevelPerturbation& all = perturbations_[lvl];
      std::vector<char> redone(static_cast<std::size_t>(nm), 0);
      for (int v : changed_here) redone[static_cast<std::size_t>(v)] = 1;
      std::vector<std::pair<int, Vec3>> merged;
      for (std::size_t i = 0; i < all.vertices.size(); ++i)
        if (!redone[static_cast<std::size_t>(all.vertices[i])])
          merged.emplace_back(all.vertices[i], all.displacement.row(static_cast<Eigen::Index>(i)).transpose());
      for (std::size_t i = 0; i < now.vertices.size(); ++i)
        merged.emplace_back(now.vertices[i], now.displacement.row(static_cast<Eigen::Index>(i)).transpose());
      std::sort(merged.begin(), merged.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      all.vertices.resize(merged.size());
      all.displacement.resize(static_cast<Eigen::Index>(merged.size()), 3);
      for (std::size_t i = 0; i < merged.size(); ++i) {
        all.vertices[i] = merged[i].first;
        all.displacement.row(static_cast<Eigen::Index>(i)) = merged[i].second.transpose();
      }
      std::vector<int> slot(static_cast<std::size_t>(nm), -1);
      MatrixX3 level_rows(static_cast<Eigen::Index>(changed_here.size()), 3);
      for (std::size_t i = 0; i < changed_here.size(); ++i) {
        slot[static_cast<std::size_t>(changed_here[i])] = static_cast<int>(i);
        level_rows.row(static_cast<Eigen::Index>(i)) = op.mesh->positions().row(changed_here[i]);
      }
      for (std::size_t i = 0; i < now.vertices.size(); ++i)
        level_rows.row(slot[static_cast<std::size_t>(now.vertices[i])]) += now.displacement.row(static_cast<Eigen::Index>(i));
      result_.set_level_rows(m, changed_here, level_rows);
      for (std::size_t j = 0; j < op.ids.size(); ++j) base_curves_[op.ids[j]] = op.curves[j];
      if (ids_now.empty()) {  // the level's last feature removed
        const auto k = static_cast<std::size_t>(op_it - operators_.begin());
        if (!visible_.fine.empty()) {
          visible_.fine.erase(visible_.fine.begin() + static_cast<std::ptrdiff_t>(k + 1));
          visible_.limit.erase(visible_.limit.begin() + static_cast<std::ptrdiff_t>(k + 1));
        }
        operators_.erase(op_it);
      }
    }
    report_.vertices[lvl] = changed_here;
    if (m < L) carried = result_.synthesize_region_from(m, changed_here, DetailSpace::Local, m + 1)[lvl + 1];
  }
  for (auto it = base_curves_.begin(); it != base_curves_.end();)
    it = features_.count(it->first) ? std::next(it) : base_curves_.erase(it);

  // The finest level's visible targets on the recomputed rows, then the limit fit's blocks there.
  std::vector<int>& finest_rows = report_.vertices[static_cast<std::size_t>(L)];
  const SurfaceMesh& finest_original = original_.mesh(L);
  if (operators_.empty()) {
    visible_.fine.clear(), visible_.limit.clear();  // the limit matrix kept: the fit below reads it
  } else if (visible_.fine.empty()) {
    visible_ = compose_visible_targets(finest_original, original_.options(), operators_, backend_);
  } else if (!finest_rows.empty()) {
    const auto rows = static_cast<Eigen::Index>(finest_rows.size());
    MatrixX3 fine(rows, 3), limit(rows, 3);
    for (Eigen::Index i = 0; i < rows; ++i) fine.row(i) = visible_.fine[0].row(finest_rows[static_cast<std::size_t>(i)]),
                                            limit.row(i) = visible_.limit[0].row(finest_rows[static_cast<std::size_t>(i)]);
    for (std::size_t k = 0; k < operators_.size(); ++k) {
      fine += displace_points(*operators_[k].surface, operators_[k].curves, fine, backend_).dense(static_cast<int>(rows));
      limit += displace_points(*operators_[k].surface, operators_[k].curves, limit, backend_).dense(static_cast<int>(rows));
      for (Eigen::Index i = 0; i < rows; ++i) {
        visible_.fine[k + 1].row(finest_rows[static_cast<std::size_t>(i)]) = fine.row(i);
        visible_.limit[k + 1].row(finest_rows[static_cast<std::size_t>(i)]) = limit.row(i);
      }
    }
  }
  const auto rows_of = [&](const MatrixX3& from) {
    MatrixX3 out(static_cast<Eigen::Index>(finest_rows.size()), 3);
    for (std::size_t i = 0; i < finest_rows.size(); ++i) out.row(static_cast<Eigen::Index>(i)) = from.row(finest_rows[i]);
    return out;
  };
  if (target_ == ProfileTarget::Finest)
    result_.set_level_rows(L, finest_rows, rows_of(operators_.empty() ? finest_original.positions() : visible_.fine.back()));
  if (target_ == ProfileTarget::Limit) {
    const int n = finest_original.n_vertices();
    if (limit_fit_.rows() != n) limit_fit_ = finest_original.positions(), limit_moving_.assign(static_cast<std::size_t>(n), 0);
    if (visible_.limit_by_rows.rows() != n) {  // no feature before and none now: nothing kept to read
      visible_.limit_matrix = limit_matrix(finest_original, original_.options());
      visible_.limit_by_rows = visible_.limit_matrix;
    }
    const auto moved = [&](int v) -> Vec3 {
      return operators_.empty() ? Vec3::Zero() : Vec3((visible_.limit.back().row(v) - visible_.limit.front().row(v)).transpose());
    };
    const std::vector<int> rewritten = refit_control_points_for_limit(finest_original, visible_.limit_by_rows,
                                                                      finest_original.positions(), moved, limit_moving_,
                                                                      finest_rows, limit_fit_);
    for (int v : finest_rows) limit_moving_[static_cast<std::size_t>(v)] = moved(v).squaredNorm() > 0;
    std::vector<char> mark(static_cast<std::size_t>(n), 0);
    for (int v : finest_rows) mark[static_cast<std::size_t>(v)] = 1;
    for (int v : rewritten)
      if (!mark[static_cast<std::size_t>(v)]) mark[static_cast<std::size_t>(v)] = 1, finest_rows.push_back(v);
    result_.set_level_rows(L, finest_rows, rows_of(limit_fit_));
  }
  for (const std::vector<int>& r : report_.vertices) report_.vertices_recomputed += static_cast<long long>(r.size());
  pending_.clear();
  evaluated_ = true;
  dirty_ = false;
}

}  // namespace fairshape::feature
