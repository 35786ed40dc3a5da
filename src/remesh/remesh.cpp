#include "fairshape/remesh/remesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <optional>

#include "fairshape/core/error.h"
#include "fairshape/core/timer.h"
#include "fairshape/remesh/closest_point.h"
#include "fairshape/remesh/quad_pairing.h"
#include "fairshape/remesh/quality.h"
#include "fairshape/remesh/relaxation.h"
#include "fairshape/remesh/simplify.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape {
namespace {

// Closest-point projection and relaxation only slide vertices over the part of the dense
// surface they are near, and subdivision rounds off whatever the coarser level had: the tip of
// a horn, an ear or a tail that no vertex reached stays cut off on every finer level. So every
// dense vertex farther than `tolerance` from the level pulls the nearest vertex of the level
// (one facing its way, not yet pinned) onto itself, and pins it there; the pins are kept on the
// finer levels (vertex ids nest), as MAPS keeps the base vertices on the dense ones. A pin
// whose move (with its drag) takes some vertex's edges beyond `band` times the mean edge, and
// further than they were, is not made (keep_even_moves): it would trade the tip for a spike of
// long and short edges.
int attract(const SurfaceMesh& topology, MatrixX3& X, const SurfaceMesh& dense, const ClosestPointQuery& on_dense,
            const MatrixX3& dense_normals, double tolerance, std::vector<int>& pins, double band) {
  SurfaceMesh level = topology;
  level.positions() = X;
  const ClosestPointQuery on_level(level);
  std::vector<int> faces;
  const MatrixX3 near = on_level.closest_points(dense.positions(), &faces);
  const MatrixX3 N = vertex_normals(topology, X);
  std::vector<double> pull(static_cast<std::size_t>(X.rows()), 0.0);
  std::vector<int> chosen(static_cast<std::size_t>(X.rows()), -1);
  std::vector<char> taken(static_cast<std::size_t>(dense.n_vertices()), 0);  // one vertex per dense vertex
  for (int p : pins)
    if (p >= 0) taken[p] = 1;
  for (int i = 0; i < dense.n_vertices(); ++i) {
    const double d = (near.row(i) - dense.positions().row(i)).norm();
    if (d <= tolerance || dense.is_isolated(i) || taken[i]) continue;
    int best = -1;
    double best_d = 0;
    for (int v : topology.face_vertices(faces[i])) {
      if (pins[v] >= 0 || N.row(v).dot(dense_normals.row(i)) <= 0) continue;
      const double dv = (X.row(v) - dense.positions().row(i)).norm();
      if (best < 0 || dv < best_d) best = v, best_d = dv;
    }
    if (best >= 0 && d > pull[best]) pull[best] = d, chosen[best] = i;
  }
  // The pinned vertex drags its neighbourhood along, fading over as many rings as its move is
  // long in edges: a lone vertex pulled up a horn leaves a spike of long edges that relaxation
  // (one ring per round) would take many rounds to fill in.
  const Neighbours nb = neighbours(topology);
  const double edge = mean_edge(topology, X);
  const MatrixX3 before = X;
  const std::vector<int> pins_before = pins;
  MatrixX3 drag = MatrixX3::Zero(X.rows(), 3);
  std::vector<double> weight(static_cast<std::size_t>(X.rows()), 0.0);
  int n = 0;
  for (int v = 0; v < X.rows(); ++v) {
    if (chosen[v] < 0) continue;
    ++n;
    const Eigen::RowVector3d move = dense.positions().row(chosen[v]) - X.row(v);
    const int rings = std::min(8, static_cast<int>(std::ceil(move.norm() / edge)));
    std::vector<int> front{v};
    std::map<int, int> seen{{v, 0}};
    for (int k = 1; k <= rings; ++k) {
      std::vector<int> next;
      for (int u : front)
        for (int i = nb.start[u]; i < nb.start[u + 1]; ++i)
          if (seen.emplace(nb.ids[i], k).second) next.push_back(nb.ids[i]);
      front = next;
    }
    for (const auto& [u, k] : seen) {
      const double w = 1.0 - double(k) / (rings + 1);
      if (pins[u] < 0 && w > weight[u]) weight[u] = w, drag.row(u) = w * move;
    }
  }
  for (int v = 0; v < X.rows(); ++v)
    if (chosen[v] >= 0) pins[v] = chosen[v];
  if (n == 0) return 0;
  std::vector<int> moved;
  for (int v = 0; v < X.rows(); ++v)
    if (weight[v] > 0 && pins[v] < 0) moved.push_back(v);
  X += drag;
  for (int v = 0; v < X.rows(); ++v)
    if (pins[v] >= 0) X.row(v) = dense.positions().row(pins[v]);
  const MatrixX3 Nm = vertex_normals(topology, X);
  MatrixX3 P(static_cast<Eigen::Index>(moved.size()), 3), Q(static_cast<Eigen::Index>(moved.size()), 3);
  for (std::size_t i = 0; i < moved.size(); ++i) P.row(i) = X.row(moved[i]), Q.row(i) = Nm.row(moved[i]);
  const MatrixX3 on = on_dense.facing_points(P, Q, 2.0 * edge);
  for (std::size_t i = 0; i < moved.size(); ++i) X.row(moved[i]) = on.row(i);
  if (band > 0) {
    keep_even_moves(topology, before, X, band);
    for (int v = 0; v < X.rows(); ++v)
      if (pins_before[v] < 0 && pins[v] >= 0 && X.row(v) == before.row(v)) pins[v] = -1, --n;
  }
  return n;
}


SurfaceMesh make_base(const SurfaceMesh& dense, const RemeshOptions& opt, BaseMethod method) {
  auto triangle_base = [&](int faces) {
    return method == BaseMethod::Isotropic ? isotropic_base(dense, faces) : simplify_to_faces(dense, faces);
  };
  const bool quads = opt.subdivision.scheme == SchemeType::CatmullClark && opt.base == RemeshBase::QuadDominant;
  if (!quads) return triangle_base(opt.base_faces);
  // Pairing merges most triangles two by two: start from about twice as many, then correct
  // the count once by the fraction actually paired.
  int triangles = 2 * opt.base_faces;
  SurfaceMesh base;
  for (int attempt = 0; attempt < 2; ++attempt) {
    base = pair_triangles(triangle_base(triangles));
    if (std::abs(base.n_faces() - opt.base_faces) <= 0.05 * opt.base_faces) break;
    triangles = static_cast<int>(std::lround(triangles * double(opt.base_faces) / base.n_faces()));
  }
  return base;
}


MultiresSurface remesh_once(const SurfaceMesh& dense, const RemeshOptions& opt, BaseMethod method, RemeshReport& r) {

  r.base_faces_requested = opt.base_faces;
  Timer timer;
  r.base_method = method;
  const SurfaceMesh base = make_base(dense, opt, method);
  // The remesher cannot go below a few faces per handle, nor follow every request exactly;
  // a base far from the request is refused rather than passed off as what was asked.
  if (std::abs(base.n_faces() - opt.base_faces) > 0.25 * opt.base_faces)
    throw InvalidInput("remesh: --base-faces " + std::to_string(opt.base_faces) + ": the base made has " +
                       std::to_string(base.n_faces()) + " faces, more than 25% off the request; for this model ask for " +
                       (base.n_faces() > opt.base_faces ? "at least " : "at most ") + std::to_string(base.n_faces()) +
                       " (the dense mesh has " + std::to_string(dense.n_faces()) + " faces)");
  if (opt.subdivision.scheme == SchemeType::Loop) require_triangles(base, "remesh");
  const MultiresSurface smooth(base, opt.subdivision, opt.levels, opt.backend);
  const ClosestPointQuery on_dense(dense);
  MatrixX3 X = base.positions();
  if (opt.fit == FitMethod::Finest && opt.levels > 0) {
    const SurfaceMesh& topology = smooth.mesh(opt.levels);
    X = on_dense.closest_points(topology.positions());
    // The earlier pipeline as it was: closest points, no guard.
    relax(topology, X, on_dense, {opt.relax_rounds, 0.0, std::numeric_limits<double>::infinity()}, &r.unprojected);
  }
  const MatrixX3 dense_normals = vertex_normals(dense, dense.positions());
  std::vector<int> pins;  // per vertex of the current level: the dense vertex it is pinned to, or -1
  for (int l = 0; l < opt.levels && opt.fit == FitMethod::LevelByLevel; ++l) {
    const SurfaceMesh& topology = smooth.mesh(l + 1);
    const MatrixX3 predicted = smooth.subdivision_operator(l) * X;
    // A vertex may be an edge or so off the dense surface; its facing point is searched up to
    // two of this level's average edges away (a longer ray only costs time: the nearest hit wins).
    const double reach = 2.0 * mean_edge(topology, predicted);
    X = on_dense.facing_points(predicted, vertex_normals(topology, predicted), reach);
    // Rays from a rounded-off tip can miss it and fall back to its closest point, several onto
    // one dense vertex (the mannequin's claws: zero-length edges); such a vertex stays where
    // subdivision put it, and relaxation or a pin brings it onto the surface.
    keep_even_moves(topology, predicted, X, opt.even_band);
    pins.resize(static_cast<std::size_t>(X.rows()), -1);
    for (int v = 0; v < X.rows(); ++v)
      if (pins[v] >= 0) X.row(v) = dense.positions().row(pins[v]);
    const double tolerance = mean_edge(topology, X);
    RelaxSettings rs;
    rs.reach = reach;
    rs.band = opt.even_band;
    for (int half = 0; half < 2; ++half) {
      rs.rounds = (opt.relax_rounds + 1 - half) / 2;
      relax(topology, X, on_dense, rs, &r.unprojected, &pins);
      attract(topology, X, dense, on_dense, dense_normals, tolerance, pins, opt.pin_band);
    }
    rs.rounds = opt.relax_rounds / 2;
    relax(topology, X, on_dense, rs, &r.unprojected, &pins);
  }
  if (!X.allFinite()) throw InvalidInput("remesh: projection onto the dense surface failed (non-finite points)");
  MultiresSurface h = MultiresSurface::analyze(base, X, opt.subdivision, opt.levels, opt.backend);
  r.seconds = timer.seconds();

  const SurfaceMesh& fine = h.mesh(opt.levels);
  r.bbox_diagonal = bounding_box_diagonal(dense);
  const Eigen::VectorXd off = (fine.positions() - on_dense.closest_points(fine.positions())).rowwise().norm();
  r.off_surface = static_cast<int>((off.array() > 1e-9 * r.bbox_diagonal).count());
  r.off_surface_max = off.size() ? off.maxCoeff() : 0.0;
  r.sample_spacing = opt.sample_spacing * r.bbox_diagonal;
  const ClosestPointQuery on_fine(fine);
  const SurfaceDistance d = hausdorff_distance(dense, on_dense, fine, on_fine, r.sample_spacing);
  r.dense_to_fine = d.a_to_b;
  r.fine_to_dense = d.b_to_a;
  r.hausdorff = d.hausdorff();
  r.base_faces = base.n_faces();
  r.fine_vertices = fine.n_vertices();
  r.fine_faces = fine.n_faces();
  const EdgeLengthRange edges = edge_length_range(fine);
  r.shortest_edge = edges.shortest;
  r.longest_edge = edges.longest;
  const auto midpoint = [&fine](int e) -> Vec3 {
    return e < 0 ? Vec3::Zero() : Vec3(0.5 * (fine.position(fine.from_vertex(2 * e)) + fine.position(fine.to_vertex(2 * e))));
  };
  r.shortest_at = midpoint(edges.shortest_id);
  r.longest_at = midpoint(edges.longest_id);
  r.base_valence = valence_histogram(h.mesh(0));
  r.fine_valence = valence_histogram(fine);
  return h;
}

// How far a result is from the targets: the worse of the two, 1 = on the target.
double shortfall(const RemeshReport& r) {
  return std::max(r.hausdorff_relative() / kHausdorffTarget, r.edge_ratio() / kEdgeRatioTarget);
}

}  // namespace

