#include "fairshape/curve_design/kkt_factor.h"

#include "fairshape/core/backend.h"
#if FAIRSHAPE_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#endif

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <Eigen/Dense>
#include <unsupported/Eigen/IterativeSolvers>
#include <algorithm>

namespace fairshape {
namespace {

#if FAIRSHAPE_WITH_TBB
int last_point(const ConstraintRow& r) { return r.size == 2 ? std::max(r.points[0], r.points[1]) : r.points[0]; }

constexpr int kDense = -1;  // position_ of a dense row's multiplier: outside the band
#endif

// Reference: a plain transcription, everything rebuilt every step (dense rows included as they
// are: SparseLU takes any pattern).
class BlockKkt final : public KktFactor {
 public:
  BlockKkt(const LengthProblem& p, KktMethod method, double tol) : p_(p), method_(method), tol_(tol) {}

  bool factor(const MatrixX3& X, const std::vector<ConstraintRow>& rows, const Eigen::VectorXd* newton, double shift) override {
    const int n = 3 * p_.n_points(), m = static_cast<int>(rows.size());
    Triplets t;
    if (shift != 0)
      for (int i = 0; i < n; ++i) t.emplace_back(i, i, shift);
    const SparseMatrix& Q = p_.objective_hessian();
    for (int j = 0; j < Q.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(Q, j); it; ++it)
        for (int c = 0; c < 3; ++c) t.emplace_back(3 * it.row() + c, 3 * j + c, it.value());
    if (newton) p_.add_constraint_hessians(*newton, X, t);
    for (int r = 0; r < m; ++r)
      for (int k = 0; k < rows[r].size; ++k) {
        const Vec3 g = rows[r].grad(k);
        for (int c = 0; c < 3; ++c) {
          t.emplace_back(n + r, 3 * rows[r].point(k) + c, g[c]);
          t.emplace_back(3 * rows[r].point(k) + c, n + r, g[c]);
        }
      }
    K_.resize(n + m, n + m);
    K_.setFromTriplets(t.begin(), t.end());
    if (method_ == KktMethod::Minres) {
      minres_.setTolerance(tol_);
      minres_.setMaxIterations(20 * (n + m));
      minres_.compute(K_);
      return minres_.info() == Eigen::Success;
    }
    K_.makeCompressed();
    lu_.analyzePattern(K_);
    lu_.factorize(K_);
    return lu_.info() == Eigen::Success;
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) override {
    return method_ == KktMethod::Minres ? Eigen::VectorXd(minres_.solve(rhs)) : Eigen::VectorXd(lu_.solve(rhs));
  }
  std::string last_error() const override { return method_ == KktMethod::Direct ? lu_.lastErrorMessage() : ""; }

 private:
  const LengthProblem& p_;
  KktMethod method_;
  double tol_;
  SparseMatrix K_;
  Eigen::SparseLU<SparseMatrix> lu_;
  Eigen::MINRES<SparseMatrix, Eigen::Lower | Eigen::Upper, Eigen::IdentityPreconditioner> minres_;
};

#if FAIRSHAPE_WITH_TBB  // the optimized back end
// Optimized: banded ordering, fixed pattern, value offsets computed once — for the rows'
// structure (which points each row touches): rows of another structure get a new pattern and
// symbolic analysis, never slots computed for other rows. Dense rows are bordered (kkt_factor.h).
class BandedKkt final : public KktFactor {
 public:
  BandedKkt(const LengthProblem& p, KktMethod method, double tol) : p_(p), method_(method), tol_(tol) {}

