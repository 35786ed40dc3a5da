#include "fairshape/curve_design/length_problem.h"

#include <Eigen/SparseCholesky>
#include <cmath>

#include "fairshape/core/config.h"
#include "fairshape/core/error.h"

namespace fairshape {

LengthProblem::LengthProblem(MatrixX3 attractor, bool closed, std::vector<WeightedStencils> energies,
                             std::vector<std::unique_ptr<CurveConstraint>> constraints, Eigen::VectorXd reference_lengths)
    : attractor_(std::move(attractor)), closed_(closed), energies_(std::move(energies)),
      constraints_(std::move(constraints)), reference_lengths_(std::move(reference_lengths)) {
  if (!attractor_.allFinite()) throw InvalidInput("length problem: the attracting curve has a NaN or infinite point");
  for (const auto& c : constraints_) {
    if (const auto* s = dynamic_cast<const SegmentLengths*>(c.get())) {
      if (lengths_) throw InvalidInput("length problem: two segment-length constraints");
      lengths_ = s;
    }
    if (const auto* t = dynamic_cast<const TotalLength*>(c.get())) {
      if (total_) throw InvalidInput("length problem: two total-length constraints (keep one)");
      total_ = t;
    }
    dense_ |= c->has_dense_rows();
    n_rows_ += c->rows();
  }
  if (!lengths_ && !total_)
    throw InvalidInput("length problem: no length constraint (add {type: segment_lengths} or {type: total_length})");
  if (lengths_ && total_)
    throw InvalidInput("length problem: segment_lengths and total_length together: the total is the sum of the segments "
                       "(a dependent row); keep one");
  const int n = n_points();
  if (reference_lengths_.size() == 0 && lengths_) reference_lengths_ = lengths_->lengths();
  if (reference_lengths_.size() != (closed_ ? n : n - 1))
    throw InvalidInput("length problem: " + std::to_string(reference_lengths_.size()) + " reference lengths for a curve of " +
                       std::to_string(n) + " points");
  Q_.resize(n, n);
  b_ = MatrixX3::Zero(n, 3);
  for (const auto& e : energies_) {
    Q_ += e.weight * stencil_hessian(e.stencils, n);
    b_ += e.weight * stencil_linear_term(e.stencils, attractor_);
  }
  check_pins_reachable();
}

double LengthProblem::objective(const MatrixX3& X) const {
  double f = 0;
  for (const auto& e : energies_) f += e.weight * stencil_energy(e.stencils, X, attractor_);
  return f;
}

double LengthProblem::energy(const std::string& name, const MatrixX3& X) const {
  for (const auto& e : energies_)
    if (e.name == name) return stencil_energy(e.stencils, X, attractor_);
  return std::nan("");
}

std::vector<ConstraintRow> LengthProblem::rows(const MatrixX3& X) const {
  std::vector<ConstraintRow> out;
  out.reserve(n_rows_);
  for (const auto& c : constraints_)
    for (int r = 0; r < c->rows(); ++r) out.push_back(c->evaluate(r, X));
  return out;
}

void LengthProblem::add_constraint_hessians(const Eigen::VectorXd& scale, const MatrixX3& X, Triplets& out) const {
  int offset = 0;
  for (const auto& c : constraints_) {
    for (int r = 0; r < c->rows(); ++r) c->add_row_hessian(r, scale[offset + r], X, out);
    offset += c->rows();
  }
}

void LengthProblem::add_row_hessian(int row, double scale, const MatrixX3& X, Triplets& out) const {
  for (const auto& c : constraints_) {
    if (row < c->rows()) return c->add_row_hessian(row, scale, X, out);
    row -= c->rows();
  }
  FAIRSHAPE_ASSERT(false, "constraint row out of range");
}

bool LengthProblem::row_hessian_constant(int row) const {
  for (const auto& c : constraints_) {
    if (row < c->rows()) return c->constant_hessian();
    row -= c->rows();
  }
  FAIRSHAPE_ASSERT(false, "constraint row out of range");
  return true;
}

double LengthProblem::total_length_target() const { return total_ ? total_->target() : reference_lengths_.sum(); }

double LengthProblem::row_scale(int row) const {
  for (const auto& c : constraints_) {
    if (row < c->rows()) return c->row_scale(row);
    row -= c->rows();
  }
  FAIRSHAPE_ASSERT(false, "constraint row out of range");
  return 1;
}

double LengthProblem::max_relative_length_error(const MatrixX3& X) const {
  if (total_) return total_->length_error(X);
  const Eigen::VectorXd l = segment_lengths(X, closed_);
  return ((l - lengths_->lengths()).cwiseAbs().cwiseQuotient(lengths_->lengths())).maxCoeff();
}

double LengthProblem::max_relative_pin_error(const MatrixX3& X) const {
  double worst = 0;
  for (const auto& c : constraints_) worst = std::max(worst, c->relative_error(X, total_length_target()));
  return worst;
}

SparseMatrix constraint_jacobian(const std::vector<ConstraintRow>& rows, int n_points) {
  Triplets t;
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (int k = 0; k < rows[r].size; ++k) {
      const Vec3 g = rows[r].grad(k);
      for (int c = 0; c < 3; ++c)
        if (g[c] != 0) t.emplace_back(static_cast<int>(r), 3 * rows[r].point(k) + c, g[c]);
    }
  SparseMatrix J(static_cast<Eigen::Index>(rows.size()), 3 * n_points);
  J.setFromTriplets(t.begin(), t.end());
  return J;
}

double LengthProblem::stationarity(const MatrixX3& X) const {
  const SparseMatrix J = constraint_jacobian(rows(X), n_points());
  const MatrixX3 G = objective_gradient(X);
  const Eigen::Map<const Eigen::VectorXd> g(G.data(), G.size());  // row-major: interleaved
  // λ = argmin |g + Jᵀλ|: (J Jᵀ) λ = −J g, then the residual.
  const SparseMatrix JJt = J * J.transpose();
  Eigen::SimplicialLDLT<SparseMatrix> ldlt(JJt);
  if (ldlt.info() != Eigen::Success) return std::nan("");
  const Eigen::VectorXd lambda = ldlt.solve(-(J * g));
  const double scale = (Q_ * X).norm() + b_.norm();
  return (g + J.transpose() * lambda).norm() / std::max(scale, 1e-300);
}

// For consecutive pinned points p < q (and around a closed curve), |X_q − X_p| can be at
// most the length of the curve between them; with a total length only, the pins' polygon in
// curve order can be at most the total long.
void LengthProblem::check_pins_reachable() const {
  std::vector<std::pair<int, Vec3>> pins;
  for (const auto& c : constraints_)
    if (const auto* p = dynamic_cast<const PinnedPoints*>(c.get()))
      for (std::size_t k = 0; k < p->points().size(); ++k) pins.emplace_back(p->points()[k], p->targets().row(k).transpose());
  std::sort(pins.begin(), pins.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  if (total_) {
    double through = 0;
    const std::size_t gaps = closed_ && pins.size() > 1 ? pins.size() : pins.size() - std::min<std::size_t>(pins.size(), 1);
    for (std::size_t k = 0; k < gaps; ++k) {
      const auto& [p, xp] = pins[k];
      const auto& [q, xq] = pins[(k + 1) % pins.size()];
      if (p == q && (xp - xq).norm() > 0) throw InvalidInput("length problem: point " + std::to_string(p) + " is pinned at two places");
      through += (xq - xp).norm();
    }
    if (through > total_->target() * (1 + 1e-12))
      throw InvalidInput("infeasible edit: the held points are " + format_default(through) + " apart along the curve but its total "
                         "length is to be " + format_default(total_->target()) + "; no curve of that length passes through them "
                         "(ask a longer total_length value, or pin fewer points)");
    return;
  }
  const Eigen::VectorXd& l = lengths_->lengths();
  const auto arc = [&](int from, int to) {  // curve length from point `from` forward to `to`
    double s = 0;
    for (int i = from; i != to; i = (i + 1) % n_points()) s += l[i];
    return s;
  };
  const std::size_t checks = closed_ && pins.size() > 1 ? pins.size() : pins.size() - std::min<std::size_t>(pins.size(), 1);
  for (std::size_t k = 0; k < checks; ++k) {
    const auto& [p, xp] = pins[k];
    const auto& [q, xq] = pins[(k + 1) % pins.size()];
    if (p == q) {
      if ((xp - xq).norm() > 0) throw InvalidInput("length problem: point " + std::to_string(p) + " is pinned at two places");
      continue;
    }
    const double gap = (xq - xp).norm(), available = arc(p, q);
    if (gap > available * (1 + 1e-12))
      throw InvalidInput("infeasible edit: points " + std::to_string(p) + " and " + std::to_string(q) +
                         " are held " + format_default(gap) + " apart but the curve between them is only " +
                         format_default(available) + " long; no curve of the reference lengths reaches (move them "
                         "closer, or pin fewer points)");
  }
}

}  // namespace fairshape