std::vector<std::string> RemeshReport::misses() const {
  std::vector<std::string> out;
  auto say = [&out](const std::string& what, double got, double target, const std::string& unit) {
    if (!(got <= target)) {  // NaN and inf miss too
      std::ostringstream s;
      s << std::setprecision(3) << what << " " << got << unit << " is above the target " << target << unit << " ("
        << got / target << "x)";
      out.push_back(s.str());
    }
  };
  say("Hausdorff distance", 100.0 * hausdorff_relative(), 100.0 * kHausdorffTarget, "% of the bounding-box diagonal");
  say("edge ratio", edge_ratio(), kEdgeRatioTarget, "");
  return out;
}

MultiresSurface remesh(const SurfaceMesh& dense, const RemeshOptions& opt, RemeshReport* report) {
  if (opt.base_faces < 4 || opt.base_faces > dense.n_faces())
    throw InvalidInput("remesh: --base-faces " + std::to_string(opt.base_faces) + " outside [4, " +
                       std::to_string(dense.n_faces()) + "] (the dense mesh has " + std::to_string(dense.n_faces()) +
                       " faces)");
  if (opt.levels < 0) throw InvalidInput("remesh: --levels " + std::to_string(opt.levels) + " is negative");
  require_triangles(dense, "remesh");
  RemeshReport r;
  if (opt.base_method != BaseMethod::Auto) {
    MultiresSurface h = remesh_once(dense, opt, opt.base_method, r);
    if (report) *report = r;
    return h;
  }
  // Neither base wins everywhere (papers/boier-martin/README.md, "Remesher quality"): edge
  // collapse keeps thin tips (the cow's horns and tail), the isotropic base gives even edges
  // and follows flat CAD faces (fandisk). Both are made and measured; the closer to the
  // targets is kept, and the report says which, with the time of both.
  // A base that cannot be made at this size (InvalidInput) leaves the other; with neither,
  // the edge-collapse base's error is the one reported.
  Timer both;
  std::optional<MultiresSurface> hc, hi;
  RemeshReport ri;
  std::optional<InvalidInput> failed;
  try {
    hc.emplace(remesh_once(dense, opt, BaseMethod::EdgeCollapse, r));
  } catch (const InvalidInput& e) {
    failed.emplace(e);
  }
  try {
    hi.emplace(remesh_once(dense, opt, BaseMethod::Isotropic, ri));
  } catch (const InvalidInput&) {
    if (!hc) throw *failed;
  }
  const bool isotropic = hi && (!hc || shortfall(ri) < shortfall(r));
  if (isotropic) r = ri;
  r.seconds = both.seconds();
  if (report) *report = r;
  return isotropic ? std::move(*hi) : std::move(*hc);
}

}  // namespace fairshape