  bool factor(const MatrixX3& X, const std::vector<ConstraintRow>& rows, const Eigen::VectorXd* newton, double shift) override {
    if (K_.rows() == 0 || !same_structure(rows)) build_pattern(X, rows);
    double* v = K_.valuePtr();
    std::copy(base_.begin(), base_.end(), v);
    tbb::parallel_for(tbb::blocked_range<int>(0, static_cast<int>(rows.size()), 4096), [&](const auto& range) {
      for (int r = range.begin(); r != range.end(); ++r)
        if (!rows[r].dense)
          for (int k = 0; k < rows[r].size; ++k)
            for (int c = 0; c < 3; ++c) v[jacobian_slot_[6 * r + 3 * k + c]] += rows[r].gradient[k][c];
    });
    if (newton) {
      for (const auto& h : hessian_slots_) v[h.slot] += (*newton)[h.row] * h.coefficient;
      // Hessians that move with X (a total length's): re-read at X, same entries in the same order.
      for (const auto& vh : varying_hessians_) {
        Triplets at_x;
        p_.add_row_hessian(vh.row, (*newton)[vh.row], X, at_x);
        FAIRSHAPE_ASSERT(at_x.size() == vh.slots.size(), "a row's Hessian changed its pattern");
        for (std::size_t e = 0; e < at_x.size(); ++e)
          if (vh.slots[e] >= 0) v[vh.slots[e]] += at_x[e].value();
      }
    }
    if (shift != 0)
      for (int slot : point_diagonal_slot_) v[slot] += shift;
    bool ok = false;
    if (method_ == KktMethod::Minres) {
      minres_.setTolerance(tol_);
      minres_.setMaxIterations(20 * static_cast<int>(K_.rows()));
      minres_.compute(K_);
      ok = minres_.info() == Eigen::Success;
    } else {
      if (!analyzed_) {
        ldlt_.analyzePattern(K_);
        analyzed_ = true;
      }
      ldlt_.factorize(K_);
      ok = ldlt_.info() == Eigen::Success;
    }
    return ok && border(rows);
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) override {
    const int k = static_cast<int>(dense_rows_.size());
    Eigen::VectorXd b(K_.rows()), s(k);
    for (Eigen::Index i = 0; i < rhs.size(); ++i)
      if (position_[i] != kDense) b[position_[i]] = rhs[i];
    for (int d = 0; d < k; ++d) s[d] = rhs[3 * p_.n_points() + dense_rows_[d]];
    Eigen::VectorXd y, mu;
    bordered_solve(b, s, y, mu);
    if (method_ == KktMethod::Direct) {
      // The −δ on the multiplier diagonal keeps LDLᵀ without pivoting stable; one step of
      // refinement against the exact (bordered) system removes its O(δ) error.
      Eigen::VectorXd dy, dmu;
      const Eigen::VectorXd rb = b - exact_product(y) - (k ? Eigen::VectorXd(B_ * mu) : Eigen::VectorXd::Zero(b.size()));
      const Eigen::VectorXd rs = k ? Eigen::VectorXd(s - B_.transpose() * y) : Eigen::VectorXd();
      bordered_solve(rb, rs, dy, dmu);
      y += dy;
      mu += dmu;
    }
    Eigen::VectorXd x(rhs.size());
    for (Eigen::Index i = 0; i < rhs.size(); ++i)
      if (position_[i] != kDense) x[i] = y[position_[i]];
    for (int d = 0; d < k; ++d) x[3 * p_.n_points() + dense_rows_[d]] = mu[d];
    return x;
  }

  int negative_pivots() const override {
    if (method_ != KktMethod::Direct || !analyzed_ || ldlt_.info() != Eigen::Success) return -1;
    // Haynsworth: inertia(K) = inertia(A) + inertia(S), S = −Bᵀ A⁻¹ B the Schur complement.
    return static_cast<int>((ldlt_.vectorD().array() < 0).count()) + schur_negative_;
  }

 private:
  struct HessianSlot {
    int slot, row;
    double coefficient;
  };
  struct VaryingHessian {
    int row;
    std::vector<int> slots;  // one per entry add_row_hessian emits; −1: the upper triangle's copy
  };

  Eigen::VectorXd inner_solve(const Eigen::VectorXd& b) const {
    return method_ == KktMethod::Minres ? Eigen::VectorXd(minres_.solve(b)) : Eigen::VectorXd(ldlt_.solve(b));
  }

  // [A B; Bᵀ 0][y; μ] = [b; s]: y = u − Vμ with u = A⁻¹b, μ = (BᵀV)⁻¹(Bᵀu − s).
  void bordered_solve(const Eigen::VectorXd& b, const Eigen::VectorXd& s, Eigen::VectorXd& y, Eigen::VectorXd& mu) const {
    y = inner_solve(b);
    if (dense_rows_.empty()) {
      mu.resize(0);
      return;
    }
    mu = btv_lu_.solve(B_.transpose() * y - s);
    y -= V_ * mu;
  }

