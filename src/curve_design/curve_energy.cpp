#include "fairshape/curve_design/curve_energy.h"

#include "fairshape/core/config.h"

namespace fairshape {

std::vector<CurveStencil> bending_stencils(int n, bool closed) {
  std::vector<CurveStencil> out;
  const int first = closed ? 0 : 1, last = closed ? n : n - 1;
  for (int i = first; i < last; ++i) out.push_back({3, {(i + n - 1) % n, i, (i + 1) % n}, {0.25, -0.5, 0.25}, -1});
  return out;
}

namespace {

// §3: E = Σ_i |¼ (c_{i−1} − 2 c_i + c_{i+1})|² over interior points (all points when closed),
// whose Hessian is the paper's banded H = (1/8)·[1 −2 1; −2 5 −4 1; 1 −4 6 −4 1; ...].
class Bending final : public CurveEnergy {
 public:
  std::vector<CurveStencil> stencils(int n, bool closed) const override { return bending_stencils(n, closed); }
};

// Σ_i |c_{i+1} − c_i|²: the membrane analogue, for comparison with bending.
class Stretching final : public CurveEnergy {
 public:
  std::vector<CurveStencil> stencils(int n, bool closed) const override {
    std::vector<CurveStencil> out;
    for (int i = 0; i < (closed ? n : n - 1); ++i) out.push_back({2, {i, (i + 1) % n, 0}, {-1.0, 1.0, 0}, -1});
    return out;
  }
};

// §3: D = Σ_i |c_i − a_i|², the distance to the attracting curve.
class AttractorDistance final : public CurveEnergy {
 public:
  std::vector<CurveStencil> stencils(int n, bool) const override {
    std::vector<CurveStencil> out;
    for (int i = 0; i < n; ++i) out.push_back({1, {i, 0, 0}, {1.0, 0, 0}, i});
    return out;
  }
};

template <class T>
CurveEnergyRegistry::Factory plain() {
  return [](Config&) { return std::make_unique<T>(); };
}

}  // namespace

void register_curve_energies(CurveEnergyRegistry& r) {
  // One implementation serves both back ends: these build stencil lists, never the hot loop.
  for (Backend b : built_backends()) {
    r.add("bending", b, "Sauvage et al. §3: Σ|¼(c[i-1] - 2c[i] + c[i+1])|²", plain<Bending>());
    r.add("stretching", b, "Σ|c[i+1] - c[i]|² (first differences)", plain<Stretching>());
    r.add("attractor_distance", b, "Sauvage et al. §3: D = Σ|c[i] - a[i]|²", plain<AttractorDistance>());
  }
}

namespace {
Eigen::RowVector3d stencil_value(const CurveStencil& s, const MatrixX3& X, const MatrixX3& A) {
  Eigen::RowVector3d r = Eigen::RowVector3d::Zero();
  for (int j = 0; j < s.size; ++j) r += s.coeffs[j] * X.row(s.points[j]);
  if (s.attractor_point >= 0) r -= A.row(s.attractor_point);
  return r - s.constant.transpose();
}
}  // namespace

double stencil_energy(const std::vector<CurveStencil>& stencils, const MatrixX3& X, const MatrixX3& A) {
  double e = 0;
  for (const auto& s : stencils) e += stencil_value(s, X, A).squaredNorm();
  return e;
}

SparseMatrix stencil_hessian(const std::vector<CurveStencil>& stencils, int n) {
  Triplets t;
  for (const auto& s : stencils)
    for (int a = 0; a < s.size; ++a)
      for (int b = 0; b < s.size; ++b) t.emplace_back(s.points[a], s.points[b], 2 * s.coeffs[a] * s.coeffs[b]);
  SparseMatrix H(n, n);
  H.setFromTriplets(t.begin(), t.end());
  return H;
}

MatrixX3 stencil_linear_term(const std::vector<CurveStencil>& stencils, const MatrixX3& A) {
  MatrixX3 b = MatrixX3::Zero(A.rows(), 3);
  for (const auto& s : stencils) {
    Eigen::RowVector3d o = s.constant.transpose();
    if (s.attractor_point >= 0) o += A.row(s.attractor_point);
    if (o.isZero(0)) continue;
    for (int j = 0; j < s.size; ++j) b.row(s.points[j]) += 2 * s.coeffs[j] * o;
  }
  return b;
}

}  // namespace fairshape
