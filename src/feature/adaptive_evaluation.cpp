#include "fairshape/feature/adaptive_evaluation.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <unordered_set>

#include "fairshape/feature/adaptive_mesh.h"
#include "fairshape/feature/perturbation.h"
#include "fairshape/feature/profile_measure.h"
#include "fairshape/feature/sparse_visible_profile.h"
#include "fairshape/feature/triangle_surface.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape::feature {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

// The same parameter point one level coarser: the inverse of level_attachment's child_point
// (Loop's 1:4 split is a midpoint split of the parameter triangle; children as child_faces).
SurfacePoint parent_point(const SurfacePoint& p) {
  const Vec3& b = p.bary;
  Vec3 q;
  switch (p.face & 3) {
    case 0: q = {b[0] + 0.5 * (b[1] + b[2]), 0.5 * b[1], 0.5 * b[2]}; break;  // (a, ab, ca)
    case 1: q = {0.5 * b[0], 0.5 * b[0] + b[1] + 0.5 * b[2], 0.5 * b[2]}; break;  // (ab, b, bc)
    case 2: q = {0.5 * b[0], 0.5 * b[1], 0.5 * (b[0] + b[1]) + b[2]}; break;  // (ca, bc, c)
    default: q = {0.5 * (b[0] + b[2]), 0.5 * (b[0] + b[1]), 0.5 * (b[1] + b[2])};  // (ab, bc, ca)
  }
  return {p.face >> 2, q};
}

double segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double l2 = ab.squaredNorm();
  const double t = l2 > 0 ? std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Segments in a uniform grid, for "is this point within d of the curve" (d ≤ the cell size).
class SegmentGrid {
 public:
  SegmentGrid(std::vector<std::pair<Vec3, Vec3>> segments, double cell) : segments_(std::move(segments)), cell_(cell) {
    for (int s = 0; s < static_cast<int>(segments_.size()); ++s) {
      const auto& [a, b] = segments_[s];
      const Eigen::Array3i lo = key(a.cwiseMin(b)) - 1, hi = key(a.cwiseMax(b)) + 1;
      for (int x = lo[0]; x <= hi[0]; ++x)
        for (int y = lo[1]; y <= hi[1]; ++y)
          for (int z = lo[2]; z <= hi[2]; ++z) cells_[hash(x, y, z)].push_back(s);
    }
  }
  double distance(const Vec3& p) const {
    if (cells_.empty() || !p.allFinite()) return std::numeric_limits<double>::infinity();
    const Eigen::Array3i k = key(p);
    const auto it = cells_.find(hash(k[0], k[1], k[2]));
    double d = std::numeric_limits<double>::infinity();
    if (it != cells_.end())
      for (int s : it->second) d = std::min(d, segment_distance(p, segments_[s].first, segments_[s].second));
    return d;  // exact when below cell_, else at least cell_ (or infinity)
  }
  double cell() const { return cell_; }

 private:
  // Clamped before the cast, which is undefined beyond int's range (far cells share a key: the
  // distance test below stays exact).
  Eigen::Array3i key(const Vec3& p) const {
    constexpr double kLimit = 1 << 20;
    return (p.array() / cell_).floor().max(-kLimit).min(kLimit).cast<int>();
  }
  static std::int64_t hash(int x, int y, int z) {
    return (std::int64_t(x) * 73856093) ^ (std::int64_t(y) * 19349663) ^ (std::int64_t(z) * 83492791);
  }
  std::vector<std::pair<Vec3, Vec3>> segments_;
  double cell_;
  std::unordered_map<std::int64_t, std::vector<int>> cells_;
};

// Angle between the plane of the triangle (a, b, o) and the line from `mid` to o (Figure 13).
double midpoint_angle(const Vec3& a, const Vec3& b, const Vec3& o, const Vec3& mid) {
  const Vec3 n = (b - a).cross(o - a).normalized();
  const Vec3 line = mid - o;
  return std::asin(std::min(1.0, std::abs(line.dot(n)) / line.norm()));
}

