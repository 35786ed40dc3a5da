#include "design/edit_solve.h"

#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>

#include <cmath>
#include <optional>

#include "core/timer.h"
#include "problem/constrained_system.h"
#include "problem/least_squares.h"

namespace fairshape {
namespace {

EditSolution kkt_once(const EditProblem& p, Backend backend) {
  Timer setup;
  const SparseMatrix& A = p.constraints.A;
  const Eigen::Index n = p.H.rows(), m = A.rows();
  // Constraint rows scaled to H's size: on remeshed levels H's diagonal spans 1e8..1e14, and
  // an unscaled [H Aᵀ; A 0] loses most digits in the LU. (λ is scaled too; it is not used.)
  const double diag_max = p.H.diagonal().cwiseAbs().maxCoeff();
  const double s = diag_max > 0 ? diag_max : 1.0;
  Triplets t;
  for (int c = 0; c < p.H.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(p.H, c); it; ++it) t.emplace_back(static_cast<int>(it.row()), c, it.value());
  for (int c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) {
      t.emplace_back(static_cast<int>(n + it.row()), c, s * it.value());
      t.emplace_back(c, static_cast<int>(n + it.row()), s * it.value());
    }
  SparseMatrix K(n + m, n + m);
  K.setFromTriplets(t.begin(), t.end());
  Eigen::MatrixXd rhs(n + m, p.g.cols());
  rhs.topRows(n) = p.g;
  rhs.bottomRows(m) = s * p.constraints.C;
  EditSolution out;
  Eigen::MatrixXd sol;
  bool ok = false;
  auto factor_and_solve = [&](auto& lu) {
    lu.compute(K);
    ok = lu.info() == Eigen::Success;
    out.analyze_s = setup.seconds();
    Timer t;
    if (ok) sol = lu.solve(rhs);
    out.solve_s = t.seconds();
  };
  if (backend == Backend::Reference) {
    Eigen::SparseLU<SparseMatrix> lu;
    factor_and_solve(lu);
  } else {
    Eigen::UmfPackLU<SparseMatrix> lu;
    factor_and_solve(lu);
  }
  // UMFPACK can "succeed" on a numerically singular K and return huge values: check the residual.
  const double residual = ok && sol.allFinite() ? relative_residual(K, rhs, sol) : 0.0;
  if (!ok || !sol.allFinite() || residual > 1e-6) {
    out.summary.message = "KKT system is singular (nothing pins the deformation?)";
    out.delta = Eigen::MatrixXd::Zero(n, p.g.cols());
    return out;
  }
  out.delta = sol.topRows(n);
  out.summary = {Termination::Converged, 1, residual, ""};
  out.constrained_vertices = static_cast<int>(m);
  return out;
}

// Dependent rows (a fixed region propagated to a coarser level) make K singular: keep a
// maximal independent set (rank-revealing sparse QR) and say how many rows were dropped; if
// the dropped rows disagree with the kept ones, constraint_residual shows it.
EditSolution solve_kkt(const EditProblem& p, Backend backend) {
  EditSolution out = kkt_once(p, backend);
  if (out.summary.termination == Termination::Converged) return out;
  Timer t;
  const std::vector<int> keep = independent_rows(p.constraints.A, backend);
  if (keep.size() == static_cast<std::size_t>(p.constraints.A.rows())) return out;
  const SparseMatrix pick_t = row_picker(p.constraints.A.rows(), keep).transpose();
  EditProblem reduced{p.H, p.g, {}, nullptr};
  reduced.constraints.A = pick_t * p.constraints.A;
  reduced.constraints.C = pick_t * p.constraints.C;
  const double qr_s = t.seconds();
  out = kkt_once(reduced, backend);
  out.analyze_s += qr_s;
  const std::string dropped = std::to_string(p.constraints.A.rows() - static_cast<Eigen::Index>(keep.size()));
  out.summary.message = out.summary.message.empty() ? "dropped " + dropped + " dependent constraint rows"
                                                    : out.summary.message.append(" after dropping ").append(dropped).append(" dependent constraint rows");
  return out;
}

// Columns x, y, z stacked into one: an n × 3 matrix is, column-major, already [x; y; z].
Eigen::VectorXd stack(const Eigen::MatrixXd& M) { return Eigen::Map<const Eigen::VectorXd>(M.data(), M.size()); }
Eigen::MatrixXd unstack(const Eigen::MatrixXd& v) { return Eigen::Map<const Eigen::MatrixXd>(v.data(), v.size() / 3, 3); }

// The one coupled system of §5 on [Δx; Δy; Δz]: H three times on the diagonal, each point
// row three times, then the normal rows.
EditProblem stacked(const EditProblem& p) {
  const LinearConstraints& lc = p.constraints;
  EditProblem s;
  s.levels = p.levels;
  s.H = block_diagonal(p.H, 3);
  s.g = stack(p.g);
  const SparseMatrix A3 = block_diagonal(lc.A, 3);
  SparseMatrix A(A3.rows() + lc.A_coupled.rows(), A3.cols());
  Triplets t;
  for (const SparseMatrix* part : {&A3, &lc.A_coupled})
    for (int c = 0; c < part->outerSize(); ++c)
      for (SparseMatrix::InnerIterator it(*part, c); it; ++it)
        t.emplace_back(static_cast<int>(it.row() + (part == &A3 ? 0 : A3.rows())), c, it.value());
  A.setFromTriplets(t.begin(), t.end());
  s.constraints.A = A;
  s.constraints.C = stacked_targets(lc, lc.C);
  return s;
}

void check_sizes(const EditProblem& p) {
  if (p.constraints.A.rows() == 0)
    throw InvalidInput(p.constraints.coupled()
                           ? "edit: normal constraints fix no position: add a point or fixed constraint"
                           : "edit: no constraint: the deformation is undetermined (add a point or fixed constraint)");
  if (p.H.rows() != p.H.cols() || p.g.rows() != p.H.rows() || p.constraints.A.cols() != p.H.rows() ||
      (p.constraints.coupled() && p.constraints.A_coupled.cols() != 3 * p.H.rows()))
    throw InvalidInput("edit: H, g and the constraints disagree in size");
}

// The vertices some constraint row touches, and A restricted to them.
SparseMatrix touched_columns(const SparseMatrix& A, std::vector<int>& touched) {
  std::vector<int> column_of(A.cols(), -1);
  for (int c = 0; c < A.outerSize(); ++c)
    if (SparseMatrix::InnerIterator(A, c)) {
      column_of[c] = static_cast<int>(touched.size());
      touched.push_back(c);
    }
  Triplets t;
  for (int c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) t.emplace_back(static_cast<int>(it.row()), column_of[c], it.value());
  SparseMatrix Ac(A.rows(), static_cast<Eigen::Index>(touched.size()));
  Ac.setFromTriplets(t.begin(), t.end());
  return Ac;
}

}  // namespace

Eigen::MatrixXd stacked_targets(const LinearConstraints& lc, const Eigen::MatrixXd& C) {
  Eigen::MatrixXd out(3 * C.rows() + lc.C_coupled.rows(), 1);
  out << stack(C), lc.C_coupled;
  return out;
}

PreparedEdit::PreparedEdit(const EditProblem& p, Solver& solver, Backend backend) : solver_(solver) {
  Timer setup;
  check_sizes(p);
  original_ = &p;
  if (p.constraints.coupled()) stacked_ = stacked(p);
  const EditProblem& s = solved();
  ls_ = std::make_unique<MinNormLeastSquares>(touched_columns(s.constraints.A, touched_), backend);
  red_ = reduce({s.H, s.g, touched_, Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(touched_.size()), s.g.cols())});
  if (!red_.free.empty()) {
    if (solver.uses_levels()) {
      if (!s.levels) throw InvalidInput("edit: a multilevel solver needs a hierarchy below the edit level");
      // The solver sees the reduced system: its finest unknowns are the free vertices.
      solver.set_levels(s.levels, {red_.free, static_cast<int>(s.H.rows() / s.levels->prolongation.back().rows())});
    }
    solver.analyze(red_.A);
  }
  analyze_s_ = setup.seconds();
}