  // After A's factorization: V = A⁻¹B, BᵀV and the Schur complement's inertia.
  bool border(const std::vector<ConstraintRow>& rows) {
    schur_negative_ = 0;
    const int k = static_cast<int>(dense_rows_.size());
    if (k == 0) return true;
    B_.setZero(K_.rows(), k);
    for (int d = 0; d < k; ++d) {
      const ConstraintRow& r = rows[static_cast<std::size_t>(dense_rows_[d])];
      for (int i = 0; i < r.size; ++i)
        for (int c = 0; c < 3; ++c) B_(position_[3 * i + c], d) = r.dense_gradient(i, c);
    }
    V_.resize(K_.rows(), k);
    for (int d = 0; d < k; ++d) V_.col(d) = inner_solve(B_.col(d));
    if (!V_.allFinite()) return false;
    Eigen::MatrixXd btv = B_.transpose() * V_;
    btv = 0.5 * (btv + btv.transpose());
    btv_lu_.compute(btv);
    if (!(std::abs(btv_lu_.determinant()) > 0)) return false;  // the dense rows depend on the others
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(-btv, Eigen::EigenvaluesOnly);
    schur_negative_ = static_cast<int>((eig.eigenvalues().array() < 0).count());
    return true;
  }

  Eigen::VectorXd exact_product(const Eigen::VectorXd& y) const {
    Eigen::VectorXd out = K_.selfadjointView<Eigen::Lower>() * y;
    for (int r : multiplier_position_) out[r] += delta_ * y[r];  // undo the regularization
    return out;
  }

  // Row sizes and points, three entries a row (an unused second point is 0, as ConstraintRow
  // has it; a dense row is −1 and its size).
  static std::vector<int> structure_of(const std::vector<ConstraintRow>& rows) {
    std::vector<int> out;
    out.reserve(3 * rows.size());
    for (const auto& r : rows)
      if (r.dense) out.insert(out.end(), {-1, r.size, 0});
      else out.insert(out.end(), {r.size, r.points[0], r.size == 2 ? r.points[1] : 0});
    return out;
  }
  bool same_structure(const std::vector<ConstraintRow>& rows) const { return structure_of(rows) == structure_; }