// One Loop step of positions X on the patch mesh (rows as subdivide_positions_matrix_free
// numbers the children).
MatrixX3 loop_step(const SurfaceMesh& patch, const SubdivisionOptions& opt, const MatrixX3& X) {
#if FAIRSHAPE_WITH_TBB
  MatrixX3 Y;
  subdivide_positions_matrix_free(patch, opt, X, Y);
  return Y;
#else
  SurfaceMesh m = patch;
  m.positions() = X;
  return subdivide_once(m, opt, Backend::Reference).positions();
#endif
}

class Evaluator {
 public:
  Evaluator(const SurfaceMesh& base, const SubdivisionOptions& opt, int levels, const std::vector<FeatureCurve>& features,
            const AdaptiveEvaluationOptions& options)
      : base_(base), opt_(opt), L_(levels), features_(features), options_(options),
        wants_(static_cast<std::size_t>(levels + 1)) {}

  // Passes until every mark is refinable. A pass that asked for new faces is re-run from the
  // lowest level that got one: the levels up to it keep their faces and positions (a level's
  // faces depend only on the marks of the levels above it).
  AdaptiveEvaluation run() {
    out_.levels.push_back(sparse_base_level(base_));
    out_.levels[0].original = out_.levels[0].positions;
    for (const FeatureCurve& c : features_) {
      out_.feature_level.push_back(c.level);
      heights_ += std::max(std::abs(c.params.height), std::abs(c.params.height * c.params.end_height_ratio));
    }
    curves_.assign(features_.size(), {});
    applied_.assign(static_cast<std::size_t>(L_ + 1), 0);
    moved_.assign(static_cast<std::size_t>(L_ + 1), 0);
    for (int pass = 1, start = 0;; ++pass) {
      out_.passes = pass;
      out_.levels.resize(static_cast<std::size_t>(start + 1));
      out_.split.resize(static_cast<std::size_t>(start));
      for (int k = start + 1; k <= L_; ++k) applied_[k] = 0, moved_[k] = 0;
      for (std::size_t i = 0; i < features_.size(); ++i)
        if (features_[i].level > start) curves_[i] = {};
      lowest_new_ = L_ + 1;
      if (evaluate_pass(start)) {
        for (int m : moved_) out_.vertices_moved += m;
        out_.curves = curves_;
        build_output();
        return std::move(out_);
      }
      if (lowest_new_ > L_)  // nothing new asked for: the next pass would fail the same way
        throw std::logic_error("adaptive evaluation: a needed face could not be asked for (pass " +
                               std::to_string(pass) + ")");
      start = lowest_new_;
    }
  }

 private:
  // One evaluation of levels start..L; false when a needed face was missing (its parents are
  // then marked in wants_ and the caller runs again).
  bool evaluate_pass(int start) {
    for (int k = start; k <= L_; ++k) {
      if (!applied_[k]) {
        if (!apply_features(k)) return false;
        applied_[k] = 1;
      }
      if (k == L_) {
        if (!finish_finest()) return false;
        out_.split.emplace_back(out_.levels[k].face.size(), 0);
        return true;
      }
      SparseLevel& S = out_.levels[k];
      if (S.face.empty()) {  // nothing reached this level: nothing below it either
        out_.split.emplace_back();
        const MatrixX3 none;
        out_.levels.push_back(refine_sparse(S, SparsePatch{}, none, {}, &none));
        continue;
      }
      const SparsePatch patch = make_patch(S);
      const MatrixX3 Y = loop_step(patch.mesh, opt_, patch.mesh.positions());
      // The same step without the features (the finest targets displace it): the positions
      // themselves until a feature has moved them.
      MatrixX3 Y0;
      const bool featured = !(S.original.array() == S.positions.array()).all();
      if (featured) {
        MatrixX3 X0(patch.mesh.n_vertices(), 3);
        for (int v = 0; v < patch.mesh.n_vertices(); ++v) X0.row(v) = S.original.row(patch.local[static_cast<std::size_t>(v)]);
        Y0 = loop_step(patch.mesh, opt_, X0);
      }
      std::vector<char> split(S.face.size(), 0);
      bool missing = false;
      const auto want = [&](int f) {
        if (split[f]) return;
        if (S.refinable(f)) split[f] = 1;
        else need_refinable(k, S.face[f]), missing = true;
      };
      const std::vector<UniformId> wanted(wants_[k].begin(), wants_[k].end());  // want() may add to it
      for (UniformId id : wanted) {
        const int f = S.face_of(id);
        if (f >= 0) want(f);
        else need_refinable(k, id), missing = true;
      }
      if (k < options_.from_level)
        for (int f = 0; f < S.n_local_faces(); ++f) want(f);
      const std::vector<double> angle = mark_supports(k, want, missing);
      if (featured) mark_changed(k, want, [&](int f) { if (S.refinable(f)) split[f] = 1; }, missing);
      if (missing) return false;
      mark_unflat(S, patch, Y, angle, want);
      for (bool changed = true; changed;) {  // balance: a leaf between three split faces is split
        changed = false;
        for (int f = 0; f < S.n_local_faces(); ++f) {
          if (split[f]) continue;
          int n = 0;
          for (int i = 0; i < 3; ++i) {
            const int g = S.across(f, i);
            n += g >= 0 && split[g];
          }
          if (n == 3) {
            want(f);  // refinable: each corner is shared by two split faces (so complete)
            changed = changed || split[f];
          }
        }
      }
      if (missing) return false;
      std::vector<int> refine;
      for (int f = 0; f < S.n_local_faces(); ++f)
        if (split[f]) refine.push_back(f);
      out_.levels.push_back(refine_sparse(S, patch, Y, refine, featured ? &Y0 : &Y));
      out_.split.push_back(std::move(split));
    }
    return true;
  }

