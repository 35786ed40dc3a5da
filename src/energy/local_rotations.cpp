#include "fairshape/energy/local_rotations.h"

#include <Eigen/LU>
#include <Eigen/SVD>

#include "fairshape/core/parallel_for.h"  // both back ends fit rotations here (serial without TBB)
#include "fairshape/energy/divided_differences.h"

namespace fairshape {

LocalRotations::LocalRotations(const SurfaceMesh& rest, const StretchBendWeights& w, double scale)
    : w_(term_weights(w, scale)), n_(rest.n_vertices()) {
  // One entry per fit of the energy: a vertex, or each side of a sharp crease through it
  // (sector_fits), which then turns on its own.
  std::vector<std::vector<Vertex>> per_vertex(static_cast<std::size_t>(n_));
  for_each_range(0, n_, 512, [&](const IndexRange<int>& r) {
    for (int v = r.begin(); v != r.end(); ++v) {
      if (rest.is_isolated(v)) continue;
      for (const LocalFit& fit : sector_fits(rest, v)) {
        Vertex out;
        out.ids = stencil(v, fit);
        out.G = difference_rows(fit);
        out.weight = fit.weight;
        out.rest.setZero();
        for (std::size_t j = 0; j < out.ids.size(); ++j)
          out.rest += out.G.col(static_cast<Eigen::Index>(j)) * rest.positions().row(out.ids[j]);
        per_vertex[static_cast<std::size_t>(v)].push_back(std::move(out));
      }
    }
  });
  for (auto& fits : per_vertex)
    for (auto& f : fits) vertices_.push_back(std::move(f));
}

std::vector<Mat3> LocalRotations::fit(const MatrixX3& deformed, RotationFit how) const {
  const Eigen::Vector<double, 5> w = how == RotationFit::Exact ? w_ : Eigen::Vector<double, 5>(1, 1, 0, 0, 0);
  std::vector<Mat3> R(vertices_.size(), Mat3::Identity());
  for_each_range(std::size_t{0}, vertices_.size(), 512, [&](const IndexRange<std::size_t>& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      const Vertex& x = vertices_[v];
      if (x.ids.empty()) continue;
      Eigen::Matrix<double, 5, 3> now = Eigen::Matrix<double, 5, 3>::Zero();
      for (std::size_t j = 0; j < x.ids.size(); ++j)
        now += x.G.col(static_cast<Eigen::Index>(j)) * deformed.row(x.ids[j]);
      // The rotation that minimizes vertex i's share of E_R for these positions: max tr(R M)
      // with M = Σ_m w_m (g_m P)ᵀ(g_m X) (a weighted Procrustes problem), R = V Uᵀ for
      // M = U Σ Vᵀ, a reflection turned into the nearest rotation by flipping the direction of
      // the smallest singular value. Being the exact minimizer makes every local/global round
      // lower E_R, which the accelerated rounds of rotation_aware_edit.cpp rely on.
      const Mat3 M = x.rest.transpose() * w.asDiagonal() * now;
      const Eigen::JacobiSVD<Mat3> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
      Mat3 V = svd.matrixV();
      if ((V * svd.matrixU().transpose()).determinant() < 0) V.col(2) *= -1.0;
      R[v] = V * svd.matrixU().transpose();
    }
  });
  return R;
}

double LocalRotations::energy(const MatrixX3& deformed) const {
  const std::vector<Mat3> R = fit(deformed);
  double e = 0;
  for (std::size_t v = 0; v < vertices_.size(); ++v) {
    const Vertex& x = vertices_[v];
    if (x.ids.empty()) continue;
    Eigen::Matrix<double, 5, 3> now = Eigen::Matrix<double, 5, 3>::Zero();
    for (std::size_t j = 0; j < x.ids.size(); ++j) now += x.G.col(static_cast<Eigen::Index>(j)) * deformed.row(x.ids[j]);
    e += 0.5 * x.weight * (w_.asDiagonal() * (now - x.rest * R[v].transpose()).cwiseAbs2()).sum();
  }
  return e;
}

double LocalRotations::constant_term(const std::vector<Mat3>& R) const {
  double c = 0;
  for (std::size_t v = 0; v < vertices_.size(); ++v) {
    const Vertex& x = vertices_[v];
    if (x.ids.empty()) continue;
    c += 0.5 * x.weight * (w_.asDiagonal() * (x.rest * (R[v].transpose() - Mat3::Identity())).cwiseAbs2()).sum();
  }
  return c;
}

Eigen::MatrixXd LocalRotations::linear_term(const std::vector<Mat3>& R) const {
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n_, 3);
  for (std::size_t v = 0; v < vertices_.size(); ++v) {
    const Vertex& x = vertices_[v];
    if (x.ids.empty()) continue;
    // Gᵀ W (G P)(Rᵀ − I): the rest derivatives turned, minus the unturned ones.
    const Eigen::Matrix<double, 5, 3> turned = x.weight * (w_.asDiagonal() * (x.rest * (R[v].transpose() - Mat3::Identity())));
    for (std::size_t j = 0; j < x.ids.size(); ++j)
      b.row(x.ids[j]) += x.G.col(static_cast<Eigen::Index>(j)).transpose() * turned;
  }
  return b;
}

}  // namespace fairshape
