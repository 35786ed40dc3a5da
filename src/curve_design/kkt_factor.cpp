#include "fairshape/curve_design/kkt_factor.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <unsupported/Eigen/IterativeSolvers>
#include <algorithm>

namespace fairshape {
namespace {

int last_point(const ConstraintRow& r) { return r.size == 2 ? std::max(r.points[0], r.points[1]) : r.points[0]; }

// Reference: a plain transcription, everything rebuilt every step.
class BlockKkt final : public KktFactor {
 public:
  BlockKkt(const LengthProblem& p, KktMethod method, double tol) : p_(p), method_(method), tol_(tol) {}

  bool factor(const std::vector<ConstraintRow>& rows, const Eigen::VectorXd* newton, double shift) override {
    const int n = 3 * p_.n_points(), m = static_cast<int>(rows.size());
    Triplets t;
    if (shift != 0)
      for (int i = 0; i < n; ++i) t.emplace_back(i, i, shift);
    const SparseMatrix& Q = p_.objective_hessian();
    for (int j = 0; j < Q.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(Q, j); it; ++it)
        for (int c = 0; c < 3; ++c) t.emplace_back(3 * it.row() + c, 3 * j + c, it.value());
    if (newton) p_.add_constraint_hessians(*newton, t);
    for (int r = 0; r < m; ++r)
      for (int k = 0; k < rows[r].size; ++k)
        for (int c = 0; c < 3; ++c) {
          t.emplace_back(n + r, 3 * rows[r].points[k] + c, rows[r].gradient[k][c]);
          t.emplace_back(3 * rows[r].points[k] + c, n + r, rows[r].gradient[k][c]);
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

// Optimized: banded ordering, fixed pattern, value offsets computed once — for the rows'
// structure (which points each row touches): rows of another structure get a new pattern and
// symbolic analysis, never slots computed for other rows.
class BandedKkt final : public KktFactor {
 public:
  BandedKkt(const LengthProblem& p, KktMethod method, double tol) : p_(p), method_(method), tol_(tol) {}

  bool factor(const std::vector<ConstraintRow>& rows, const Eigen::VectorXd* newton, double shift) override {
    if (K_.rows() == 0 || !same_structure(rows)) build_pattern(rows);
    double* v = K_.valuePtr();
    std::copy(base_.begin(), base_.end(), v);
    tbb::parallel_for(tbb::blocked_range<int>(0, static_cast<int>(rows.size()), 4096), [&](const auto& range) {
      for (int r = range.begin(); r != range.end(); ++r)
        for (int k = 0; k < rows[r].size; ++k)
          for (int c = 0; c < 3; ++c) v[jacobian_slot_[6 * r + 3 * k + c]] += rows[r].gradient[k][c];
    });
    if (newton)
      for (const auto& h : hessian_slots_) v[h.slot] += (*newton)[h.row] * h.coefficient;
    if (shift != 0)
      for (int slot : point_diagonal_slot_) v[slot] += shift;
    if (method_ == KktMethod::Minres) {
      minres_.setTolerance(tol_);
      minres_.setMaxIterations(20 * static_cast<int>(K_.rows()));
      minres_.compute(K_);
      return minres_.info() == Eigen::Success;
    }
    if (!analyzed_) {
      ldlt_.analyzePattern(K_);
      analyzed_ = true;
    }
    ldlt_.factorize(K_);
    return ldlt_.info() == Eigen::Success;
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) override {
    Eigen::VectorXd b(rhs.size());
    for (Eigen::Index i = 0; i < rhs.size(); ++i) b[position_[i]] = rhs[i];
    Eigen::VectorXd y;
    if (method_ == KktMethod::Minres) {
      y = minres_.solve(b);
    } else {
      // The −δ on the multiplier diagonal keeps LDLᵀ without pivoting stable; one step of
      // refinement against the exact system removes its O(δ) error.
      y = ldlt_.solve(b);
      const Eigen::VectorXd r = b - exact_product(y);
      y += ldlt_.solve(r);
    }
    Eigen::VectorXd x(rhs.size());
    for (Eigen::Index i = 0; i < rhs.size(); ++i) x[i] = y[position_[i]];
    return x;
  }

  int negative_pivots() const override {
    if (method_ != KktMethod::Direct || !analyzed_ || ldlt_.info() != Eigen::Success) return -1;
    return static_cast<int>((ldlt_.vectorD().array() < 0).count());
  }

 private:
  struct HessianSlot {
    int slot, row;
    double coefficient;
  };

  Eigen::VectorXd exact_product(const Eigen::VectorXd& y) const {
    Eigen::VectorXd out = K_.selfadjointView<Eigen::Lower>() * y;
    for (int r : multiplier_position_) out[r] += delta_ * y[r];  // undo the regularization
    return out;
  }

  // Row sizes and points, three entries a row (an unused second point is 0, as ConstraintRow has it).
  static std::vector<int> structure_of(const std::vector<ConstraintRow>& rows) {
    std::vector<int> out;
    out.reserve(3 * rows.size());
    for (const auto& r : rows) out.insert(out.end(), {r.size, r.points[0], r.size == 2 ? r.points[1] : 0});
    return out;
  }
  bool same_structure(const std::vector<ConstraintRow>& rows) const { return structure_of(rows) == structure_; }

  void build_pattern(const std::vector<ConstraintRow>& rows) {
    const int np = p_.n_points(), n = 3 * np, m = static_cast<int>(rows.size());
    structure_ = structure_of(rows);
    multiplier_position_.clear();
    hessian_slots_.clear();
    analyzed_ = false;
    // Position of every natural unknown: point p's coordinates, then the rows ending at p.
    std::vector<std::vector<int>> rows_ending_at(np);
    for (int r = 0; r < m; ++r) rows_ending_at[last_point(rows[r])].push_back(r);
    position_.assign(n + m, 0);
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
    p_.add_constraint_hessians(Eigen::VectorXd::Ones(m), hess);
    for (const auto& h : hess)
      if (h.row() >= h.col()) t.push_back(lower(h.row(), h.col(), 0.0));  // structural: Newton fills it
    double scale = 0;
    for (const auto& e : t) scale = std::max(scale, std::abs(e.value()));
    delta_ = 1e-14 * std::max(scale, 1e-300);
    for (int r = 0; r < m; ++r) {
      multiplier_position_.push_back(position_[n + r]);
      t.emplace_back(position_[n + r], position_[n + r], -delta_);
      for (int k = 0; k < rows[r].size; ++k)
        for (int c = 0; c < 3; ++c) t.push_back(lower(n + r, 3 * rows[r].points[k] + c, 0.0));
    }
    K_.resize(n + m, n + m);
    K_.setFromTriplets(t.begin(), t.end());
    K_.makeCompressed();
    base_.assign(K_.valuePtr(), K_.valuePtr() + K_.nonZeros());
    jacobian_slot_.assign(6 * m, 0);
    for (int r = 0; r < m; ++r)
      for (int k = 0; k < rows[r].size; ++k)
        for (int c = 0; c < 3; ++c) jacobian_slot_[6 * r + 3 * k + c] = slot(n + r, 3 * rows[r].points[k] + c);
    point_diagonal_slot_.clear();
    for (int i = 0; i < n; ++i) point_diagonal_slot_.push_back(slot(i, i));
    for (int r = 0; r < m; ++r) {
      Triplets one;
      p_.add_row_hessian(r, 1.0, one);
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
  SparseMatrix K_;  // lower triangle, banded order
  std::vector<double> base_;
  std::vector<int> position_, jacobian_slot_, multiplier_position_, point_diagonal_slot_;
  std::vector<HessianSlot> hessian_slots_;
  std::vector<int> structure_;  // structure_of the rows the pattern was built for
  bool analyzed_ = false;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::NaturalOrdering<int>> ldlt_;
  Eigen::MINRES<SparseMatrix, Eigen::Lower, Eigen::IdentityPreconditioner> minres_;
};

}  // namespace

std::unique_ptr<KktFactor> make_kkt_factor(const LengthProblem& p, Backend backend, KktMethod method, double tol) {
  if (backend == Backend::Reference) return std::make_unique<BlockKkt>(p, method, tol);
  return std::make_unique<BandedKkt>(p, method, tol);
}

}  // namespace fairshape