  // Marks face `id` of level k for quadrisection; whether it is new (then the next pass starts
  // at this level or above).
  bool ask(int k, UniformId id) {
    if (!wants_[k].insert(id).second) return false;
    lowest_new_ = std::min(lowest_new_, k);
    return true;
  }

  // Face `id` of level k must be refinable on the next pass: it is wanted there, and its parent
  // and the faces around the parent's corners are wanted on level k − 1 (their children hold
  // the one-rings of its corners); a parent that is itself missing or not refinable is asked
  // for one level up. Returns whether anything new was asked for.
  bool need_refinable(int k, UniformId id) {
    bool added = ask(k, id);
    if (k == 0) return added;
    const UniformId P = id >> 2;
    const SparseLevel& C = out_.levels[k - 1];
    const int p = C.face_of(P);
    if (p < 0 || !C.refinable(p)) return need_refinable(k - 1, P) || added;
    for (int v : C.corners[p]) C.for_faces_around(v, [&](int g) { added |= ask(k - 1, C.face[g]); });
    return added;
  }
  // Every face around local vertex v of level k refinable next pass (so v's ring is complete).
  bool need_ring(int k, int v) {
    const SparseLevel& S = out_.levels[k];
    bool added = false;
    S.for_faces_around(v, [&](int f) { added |= need_refinable(k, S.face[f]); });
    return added;
  }

  // A feature drawn on level l changes the finer levels through the subdivision stencils: a
  // vertex of level k + 1 changes when its stencil reads a changed vertex of level k (its parent
  // or one of the parent's one-ring, the edge's ends or the two opposite corners), so the
  // changed vertices of level k + 1 lie in the children of the faces around the changed ones of
  // level k, and their one-rings in the children of the faces with a corner within one ring of
  // them: those are quadrisected (required: the changed region of level k + 1 is computed with
  // its one-rings — what a feature drawn below the finest level touches is computed down to the
  // finest, nothing far from it). Rings counted on the level adapt to its faces' sizes, however
  // irregular. Two rings more are quadrisected where they are refinable already (so that the
  // next level's required faces find their neighbours: each level's ring is half the last
  // one's), not asked for: a missing one costs a repeated pass, never a wrong position.
  template <class Want, class Take>
  void mark_changed(int k, const Want& want, const Take& take_if_refinable, bool& missing) {
    constexpr int kRequired = 2, kRings = 4;  // vertex rings around the changed ones: faces around them
    const SparseLevel& S = out_.levels[k];
    std::vector<char> ring(S.vertex.size(), 0);  // 1 + rings from the changed vertices; 0: farther
    std::vector<int> layer;
    for (int v = 0; v < S.n_local_vertices(); ++v)
      if (!(S.positions.row(v).array() == S.original.row(v).array()).all()) ring[v] = 1, layer.push_back(v);
    for (int r = 1; r <= kRings && !layer.empty(); ++r) {
      std::vector<int> next;
      for (int v : layer) {
        const bool required = r <= kRequired;
        if (!S.complete[v]) {
          if (required) need_ring(k, v), missing = true;  // its faces are not all known yet
          continue;
        }
        S.for_faces_around(v, [&](int f) {
          if (required) want(f);
          else take_if_refinable(f);
          if (r == kRings) return;
          for (int w : S.corners[f])
            if (!ring[w]) ring[w] = static_cast<char>(r + 1), next.push_back(w);
        });
      }
      layer = std::move(next);
    }
  }