  void build_pattern(const MatrixX3& X, const std::vector<ConstraintRow>& rows) {
    const int np = p_.n_points(), n = 3 * np, m = static_cast<int>(rows.size());
    structure_ = structure_of(rows);
    multiplier_position_.clear();
    hessian_slots_.clear();
    varying_hessians_.clear();
    dense_rows_.clear();
    analyzed_ = false;
    // Position of every natural unknown: point p's coordinates, then the rows ending at p;
    // dense rows stay outside the band (bordered).
    std::vector<std::vector<int>> rows_ending_at(np);
    for (int r = 0; r < m; ++r)
      if (rows[r].dense) dense_rows_.push_back(r);
      else rows_ending_at[last_point(rows[r])].push_back(r);
    position_.assign(n + m, kDense);
    int next = 0;
    for (int q = 0; q < np; ++q) {
      for (int c = 0; c < 3; ++c) position_[3 * q + c] = next++;
      for (int r : rows_ending_at[q]) position_[n + r] = next++;
    }
    const auto lower = [&](int i, int j, double v) {
      const int a = position_[i], b = position_[j];
      return Triplet(std::max(a, b), std::min(a, b), v);
    };
    Triplets t;
    const SparseMatrix& Q = p_.objective_hessian();
    for (int j = 0; j < Q.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(Q, j); it; ++it)
        if (it.row() >= j)
          for (int c = 0; c < 3; ++c) t.push_back(lower(3 * static_cast<int>(it.row()) + c, 3 * j + c, it.value()));
    Triplets hess;
    p_.add_constraint_hessians(Eigen::VectorXd::Ones(m), X, hess);
    for (const auto& h : hess)
      if (h.row() >= h.col()) t.push_back(lower(h.row(), h.col(), 0.0));  // structural: Newton fills it
    double scale = 0;
    for (const auto& e : t) scale = std::max(scale, std::abs(e.value()));
    delta_ = 1e-14 * std::max(scale, 1e-300);
    for (int r = 0; r < m; ++r) {
      if (rows[r].dense) continue;
      multiplier_position_.push_back(position_[n + r]);
      t.emplace_back(position_[n + r], position_[n + r], -delta_);
      for (int k = 0; k < rows[r].size; ++k)
        for (int c = 0; c < 3; ++c) t.push_back(lower(n + r, 3 * rows[r].points[k] + c, 0.0));
    }
    const int band = next;
    K_.resize(band, band);
    K_.setFromTriplets(t.begin(), t.end());
    K_.makeCompressed();
    base_.assign(K_.valuePtr(), K_.valuePtr() + K_.nonZeros());
    jacobian_slot_.assign(6 * m, 0);
    for (int r = 0; r < m; ++r)
      if (!rows[r].dense)
        for (int k = 0; k < rows[r].size; ++k)
          for (int c = 0; c < 3; ++c) jacobian_slot_[6 * r + 3 * k + c] = slot(n + r, 3 * rows[r].points[k] + c);
    point_diagonal_slot_.clear();
    for (int i = 0; i < n; ++i) point_diagonal_slot_.push_back(slot(i, i));
    for (int r = 0; r < m; ++r) {
      Triplets one;
      p_.add_row_hessian(r, 1.0, X, one);
      if (!p_.row_hessian_constant(r)) {
        VaryingHessian vh{r, {}};
        for (const auto& h : one) vh.slots.push_back(h.row() >= h.col() ? slot(h.row(), h.col()) : -1);
        varying_hessians_.push_back(std::move(vh));
        continue;
      }
      for (const auto& h : one)
        if (h.value() != 0 && h.row() >= h.col()) hessian_slots_.push_back({slot(h.row(), h.col()), r, h.value()});
    }
  }

  int slot(int natural_i, int natural_j) const {
    const int a = std::max(position_[natural_i], position_[natural_j]), b = std::min(position_[natural_i], position_[natural_j]);
    const int* begin = K_.innerIndexPtr() + K_.outerIndexPtr()[b];
    const int* end = K_.innerIndexPtr() + K_.outerIndexPtr()[b + 1];
    const int* it = std::lower_bound(begin, end, a);
    FAIRSHAPE_ASSERT(it != end && *it == a, "KKT pattern misses an entry");
    return static_cast<int>(it - K_.innerIndexPtr());
  }

  const LengthProblem& p_;
  KktMethod method_;
  double tol_, delta_ = 0;
  SparseMatrix K_;  // lower triangle of A (the sparse rows), banded order
  std::vector<double> base_;
  std::vector<int> position_, jacobian_slot_, multiplier_position_, point_diagonal_slot_;
  std::vector<HessianSlot> hessian_slots_;
  std::vector<VaryingHessian> varying_hessians_;
  std::vector<int> structure_;  // structure_of the rows the pattern was built for
  std::vector<int> dense_rows_;  // natural indices of the bordered rows
  Eigen::MatrixXd B_, V_;        // their gradients in banded order, and A⁻¹B
  Eigen::PartialPivLU<Eigen::MatrixXd> btv_lu_;
  int schur_negative_ = 0;
  bool analyzed_ = false;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt_;
  Eigen::MINRES<SparseMatrix, Eigen::Lower, Eigen::IdentityPreconditioner> minres_;
};
#endif

}  // namespace

std::unique_ptr<KktFactor> make_kkt_factor(const LengthProblem& p, Backend backend, KktMethod method, double tol) {
  require_backend(backend);
#if FAIRSHAPE_WITH_TBB
  if (backend == Backend::Reference) return std::make_unique<BlockKkt>(p, method, tol);
  return std::make_unique<BandedKkt>(p, method, tol);
#else
  return std::make_unique<BlockKkt>(p, method, tol);
#endif
}

}  // namespace fairshape
