#include "fairshape/energy/divided_differences.h"

#include <Eigen/Dense>
#include <cmath>
#include <optional>

#include "fairshape/core/error.h"

namespace fairshape {

std::vector<int> ordered_one_ring(const SurfaceMesh& m, int v, std::vector<int>* sharp_spokes) {
  const auto hs = m.outgoing_halfedges(v);
  const int n = static_cast<int>(hs.size());
  std::vector<int> ring;
  if (sharp_spokes) sharp_spokes->clear();
  // On a boundary the fan starts after the gap: hs[1] .. hs[n-1], then hs[0] (see SurfaceMesh).
  const bool boundary = m.is_boundary_vertex(v);
  for (int s = 0; s < n; ++s) {
    const int h = hs[boundary ? (s + 1) % n : s];
    if (sharp_spokes && !m.is_boundary_edge(SurfaceMesh::edge(h)) && m.edge_sharpness(SurfaceMesh::edge(h)) > 0)
      sharp_spokes->push_back(static_cast<int>(ring.size()));
    ring.push_back(m.to_vertex(h));
    if (m.is_boundary_halfedge(h)) continue;  // the gap: no face after the last spoke
    // Face vertices strictly between this spoke and the next one, in angular order.
    for (int g = m.next(h); m.to_vertex(g) != v && m.to_vertex(m.next(g)) != v; g = m.next(g))
      ring.push_back(m.to_vertex(g));
  }
  return ring;
}

namespace {

// `open`: the ring is a fan from one side to the other (a boundary vertex, or one sector of
// a crease), not a closed loop.
Eigen::MatrixX2d polar_map_fan(const SurfaceMesh& m, int v, const std::vector<int>& ring, bool open) {
  const int n = static_cast<int>(ring.size());
  const bool boundary = open;
  const Vec3 p0 = m.position(v);
  std::vector<Vec3> dir(n);
  std::vector<double> len(n);
  for (int j = 0; j < n; ++j) {
    const Vec3 d = m.position(ring[j]) - p0;
    len[j] = d.norm();
    if (!(len[j] > 0))
      throw InvalidInput("local parameterization: vertex " + std::to_string(v) + " coincides with its neighbour " +
                         std::to_string(ring[j]) + " (degenerate one-ring)");
    dir[j] = d / len[j];
  }
  // Angles between consecutive neighbours (cyclic inside, open on a boundary).
  const int gaps = boundary ? n - 1 : n;
  std::vector<double> angle(gaps);
  double total = 0;
  for (int j = 0; j < gaps; ++j) {
    angle[j] = std::acos(std::clamp(dir[j].dot(dir[(j + 1) % n]), -1.0, 1.0));
    total += angle[j];
  }
  if (!(total > 0))
    throw InvalidInput("local parameterization: the one-ring of vertex " + std::to_string(v) + " spans no angle");
  // Interior fans are flattened to a full disk (the paper's normalization). A boundary fan
  // keeps its true opening (a 90-degree corner stays one), shrunk only beyond a full disk:
  // this reproduces affine functions exactly on flat meshes, boundary included.
  const double scale = boundary ? std::min(1.0, 2.0 * M_PI / total) : 2.0 * M_PI / total;
  Eigen::MatrixX2d uv(n, 2);
  double theta = 0;
  for (int j = 0; j < n; ++j) {
    uv.row(j) << len[j] * std::cos(theta), len[j] * std::sin(theta);
    if (j < gaps) theta += scale * angle[j];
  }
  return uv;
}

}  // namespace

Eigen::MatrixX2d polar_map(const SurfaceMesh& m, int v, const std::vector<int>& ring) {
  return polar_map_fan(m, v, ring, m.is_boundary_vertex(v));
}

namespace {

// (ΦᵀΦ)⁻¹Φᵀ through the 5 × 5 normal equations, columns scaled by the ring size r (u, v by
// 1/r, the quadratic ones by 1/r²) so that the normal matrix is O(1) whatever the mesh scale.
// Empty when the scaled matrix is near singular: the SVD route below then decides the rank.
std::optional<Eigen::MatrixXd> full_rank_operator(const Eigen::MatrixXd& Phi) {
  if (Phi.rows() < 5) return std::nullopt;
  const double r = Phi.leftCols(2).rowwise().norm().maxCoeff();
  if (!(r > 0)) return std::nullopt;
  const Eigen::Vector<double, 5> scale(1 / r, 1 / r, 1 / (r * r), 1 / (r * r), 1 / (r * r));
  const Eigen::MatrixXd Phi_s = Phi * scale.asDiagonal();
  const Eigen::Matrix<double, 5, 5> N = Phi_s.transpose() * Phi_s;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 5, 5>> eig(N, Eigen::EigenvaluesOnly);
  // σ_min/σ_max > 1e-6 (λ ratio 1e-12): well inside the SVD route's 1e-10 rank threshold.
  if (!(eig.eigenvalues()[0] > 1e-12 * eig.eigenvalues()[4])) return std::nullopt;
  return Eigen::MatrixXd(scale.asDiagonal() * Eigen::LLT<Eigen::Matrix<double, 5, 5>>(N).solve(Phi_s.transpose()));
}

}  // namespace

Eigen::MatrixXd least_squares_operator(const Eigen::MatrixXd& Phi) {
  if (auto D = full_rank_operator(Phi)) return *D;
  // (ΦᵀΦ)⁻¹Φᵀ when Φ has full column rank. Otherwise, among all least-squares fits, the one
  // whose second-order part (rows 3-5) is smallest: c = (I − N (S N)⁺ S) Φ⁺ d, with N a basis
  // of Φ's null space and S the second-order selector. Plain least norm would trade slope
  // for curvature and bend affine data; this one reproduces it exactly.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Phi, Eigen::ComputeThinU | Eigen::ComputeFullV);
  const Eigen::VectorXd sigma = svd.singularValues();
  const double tol = 1e-10 * (sigma.size() ? sigma[0] : 0.0);
  int rank = 0;
  while (rank < sigma.size() && sigma[rank] > tol) ++rank;
  Eigen::MatrixXd pinv = Eigen::MatrixXd::Zero(5, Phi.rows());
  for (int k = 0; k < rank; ++k) pinv += svd.matrixV().col(k) * svd.matrixU().col(k).transpose() / sigma[k];
  if (rank == 5) return pinv;
  const Eigen::MatrixXd N = svd.matrixV().rightCols(5 - rank);
  const Eigen::MatrixXd SN = N.bottomRows(3);
  const Eigen::MatrixXd SN_pinv = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(SN).pseudoInverse();
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(3, 5);
  S.rightCols(3).setIdentity();
  return (Eigen::MatrixXd::Identity(5, 5) - N * SN_pinv * S) * pinv;
}

namespace {

LocalFit fit_ring(const SurfaceMesh& m, int v, std::vector<int> ring, bool open) {
  LocalFit fit;
  fit.ring = std::move(ring);
  const Eigen::MatrixX2d uv = polar_map_fan(m, v, fit.ring, open);
  Eigen::MatrixXd Phi(uv.rows(), 5);
  for (Eigen::Index j = 0; j < uv.rows(); ++j) {
    const double u = uv(j, 0), w = uv(j, 1);
    Phi.row(j) << u, w, 0.5 * u * u, u * w, 0.5 * w * w;
  }
  fit.D = least_squares_operator(Phi);
  if (!fit.D.allFinite())
    throw InvalidInput("local parameterization: the fit at vertex " + std::to_string(v) + " is not finite");
  return fit;
}

}  // namespace

LocalFit local_fit(const SurfaceMesh& m, int v) {
  if (m.is_isolated(v)) throw InvalidInput("local parameterization: vertex " + std::to_string(v) + " is isolated");
  return fit_ring(m, v, ordered_one_ring(m, v), m.is_boundary_vertex(v));
}

std::vector<LocalFit> sector_fits(const SurfaceMesh& m, int v) {
  if (m.is_isolated(v)) throw InvalidInput("local parameterization: vertex " + std::to_string(v) + " is isolated");
  std::vector<int> sharp;
  const std::vector<int> ring = ordered_one_ring(m, v, &sharp);
  const bool boundary = m.is_boundary_vertex(v);
  const int n = static_cast<int>(ring.size()), k = static_cast<int>(sharp.size());
  if (k == 0 || (!boundary && k == 1)) return {fit_ring(m, v, ring, boundary)};
  // Sector boundaries: the sharp spokes, plus the two ends of a boundary fan.
  std::vector<int> cuts = sharp;
  if (boundary) {
    if (cuts.front() != 0) cuts.insert(cuts.begin(), 0);
    if (cuts.back() != n - 1) cuts.push_back(n - 1);
  }
  const int sectors = boundary ? static_cast<int>(cuts.size()) - 1 : k;
  std::vector<LocalFit> fits;
  for (int s = 0; s < sectors; ++s) {
    const int from = cuts[s], to = boundary ? cuts[s + 1] : cuts[(s + 1) % k];
    std::vector<int> part;
    for (int j = from;; j = (j + 1) % n) {  // both sharp neighbours belong to the sector
      part.push_back(ring[j]);
      if (j == to) break;
    }
    fits.push_back(fit_ring(m, v, std::move(part), true));
    fits.back().weight = 1.0 / sectors;
  }
  return fits;
}

}  // namespace fairshape