  // The finest level as options_.target asks (sparse_visible_profile.h): the paper's result
  // (DrawnLevel), the composed displacements (Finest), or the least-squares fit of the limit
  // points (Limit, visible_profile.h). First every vertex that they and the measure read must be
  // complete: the present vertices within the measured reach of a curve (profile_measure.h:
  // its reach plus its edge, plus the features' heights — the targets are displaced by coarser
  // features — and two edges around the vertex — a limit point lies in its one-ring's hull),
  // and for the fit the moving vertices and three rings (two of unknowns, one of rows, each row's
  // limit stencil its one-ring). Where one is not, its ring is asked for (false: run again).
  bool finish_finest() {
    if (!options_.apply_features) return true;
    bool any = false;
    for (const BaseCurve& c : curves_) any = any || !c.segments.empty();
    if (!any) return true;
    SparseLevel& S = out_.levels[L_];
    const SparseVisibleTargets t =
        sparse_visible_targets(out_.levels, out_.unperturbed, curves_, out_.feature_level, opt_, options_.backend);
    const SurfaceMesh& mesh = t.finest.mesh;
    const int n = mesh.n_vertices();
    bool missing = false;
    const auto need = [&](int pv) {
      need_ring(L_, t.finest.local[static_cast<std::size_t>(pv)]);
      missing = true;
    };
    std::vector<std::pair<const BaseCurve*, double>> reach;
    for (const LevelOperator& op : t.operators)
      for (const BaseCurve& c : op.curves) reach.emplace_back(&c, measured_reach(*op.surface, c) + heights_);
    for (int v = 0; v < n; ++v) {
      if (t.complete[static_cast<std::size_t>(v)]) continue;
      double edge = 0;
      mesh.for_each_outgoing(v, [&](int h) { edge = std::max(edge, (mesh.position(mesh.to_vertex(h)) - mesh.position(v)).norm()); });
      for (const auto& [c, r] : reach)
        if (c->distance_to(mesh.position(v)) < r + 2 * edge) { need(v); break; }
    }
    if (missing) return false;
    if (options_.target == ProfileTarget::DrawnLevel) return true;
    MatrixX3 X;
    if (options_.target == ProfileTarget::Finest) {
      X = t.targets.fine.back();
    } else {
      const MatrixX3 moved = t.targets.limit.back() - t.targets.limit.front();
      std::vector<char> seen(static_cast<std::size_t>(n), 0);
      std::vector<int> layer;
      for (int v = 0; v < n; ++v)
        if (moved.row(v).squaredNorm() > 0) seen[static_cast<std::size_t>(v)] = 1, layer.push_back(v);
      for (int ring = 0; ring <= 3; ++ring) {
        std::vector<int> next;
        for (int v : layer) {
          if (!t.complete[static_cast<std::size_t>(v)]) { need(v); continue; }
          if (ring < 3)
            mesh.for_each_outgoing(v, [&](int h) {
              const int w = mesh.to_vertex(h);
              if (!seen[static_cast<std::size_t>(w)]) seen[static_cast<std::size_t>(w)] = 1, next.push_back(w);
            });
        }
        layer = std::move(next);
      }
      if (missing) return false;
      X = control_points_for_limit(mesh, t.targets.limit_matrix, mesh.positions(), moved);
    }
    for (int v = 0; v < n; ++v) S.positions.row(t.finest.local[static_cast<std::size_t>(v)]) = X.row(v);
    return true;
  }