PreparedEdit::~PreparedEdit() = default;

EditSolution PreparedEdit::solve(const Eigen::MatrixXd& C, const IterationCallback& cb, const Eigen::MatrixXd* initial) {
  const EditProblem& s = solved();
  const bool coupled = stacked_.has_value();
  const Eigen::MatrixXd targets = coupled ? stacked_targets(original_->constraints, C) : C;
  red_.set_fixed_values(ls_->solve(targets).X);
  EditSolution out;
  out.analyze_s = analyze_s_;
  out.constrained_vertices = static_cast<int>(touched_.size());
  const Eigen::MatrixXd start = initial ? (coupled ? Eigen::MatrixXd(stack(*initial)) : *initial) : Eigen::MatrixXd();
  Eigen::MatrixXd x = initial ? red_.restrict_to_free(start)
                              : Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(red_.free.size()), s.g.cols());
  if (red_.free.empty()) {
    out.summary = {Termination::Converged, 0, 0.0, "every vertex is constrained"};
  } else {
    // Callers see the whole n × 3 deformation, not the solver's reduced unknowns. The
    // reduced energy differs from the full one by a constant (the fixed vertices' part):
    // measured once, so a check costs no product with the full H.
    Eigen::MatrixXd full;
    std::optional<double> energy_offset;
    const IterationCallback expanded = [&](const IterationRecord& r) {
      full = red_.expand(*r.x);
      if (coupled) full = unstack(full);
      if (!std::isnan(r.energy) && !energy_offset)
        energy_offset = quadratic_energy(original_->H, original_->g, full) - r.energy;
      return cb({r.iteration, r.residual, r.seconds, r.energy + energy_offset.value_or(0.0), &full});
    };
    Timer t;
    out.summary = solver_.solve(red_.A, red_.b, x, cb ? expanded : IterationCallback());
    out.solve_s = t.seconds();
  }
  out.delta = red_.expand(x);
  out.constraint_residual = (s.constraints.A * out.delta - targets).norm();
  if (coupled) out.delta = unstack(out.delta);
  return out;
}

EditSolution solve_edit(const EditProblem& p, ConstraintMode mode, Solver& free_solver, Backend backend,
                        const IterationCallback& cb, const Eigen::MatrixXd* initial) {
  if (mode == ConstraintMode::Paper) return PreparedEdit(p, free_solver, backend).solve(p.constraints.C, cb, initial);
  check_sizes(p);
  if (!p.constraints.coupled()) {
    EditSolution out = solve_kkt(p, backend);
    out.constraint_residual = (p.constraints.A * out.delta - p.constraints.C).norm();
    return out;
  }
  const EditProblem s = stacked(p);
  EditSolution out = solve_kkt(s, backend);
  out.constraint_residual = (s.constraints.A * out.delta - s.constraints.C).norm();
  out.delta = unstack(out.delta);
  return out;
}

}  // namespace fairshape
