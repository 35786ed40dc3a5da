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

EditSolution solve_paper(const EditProblem& p, Solver& solver, Backend backend, const IterationCallback& cb,
                         const Eigen::MatrixXd* initial) {
  Timer setup;
  const SparseMatrix& A = p.constraints.A;
  std::vector<int> touched;  // vertices that appear in some constraint row
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
  const LeastSquaresResult ls = min_norm_least_squares(Ac, p.constraints.C, backend);

  ConstrainedSystem sys{p.H, p.g, touched, ls.X};
  const ReducedSystem red = reduce(sys);
  EditSolution out;
  out.constrained_vertices = static_cast<int>(touched.size());
  Eigen::MatrixXd x = initial ? red.restrict_to_free(*initial)
                              : Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(red.free.size()), p.g.cols());
  if (red.free.empty()) {
    out.summary = {Termination::Converged, 0, 0.0, "every vertex is constrained"};
  } else {
    if (solver.uses_levels()) {
      if (!p.levels) throw InvalidInput("edit: a multilevel solver needs a hierarchy below the edit level");
      // The solver sees the reduced system: its finest unknowns are the free vertices.
      solver.set_levels(p.levels, {red.free, static_cast<int>(p.H.rows() / p.levels->prolongation.back().rows())});
    }
    solver.analyze(red.A);
    out.analyze_s = setup.seconds();
    // Callers see the whole deformation, not the solver's reduced unknowns.
    // The reduced energy differs from the full one by a constant (the fixed vertices' part):
    // measured once, so a check costs no product with the full H.
    Eigen::MatrixXd full;
    std::optional<double> energy_offset;
    const IterationCallback expanded = [&](const IterationRecord& r) {
      full = red.expand(*r.x);
      if (!std::isnan(r.energy) && !energy_offset) energy_offset = quadratic_energy(p.H, p.g, full) - r.energy;
      return cb({r.iteration, r.residual, r.seconds, r.energy + energy_offset.value_or(0.0), &full});
    };
    Timer t;
    out.summary = solver.solve(red.A, red.b, x, cb ? expanded : IterationCallback());
    out.solve_s = t.seconds();
  }
  out.delta = red.expand(x);
  return out;
}

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
  s.constraints.C.resize(A.rows(), 1);
  s.constraints.C << stack(lc.C), lc.C_coupled;
  return s;
}

EditSolution solve_coupled(const EditProblem& p, ConstraintMode mode, Solver& solver, Backend backend,
                           const IterationCallback& cb, const Eigen::MatrixXd* initial) {
  const EditProblem s = stacked(p);
  Eigen::MatrixXd full;
  const IterationCallback unstacked = [&](const IterationRecord& r) {
    full = unstack(*r.x);
    return cb({r.iteration, r.residual, r.seconds, r.energy, &full});
  };
  const Eigen::MatrixXd start = initial ? Eigen::MatrixXd(stack(*initial)) : Eigen::MatrixXd();
  EditSolution out = mode == ConstraintMode::Kkt
                         ? solve_kkt(s, backend)
                         : solve_paper(s, solver, backend, cb ? unstacked : IterationCallback(), initial ? &start : nullptr);
  out.constraint_residual = (s.constraints.A * out.delta - s.constraints.C).norm();
  out.delta = unstack(out.delta);
  return out;
}

}  // namespace

EditSolution solve_edit(const EditProblem& p, ConstraintMode mode, Solver& free_solver, Backend backend,
                        const IterationCallback& cb, const Eigen::MatrixXd* initial) {
  if (p.constraints.A.rows() == 0)
    throw InvalidInput(p.constraints.coupled()
                           ? "edit: normal constraints fix no position: add a point or fixed constraint"
                           : "edit: no constraint: the deformation is undetermined (add a point or fixed constraint)");
  if (p.H.rows() != p.H.cols() || p.g.rows() != p.H.rows() || p.constraints.A.cols() != p.H.rows() ||
      (p.constraints.coupled() && p.constraints.A_coupled.cols() != 3 * p.H.rows()))
    throw InvalidInput("edit: H, g and the constraints disagree in size");
  if (p.constraints.coupled()) return solve_coupled(p, mode, free_solver, backend, cb, initial);
  EditSolution out =
      mode == ConstraintMode::Kkt ? solve_kkt(p, backend) : solve_paper(p, free_solver, backend, cb, initial);
  out.constraint_residual = (p.constraints.A * out.delta - p.constraints.C).norm();
  return out;
}

}  // namespace fairshape