  // Feature i's measured reach on its level (profile_measure.h's measured_reach, its faces'
  // edges read on the level as it is now: a margin, not a measure).
  double measured_reach_on(std::size_t i) const {
    const SparseLevel& A = out_.levels[static_cast<std::size_t>(features_[i].level)];
    double edge = 0;
    for (const BaseSegment& seg : curves_[i].segments) {
      const auto& c = A.corners[static_cast<std::size_t>(seg.face)];
      for (int j = 0; j < 3; ++j) edge = std::max(edge, (A.positions.row(c[j]) - A.positions.row(c[(j + 1) % 3])).norm());
    }
    return curves_[i].reach() + edge;
  }

  double support_radius(const FeatureCurve& c) const {
    return std::max(c.params.radius, c.params.right_radius()) + std::abs(c.params.height);
  }

  // The features' curves as segments on level k: finer features' control polygons carried up
  // to k (to mark their support for refinement), and the base curves of features drawn on k or
  // coarser (where their flatness threshold applies). Marks the first kind through `want`
  // and returns each face's flatness threshold in radians (0: none).
  template <class Want>
  std::vector<double> mark_supports(int k, const Want& want, bool& missing) {
    SparseLevel& S = out_.levels[k];
    std::vector<double> angle(S.face.size(), options_.surface_angle_deg * kDegree);
    std::vector<double> longest(S.face.size()), spread(S.face.size());
    std::vector<Vec3> centre(S.face.size());
    double h_max = 0;
    for (int f = 0; f < S.n_local_faces(); ++f) {
      const auto& c = S.corners[f];
      const Vec3 a = S.positions.row(c[0]).transpose(), b = S.positions.row(c[1]).transpose(),
                 d = S.positions.row(c[2]).transpose();
      centre[f] = (a + b + d) / 3;
      longest[f] = std::max({(a - b).norm(), (b - d).norm(), (d - a).norm()});
      spread[f] = std::max({(a - centre[f]).norm(), (b - centre[f]).norm(), (d - centre[f]).norm()});
      h_max = std::max(h_max, longest[f]);
    }
    for (std::size_t i = 0; i < features_.size(); ++i) {
      const FeatureCurve& fc = features_[i];
      std::vector<std::pair<Vec3, Vec3>> segments;
      const bool finer = fc.level > k;
      if (finer) {
        FeatureCurve up = fc;  // the control polygon carried up to level k, on local faces
        up.level = k;
        for (SurfacePoint& p : up.points) {
          for (int j = fc.level; j > k; --j) p = parent_point(p);
          const int f = S.face_of(p.face);
          if (f < 0) { need_refinable(k, p.face); missing = true; }
          p.face = f;
        }
        if (missing) continue;
        segments = coarse_segments(k, up);
      } else {
        for (const BaseSegment& s : curves_[i].segments) segments.emplace_back(s.a, s.b);
      }
      if (segments.empty()) continue;
      // A finer feature's support, three of the face's edges around its reach; five for one drawn
      // below the finest level (its level refines the measured reach and three of its own edges
      // from there on, below).
      const double margin_edges = finer ? (fc.level < L_ ? 5.0 : 3.0) : 2.0;
      const double reach = support_radius(fc);
      // Applied on a level l < L: the finest level must hold, with their one-rings, the
      // vertices the measure and the targets read (finish_finest: within the measured reach,
      // profile_measure.h, plus the heights): refined towards it on every level from l on, with
      // three of the face's edges as for a finer feature's support (mark_changed adds what the
      // stencils change, which this usually covers).
      const double measured = !finer && k < L_ && options_.apply_features ? measured_reach_on(i) + heights_ : 0.0;
      const SegmentGrid grid(std::move(segments), std::max(reach, measured) + margin_edges * h_max + 2 * h_max);
      const double feature_angle = fc.params.flatness_angle_deg * kDegree;
      for (int f = 0; f < S.n_local_faces(); ++f) {
        const double d = grid.distance(centre[f]) - spread[f];
        if (measured > 0 && d <= measured + 3 * longest[f]) want(f);
        if (d > reach + margin_edges * longest[f]) continue;
        if (finer) want(f);
        else angle[f] = angle[f] > 0 ? std::min(angle[f], feature_angle) : feature_angle;
      }
    }
    return angle;
  }

