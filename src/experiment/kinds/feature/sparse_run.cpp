#include "fairshape/experiment/kinds/feature/sparse_run.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>

#include "fairshape/core/timer.h"
#include "fairshape/experiment/kinds/feature/curve_placement_config.h"
#include "fairshape/experiment/kinds/feature/feature_folds.h"
#include "fairshape/experiment/kinds/feature/feature_width_check.h"
#include "fairshape/experiment/metric_format.h"
#include "fairshape/feature/adaptive_evaluation.h"
#include "fairshape/feature/curve_on_level.h"
#include "fairshape/feature/level_attachment.h"
#include "fairshape/feature/feature_scale.h"
#include "fairshape/feature/perturbation.h"
#include "fairshape/feature/profile_measure.h"
#include "fairshape/feature/sparse_measure.h"
#include "fairshape/feature/triangle_surface.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/mesh/polyline.h"
#include "fairshape/remesh/closest_point.h"
#include "fairshape/subdivision/multires_surface.h"

namespace fairshape {
namespace fs = std::filesystem;

void check_sparse_run(const FeatureRunSpec& s) {
  const std::string sparse = " with adaptive.evaluation: sparse";
  for (const FeatureSpec& f : s.features) {
    if (f.step > 0 || f.until >= 0 || !f.moves.empty() || !f.changes.empty())
      throw InvalidConfig(f.key + ": design steps (step, until, moves, changes) re-evaluate the uniform hierarchy; not" +
                          sparse);
  }
  if (s.vtk)
    throw InvalidConfig("output.vtk:" + sparse + " no VTK is written (its limit surface and levels need the whole "
                        "hierarchy; valid: none)");
  if (!s.adaptive)
    throw InvalidConfig("adaptive.enabled: false" + sparse + " (the result is the adaptive mesh; valid: true)");
}

namespace {

std::int64_t uniform_faces(const SurfaceMesh& base, int level) { return static_cast<std::int64_t>(base.n_faces()) << (2 * level); }

// World points placed level by level: projected on the base mesh, then on each finer level
// carried down by parameter (child_point) and projected again on the sparse level a
// non-applying evaluation refines around them (the curve's support, radius plus three edges:
// the sag between two consecutive levels is a fraction of an edge, so the uniform level's
// nearest point lies among the present faces). A face whose corners lack their one-rings is at
// the edge of the computed region and refused rather than trusted.
void place_world_points(FeatureRunSpec& spec, const SurfaceMesh& base, const SubdivisionOptions& opt, double diag) {
  std::vector<FeatureSpec*> todo;
  for (FeatureSpec& f : spec.features)
    if (!f.world_points.empty()) todo.push_back(&f);
  if (todo.empty()) return;
  std::vector<std::vector<feature::SurfacePoint>> at(todo.size());
  const auto place = [&](const feature::TriangleSurface& s, int level, std::size_t i) {
    FeatureSpec g = *todo[i];
    g.curve.level = level;
    if (level < g.curve.level) g.max_distance = 1;  // a coarse level is farther from the points
    place_on_level(s, diag, g);
    at[i] = g.curve.points;
  };
  const feature::TriangleSurface on_base(base, feature::loop_limit_normals(base));
  for (std::size_t i = 0; i < todo.size(); ++i) place(on_base, 0, i);
  for (int k = 1; k <= spec.levels; ++k) {
    std::vector<feature::FeatureCurve> probes;
    std::vector<std::size_t> which;
    for (std::size_t i = 0; i < todo.size(); ++i) {
      if (todo[i]->curve.level < k) continue;
      feature::FeatureCurve c = todo[i]->curve;
      c.level = k;
      c.points = at[i];
      for (feature::SurfacePoint& p : c.points) p = feature::child_point(p);
      probes.push_back(std::move(c));
      which.push_back(i);
    }
    if (probes.empty()) break;
    feature::AdaptiveEvaluationOptions o;
    o.apply_features = false;
    o.backend = spec.implementation;
    const feature::AdaptiveEvaluation a = feature::evaluate_adaptive(base, opt, k, probes, o);
    const feature::SparseLevel& S = a.levels[static_cast<std::size_t>(k)];
    const feature::SparsePatch patch = feature::make_patch(S);
    const feature::TriangleSurface s(patch.mesh, feature::loop_limit_normals(patch.mesh));
    for (std::size_t i : which) {
      place(s, k, i);
      for (feature::SurfacePoint& p : at[i]) {
        for (int v : S.corners[static_cast<std::size_t>(p.face)])
          if (!S.complete[static_cast<std::size_t>(v)])
            throw InvalidInput("feature '" + todo[i]->curve.name + "': a point projects to the edge of the region refined "
                               "around it on level " + std::to_string(k) + " (adaptive.evaluation: sparse); use uniform");
        p.face = static_cast<int>(S.face[static_cast<std::size_t>(p.face)]);
      }
    }
  }
  for (std::size_t i = 0; i < todo.size(); ++i) todo[i]->curve.points = at[i];
}

// The config key of a feature's placement tool ("features[2].geodesic").
std::string placement_key(const FeatureSpec& f) {
  static const char* names[] = {"geodesic", "section", "polyline"};
  return f.key + "." + names[f.placement->index()];
}

// The placement tools (geodesic, section, polyline) run on the whole level a curve is drawn on
// (a geodesic's path and a section's loop may cross any part of it). A sparse run computes that
// level whole where it is small enough (adaptive.placement_max_faces): the uniform Loop levels up
// to it — the same level the uniform run places on, so the same faces and coordinates — kept only
// while placing. Above the limit the run is refused, naming the key and what to do.
void place_with_tools(FeatureRunSpec& spec, const SurfaceMesh& base, const SubdivisionOptions& opt, double diag) {
  int deepest = -1;
  for (const FeatureSpec& f : spec.features) {
    if (!f.placement) continue;
    const std::int64_t faces = uniform_faces(base, f.curve.level);
    if (faces > spec.adaptive_placement_max_faces)
      throw InvalidConfig(placement_key(f) + ": the tool needs its whole level; level " + std::to_string(f.curve.level) +
                          " has " + std::to_string(faces) + " faces > adaptive.placement_max_faces " +
                          std::to_string(spec.adaptive_placement_max_faces) +
                          " with adaptive.evaluation: sparse (draw the curve on a coarser level, raise "
                          "adaptive.placement_max_faces, give points or surface_points, or use adaptive.evaluation: uniform)");
    deepest = std::max(deepest, f.curve.level);
  }
  if (deepest < 0) return;
  const MultiresSurface whole(base, opt, deepest, spec.implementation);
  std::map<int, feature::TriangleSurface> drawn_on;  // one per level: its normals and AABB tree
  for (FeatureSpec& f : spec.features) {
    if (!f.placement) continue;
    const SurfaceMesh& level = whole.mesh(f.curve.level);
    const feature::TriangleSurface& s = drawn_on.try_emplace(f.curve.level, level, feature::loop_limit_normals(level)).first->second;
    place_on_level(s, diag, f);
  }
}

// A base curve with its segments' faces as uniform ids (they are local to the level's patch).
feature::BaseCurve on_uniform_faces(feature::BaseCurve c, const feature::SparseLevel& S) {
  for (feature::BaseSegment& s : c.segments) s.face = static_cast<int>(S.face[static_cast<std::size_t>(s.face)]);
  return c;
}

Vec3 point_on(const feature::SparseLevel& S, const feature::SurfacePoint& p) {
  const int f = S.face_of(p.face);
  if (f < 0) throw std::logic_error("sparse run: an attachment's face is not computed");
  Vec3 x = Vec3::Zero();
  for (int c = 0; c < 3; ++c) x += p.bary[c] * S.positions.row(S.corners[static_cast<std::size_t>(f)][c]).transpose();
  return x;
}

}  // namespace

namespace {
struct SparseRunEvaluation {
  SurfaceMesh base;
  std::vector<feature::FeatureCurve> curves;
  feature::AdaptiveEvaluation a;
  double apply_s = 0;
};

// The base mesh read, the features placed on sparse levels and evaluated.
SparseRunEvaluation evaluate_sparse_run(FeatureRunSpec& spec) {
  SparseRunEvaluation e;
  e.base = read_mesh(spec.mesh_path);
  const SurfaceMesh& base = e.base;
  SubdivisionOptions opt;
  opt.scheme = SchemeType::Loop;
  opt.weights = spec.loop_weights;
  // max_distance scales with the base mesh's diagonal (the uniform run takes the finest
  // level's, the same up to the surface's shrinkage).
  const double diag = (base.positions().colwise().maxCoeff() - base.positions().colwise().minCoeff()).norm();
  place_with_tools(spec, base, opt, diag);
  place_world_points(spec, base, opt, diag);
  for (FeatureSpec& f : spec.features) {
    for (const auto& p : f.curve.points)
      if (p.face < 0 || p.face >= uniform_faces(base, f.curve.level))
        throw InvalidInput("feature '" + f.curve.name + "': face " + std::to_string(p.face) + " is not a face of level " +
                           std::to_string(f.curve.level));
    check_feature_width(f, base, spec.levels);
    e.curves.push_back(f.curve);
  }
  feature::AdaptiveEvaluationOptions o;
  o.from_level = 0;  // from the base mesh: the features' supports are refined to their levels
  o.surface_angle_deg = spec.adaptive_surface_angle_deg;
  o.backend = spec.implementation;
  o.target = spec.profile_target;
  const Timer apply;
  e.a = feature::evaluate_adaptive(base, opt, spec.levels, e.curves, o);
  e.apply_s = apply.seconds();
  return e;
}
}  // namespace

void check_sparse_features(FeatureRunSpec& spec) { (void)evaluate_sparse_run(spec); }

void execute_sparse_feature_run(FeatureRunSpec& spec, const RunOutputs& out, MetricRow& row) {
  const SparseRunEvaluation e = evaluate_sparse_run(spec);
  const SurfaceMesh& base = e.base;
  const std::vector<feature::FeatureCurve>& curves = e.curves;
  const feature::AdaptiveEvaluation& a = e.a;
  const int L = spec.levels;
  row["apply_s"] = num(e.apply_s);
  const feature::SparseLevel& S = a.levels[static_cast<std::size_t>(L)];
  row["n_fine"] = std::to_string(S.n_local_vertices());  // computed, not the uniform count
  row["triangles_uniform"] = std::to_string(uniform_faces(base, L));
  const double diag = (base.positions().colwise().maxCoeff() - base.positions().colwise().minCoeff()).norm();
  if (S.original.rows() != S.positions.rows())
    throw std::logic_error("sparse run: the finest level's positions without the features are missing");
  // Against the surface without features, as the uniform run's (every vertex the features move
  // is present: adaptive_evaluation.h).
  const Eigen::VectorXd moved = (S.positions - S.original).rowwise().norm();
  row["max_displacement"] = num(moved.maxCoeff());
  // The present faces of the finest level hold every face a feature moved: their folds are the run's.
  const FoldReport folds = flipped_triangles(S.corners, S.original, S.positions);
  // The finest vertices moved, as the uniform run counts them (its threshold scales with the
  // finest level's diagonal, this one with the base mesh's: the same up to the shrinkage).
  row["vertices_moved"] = std::to_string((moved.array() > 1e-12 * diag).count());
  row["adaptive_evaluation"] = "sparse";
  row["adaptive_faces_computed"] = std::to_string(a.faces_computed());
  row["triangles_adaptive"] = std::to_string(a.mesh.n_faces());
  fs::create_directories(fs::path(out.dir) / "adaptive");
  write_mesh(a.mesh, (fs::path(out.dir) / "adaptive" / (out.run_id + ".obj")).string());
  write_mesh(a.mesh, out.final_path());

  // features.csv: the finest level and the limit measured on the finest sparse level
  // (feature/sparse_measure.h), as the uniform run measures them.
  SubdivisionOptions opt;
  opt.scheme = SchemeType::Loop;
  opt.weights = spec.loop_weights;
  const std::vector<feature::SparseFeatureMeasure> measured = feature::measure_sparse_features(a, L, opt, spec.implementation);
  const feature::ProfileGates gates = feature::profile_gates(spec.profile_target);
  // Each finer level of the result as a patch of its present faces, and each featured level
  // before its features (the surface the curves were built on, their normals), for carrying the
  // curves to where the features are.
  struct ResultPatch {
    feature::SparsePatch patch;
    std::unique_ptr<ClosestPointQuery> query;
  };
  std::map<int, ResultPatch> result_patches;
  const auto result_patch = [&](int level) -> const ResultPatch& {
    auto [it, added] = result_patches.try_emplace(level);
    if (added) {
      it->second.patch = feature::make_patch(a.levels[static_cast<std::size_t>(level)]);
      it->second.query = std::make_unique<ClosestPointQuery>(it->second.patch.mesh);
    }
    return it->second;
  };
  std::map<int, std::pair<SurfaceMesh, std::unique_ptr<feature::TriangleSurface>>> drawn_surfaces;
  const auto drawn_surface = [&](int level) -> const feature::TriangleSurface& {
    auto [it, added] = drawn_surfaces.try_emplace(level);
    if (added) {
      feature::SparseLevel before = a.levels[static_cast<std::size_t>(level)];
      before.positions = a.unperturbed[static_cast<std::size_t>(level)];
      it->second.first = feature::make_patch(before).mesh;
      it->second.second = std::make_unique<feature::TriangleSurface>(it->second.first, feature::loop_limit_normals(it->second.first));
    }
    return *it->second.second;
  };
  double heights = 0;
  for (const feature::FeatureCurve& c : curves)
    heights += std::max(std::abs(c.params.height), std::abs(c.params.height * c.params.end_height_ratio));
  fs::create_directories(fs::path(out.dir) / "curves");
  int segments = 0, within = 0;
  double fine = 0, limit = 0, height = 0, width = 0;
  bool any_limit = false;
  std::string first_miss;
  for (std::size_t i = 0; i < a.curves.size(); ++i) {
    const feature::BaseCurve& bc = a.curves[i];
    const feature::FeatureParams& q = curves[i].params;
    segments += static_cast<int>(bc.segments.size());
    MatrixX3 X(static_cast<Eigen::Index>(bc.segments.size() + (bc.closed ? 0 : 1)), 3);
    for (std::size_t j = 0; j < bc.segments.size(); ++j) X.row(static_cast<Eigen::Index>(j)) = bc.segments[j].a.transpose();
    if (!bc.closed) X.row(X.rows() - 1) = bc.segments.back().b.transpose();
    write_polyline(Polyline{X, bc.closed},
                   (fs::path(out.dir) / "curves" / (out.run_id + "_" + file_name_part(curves[i].name) + ".obj")).string());
    const feature::SparseFeatureMeasure& f = measured[i];
    const feature::ProfileMeasure& m = f.fine;
    const feature::ProfileMeasure& b = f.limit;
    // The surface profile_on makes exact decides (profile_measure.h, profile_gates); a gated
    // limit that is not measured (the support not refined completely) is a miss, said in the row.
    std::string why;
    if (gates.fine) why = feature::profile_miss("finest level", m, q);
    if (why.empty() && gates.limit) why = f.limit_measured ? feature::profile_miss("limit", b, q) : f.limit_note;
    // A profile met exactly is still not a fine feature when it dwarfs the surface there.
    if (const std::string too_tall = feature::feature_scale_miss(f.scale); !too_tall.empty())
      why = too_tall + (why.empty() ? "" : "; " + why);
    const auto at_limit = [&](double x) { return f.limit_measured ? num(x) : std::string("nan"); };
    const int level = curves[i].level;
    out.add_row("features", {curves[i].name, std::to_string(level), num(q.height), num(q.radius), num(q.right_radius()),
                             num(m.height_min), num(m.height_max), num(m.width_left), num(m.width_right), num(m.height_error),
                             num(m.width_error), num(m.profile_error), at_limit(b.height_min), at_limit(b.height_max),
                             at_limit(b.width_left), at_limit(b.width_right), at_limit(b.height_error),
                             at_limit(b.width_error), at_limit(b.profile_error), why.empty() ? "1" : "0", why,
                             feature::gates_name(gates)});
    within += why.empty() ? 1 : 0;
    fine = std::max(fine, m.profile_error), height = std::max(height, m.height_error), width = std::max(width, m.width_error);
    if (f.limit_measured) {
      any_limit = true;
      limit = std::max(limit, b.profile_error), height = std::max(height, b.height_error), width = std::max(width, b.width_error);
    }
    if (!why.empty() && first_miss.empty()) first_miss = "feature '" + curves[i].name + "' (level " + std::to_string(level) + "), " + why;
    // attachments.csv: the curve on its level (its own faces and coordinates) and on every finer
    // one where the feature is (feature/curve_on_level.h), on the result there: the faces under
    // the curve and its crest are computed on each (the feature changes them).
    const auto add = [&](int at, std::size_t j, const feature::SurfacePoint& p, const Vec3& x) {
      out.add_row("attachments", {curves[i].name, std::to_string(at), std::to_string(j), std::to_string(p.face), num(p.bary[0]),
                                  num(p.bary[1]), num(p.bary[2]), num(x.x()), num(x.y()), num(x.z())});
    };
    const auto drawn = feature::attachments_per_level(on_uniform_faces(bc, a.levels[static_cast<std::size_t>(level)]), level, level);
    for (std::size_t j = 0; j < drawn.front().size(); ++j)
      add(level, j, drawn.front()[j], point_on(a.levels[static_cast<std::size_t>(level)], drawn.front()[j]));
    for (int at = level + 1; at <= L; ++at) {
      const ResultPatch& r = result_patch(at);
      const feature::CarriedCurve c = feature::carry_curve(bc, drawn_surface(level), r.patch.mesh, *r.query,
                                                           feature::carry_reach(bc, heights));
      for (std::size_t j = 0; j < c.at.size(); ++j) {
        const feature::SurfacePoint p{static_cast<int>(a.levels[static_cast<std::size_t>(at)].face[static_cast<std::size_t>(c.at[j].face)]),
                                      c.at[j].bary};
        add(at, j, p, c.x.row(static_cast<Eigen::Index>(j)).transpose());
      }
    }
  }
  row["segments"] = std::to_string(segments);
  row["features_within_tolerance"] = std::to_string(within);
  row["worst_profile_error_fine"] = num(fine);
  row["worst_profile_error_limit"] = any_limit ? num(limit) : "";  // runs.csv holds finite numbers or nothing
  row["worst_height_error"] = num(height);
  row["worst_width_error"] = num(width);
  if (!first_miss.empty()) {
    row["termination"] = std::string(to_string(Termination::ConstraintsUnmet));
    row["message"] = std::to_string(a.curves.size() - static_cast<std::size_t>(within)) + " of " +
                     std::to_string(a.curves.size()) + " features miss their tolerance; first: " + first_miss;
  }
  report_folds(folds, row);
}

}  // namespace fairshape