  // A finer feature's curve on level k: walked on the level's surface like the feature's own
  // base curve (it follows the surface, where the chord between its points may cut through
  // it); where the walk fails on this coarse level, the chords between the points.
  std::vector<std::pair<Vec3, Vec3>> coarse_segments(int k, const FeatureCurve& up) {
    std::vector<std::pair<Vec3, Vec3>> segments;
    const SparseLevel& S = out_.levels[k];
    try {
      const SparsePatch patch = make_patch(S);
      const TriangleSurface surface(patch.mesh, loop_limit_normals(patch.mesh));
      for (const BaseSegment& s : build_base_curve(surface, up).segments) segments.emplace_back(s.a, s.b);
      return segments;
    } catch (const InvalidInput&) {
      segments.clear();
    }
    std::vector<Vec3> points;
    for (const SurfacePoint& p : up.points) {
      const auto& c = S.corners[p.face];
      points.push_back(p.bary[0] * S.positions.row(c[0]).transpose() + p.bary[1] * S.positions.row(c[1]).transpose() +
                       p.bary[2] * S.positions.row(c[2]).transpose());
    }
    for (std::size_t j = 0; j + 1 < points.size(); ++j) segments.emplace_back(points[j], points[j + 1]);
    if (up.closed && points.size() > 2) segments.emplace_back(points.back(), points.front());
    if (points.size() == 1) segments.emplace_back(points[0], points[0]);
    return segments;
  }

  // Figure 13: a face whose edge midpoint (level k + 1) leaves the plane of a triangle sharing
  // the edge by more than the face's threshold. Midpoints are exact where both faces of the
  // edge are present; an edge missing its other face is judged on this face alone.
  template <class Want>
  void mark_unflat(const SparseLevel& S, const SparsePatch& patch, const MatrixX3& Y, const std::vector<double>& angle,
                   const Want& want) const {
    const int patch_nv = patch.mesh.n_vertices();
    const auto pos = [&](int v) { return Vec3(S.positions.row(v).transpose()); };
    for (int f = 0; f < S.n_local_faces(); ++f) {
      if (!(angle[f] > 0)) continue;
      int h = patch.mesh.face_halfedge(f);
      for (int i = 0; i < 3; ++i, h = patch.mesh.next(h)) {
        const int g = S.across(f, i);
        if (g < 0 && !((S.on_boundary[f] >> i) & 1)) continue;  // the other face is absent: not exact
        const Vec3 mid = Y.row(patch_nv + SurfaceMesh::edge(h)).transpose();
        const auto& c = S.corners[f];
        bool unflat = midpoint_angle(pos(c[i]), pos(c[(i + 1) % 3]), pos(c[(i + 2) % 3]), mid) > angle[f];
        if (g >= 0 && !unflat) {
          const auto& d = S.corners[g];
          int o = 0;
          while (d[o] == c[i] || d[o] == c[(i + 1) % 3]) ++o;
          unflat = midpoint_angle(pos(c[i]), pos(c[(i + 1) % 3]), pos(d[o]), mid) > angle[f];
        }
        if (unflat) { want(f); break; }
      }
    }
  }

  // Asks for the rings of the incomplete vertices of level k within a feature's reach (plus
  // three of the level's longest edges) of its control polygon. Whether anything new was asked.
  bool widen_near(int k, const std::vector<FeatureCurve>& local) {
    const SparseLevel& S = out_.levels[k];
    double h = 0;
    for (const auto& c : S.corners)
      for (int i = 0; i < 3; ++i) h = std::max(h, (S.positions.row(c[i]) - S.positions.row(c[(i + 1) % 3])).norm());
    std::vector<int> incomplete;
    for (int v = 0; v < S.n_local_vertices(); ++v)
      if (!S.complete[v]) incomplete.push_back(v);
    bool added = false;
    for (const FeatureCurve& c : local) {
      std::vector<Vec3> p;
      for (const SurfacePoint& q : c.points) {
        const auto& f = S.corners[q.face];
        p.push_back(q.bary[0] * S.positions.row(f[0]).transpose() + q.bary[1] * S.positions.row(f[1]).transpose() +
                    q.bary[2] * S.positions.row(f[2]).transpose());
      }
      if (c.closed) p.push_back(p.front());
      const double reach = support_radius(c) + 3 * h;
      for (int v : incomplete) {
        const Vec3 x = S.positions.row(v).transpose();
        double d = p.size() == 1 ? (x - p[0]).norm() : std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j + 1 < p.size(); ++j) d = std::min(d, segment_distance(x, p[j], p[j + 1]));
        if (d <= reach) added |= need_ring(k, v);
      }
    }
    return added;
  }

  // The features drawn on level k, applied to its control points as FeaturedSurface does with
  // ProfileTarget::DrawnLevel. False when the level lacks faces they need (asked for).
  bool apply_features(int k) {
    std::vector<std::size_t> on_level;
    for (std::size_t i = 0; i < features_.size(); ++i)
      if (features_[i].level == k) on_level.push_back(i);
    if (on_level.empty() || !options_.apply_features) return true;
    SparseLevel& S = out_.levels[k];
    bool missing = false;
    std::vector<FeatureCurve> local;
    for (std::size_t i : on_level) {
      FeatureCurve c = features_[i];
      for (SurfacePoint& p : c.points) {
        const int f = S.face_of(p.face);
        if (f < 0) { need_refinable(k, p.face); missing = true; }
        else p.face = f;  // the patch's face f is present face f
      }
      local.push_back(std::move(c));
    }
    if (missing) return false;
    // Every face a curve point lies in with complete corners (its walk and normals are exact).
    for (const FeatureCurve& c : local)
      for (const SurfacePoint& p : c.points)
        for (int v : S.corners[p.face])
          if (!S.complete[v]) need_ring(k, v), missing = true;
    if (missing) return false;
    const SparsePatch patch = make_patch(S);
    const TriangleSurface surface(patch.mesh, loop_limit_normals(patch.mesh));
    std::vector<BaseCurve> curves;
    LevelPerturbation d;
    try {
      for (const FeatureCurve& c : local) curves.push_back(build_base_curve(surface, c));
      d = compute_perturbation(surface, curves, options_.backend);
    } catch (const InvalidInput&) {
      // A walk may have met the edge of the computed region rather than of the surface: widen
      // the region around every incomplete vertex near a curve and try again; the error stands
      // when there is none (the feature is wrong on the whole surface too).
      if (!widen_near(k, local)) throw;
      return false;
    }
    // Exact only if the moved vertices and two rings around them are complete (their limit
    // normals, the rays' faces): else the region is widened and the pass repeated.
    std::vector<char> checked(S.vertex.size(), 0);
    const auto check = [&](int v) {
      if (checked[v]) return;
      checked[v] = 1;
      if (!S.complete[v]) need_ring(k, v), missing = true;
    };
    for (int pv : d.vertices) {
      const int v = patch.local[pv];
      check(v);
      S.for_faces_around(v, [&](int f) {
        for (int w : S.corners[f]) {
          check(w);
          S.for_faces_around(w, [&](int g) { for (int u : S.corners[g]) check(u); });
        }
      });
    }
    for (const BaseCurve& bc : curves)
      for (const BaseSegment& s : bc.segments)
        for (int v : S.corners[s.face]) check(v);
    if (missing) return false;
    out_.unperturbed.resize(static_cast<std::size_t>(L_ + 1));
    out_.unperturbed[static_cast<std::size_t>(k)] = S.positions;
    for (std::size_t r = 0; r < d.vertices.size(); ++r)
      S.positions.row(patch.local[d.vertices[r]]) += d.displacement.row(static_cast<Eigen::Index>(r));
    moved_[k] = static_cast<int>(d.vertices.size());
    for (std::size_t j = 0; j < on_level.size(); ++j) curves_[on_level[j]] = std::move(curves[j]);
    return true;
  }

  void build_output() {
    out_.triangles_per_level.assign(static_cast<std::size_t>(L_ + 1), 0);
    for (const FeatureCurve& c : features_) out_.feature_angle_deg.push_back(c.params.flatness_angle_deg);
    std::unordered_map<UniformId, int> index;
    const auto id = [&](UniformId v) {
      const auto [it, inserted] = index.try_emplace(v, static_cast<int>(out_.mesh_vertex.size()));
      if (inserted) out_.mesh_vertex.push_back(v);
      return it->second;
    };
    PolygonList faces;
    for (int k = 0; k <= L_; ++k) {
      const SparseLevel& S = out_.levels[k];
      for (int f = 0; f < S.n_local_faces(); ++f) {
        if (out_.split[k][f]) continue;
        std::array<int, 3> corner{}, mid{-1, -1, -1};
        for (int i = 0; i < 3; ++i) {
          corner[i] = id(S.vertex[S.corners[f][i]]);
          const UniformId m = S.n_vertices + (S.halfedges[f][i] >> 1);
          if (k < L_ && out_.levels[k + 1].vertex_of(m) >= 0) mid[i] = id(m);
        }
        for (const auto& t : green_closure(corner, mid)) {
          faces.push_back({t[0], t[1], t[2]});
          ++out_.triangles_per_level[static_cast<std::size_t>(k)];
        }
      }
    }
    MatrixX3 V(static_cast<Eigen::Index>(out_.mesh_vertex.size()), 3);
    out_.mesh_vertex_level.assign(out_.mesh_vertex.size(), -1);
    for (std::size_t i = 0; i < out_.mesh_vertex.size(); ++i)
      for (int k = L_; k >= 0; --k)
        if (const int v = out_.levels[k].vertex_of(out_.mesh_vertex[i]); v >= 0) {
          V.row(static_cast<Eigen::Index>(i)) = out_.levels[k].positions.row(v);
          out_.mesh_vertex_level[i] = k;
          break;
        }
    out_.mesh = SurfaceMesh::from_polygons(V, faces);
  }

  const SurfaceMesh& base_;
  const SubdivisionOptions& opt_;
  const int L_;
  const std::vector<FeatureCurve>& features_;
  const AdaptiveEvaluationOptions& options_;
  std::vector<std::unordered_set<UniformId>> wants_;  // per level: faces to quadrisect
  std::vector<BaseCurve> curves_;                      // per feature, once applied
  std::vector<char> applied_;                          // per level: its features are applied
  std::vector<int> moved_;                             // per level: vertices its features moved
  int lowest_new_ = 0;                                 // lowest level given a new mark this pass
  double heights_ = 0;                                 // the features' largest heights, summed
  AdaptiveEvaluation out_;
};

}  // namespace

long long AdaptiveEvaluation::faces_computed() const {
  long long n = 0;
  for (const SparseLevel& s : levels) n += s.n_local_faces();
  return n;
}

AdaptiveEvaluation evaluate_adaptive(const SurfaceMesh& base, const SubdivisionOptions& opt, int levels,
                                     const std::vector<FeatureCurve>& features,
                                     const AdaptiveEvaluationOptions& options) {
  if (opt.scheme != SchemeType::Loop) throw InvalidInput("adaptive evaluation: the scheme must be Loop");
  if (base.has_sharpness())
    throw InvalidInput("adaptive evaluation: crease and corner tags are not supported (use evaluation: uniform)");
  if (levels < 0) throw InvalidInput("adaptive evaluation: levels " + std::to_string(levels) + " < 0");
  if (options.from_level < 0 || options.from_level > levels)
    throw InvalidInput("adaptive evaluation: from_level " + std::to_string(options.from_level) + " outside 0.." +
                       std::to_string(levels));
  if (!(options.surface_angle_deg >= 0 && options.surface_angle_deg < 90))
    throw InvalidInput("adaptive evaluation: surface_angle_deg " + std::to_string(options.surface_angle_deg) +
                       " outside [0, 90)");
  for (const FeatureCurve& c : features) {
    if (c.level < 0 || c.level > levels)
      throw InvalidInput("feature '" + c.name + "': level " + std::to_string(c.level) + " outside 0.." +
                         std::to_string(levels));
    if (!(c.params.flatness_angle_deg > 0 && c.params.flatness_angle_deg < 90))
      throw InvalidInput("feature '" + c.name + "': flatness_angle_deg " + std::to_string(c.params.flatness_angle_deg) +
                         " outside (0, 90)");
  }
  return Evaluator(base, opt, levels, features, options).run();
}

}  // namespace fairshape::feature
