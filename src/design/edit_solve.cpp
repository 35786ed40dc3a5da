#include "design/edit_solve.h"

#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>

#include <cmath>

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
                              : Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(red.free.size()), 3);
  if (red.free.empty()) {
    out.summary = {Termination::Converged, 0, 0.0, "every vertex is constrained"};
  } else {
    solver.analyze(red.A);
    out.analyze_s = setup.seconds();
    // Callers see the whole deformation, not the solver's reduced unknowns.
    Eigen::MatrixXd full;
    const IterationCallback expanded = [&](const IterationRecord& r) {
      full = red.expand(*r.x);
      const double energy = std::isnan(r.energy) ? r.energy : quadratic_energy(p.H, p.g, full);
      return cb({r.iteration, r.residual, r.seconds, energy, &full});
    };
    Timer t;
    out.summary = solver.solve(red.A, red.b, x, cb ? expanded : IterationCallback());
    out.solve_s = t.seconds();
  }
  out.delta = red.expand(x);
  return out;
}

EditSolution solve_kkt(const EditProblem& p, Backend backend) {
  Timer setup;
  const SparseMatrix& A = p.constraints.A;
  const Eigen::Index n = p.H.rows(), m = A.rows();
  Triplets t;
  for (int c = 0; c < p.H.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(p.H, c); it; ++it) t.emplace_back(static_cast<int>(it.row()), c, it.value());
  for (int c = 0; c < A.outerSize(); ++c)
    for (SparseMatrix::InnerIterator it(A, c); it; ++it) {
      t.emplace_back(static_cast<int>(n + it.row()), c, it.value());
      t.emplace_back(c, static_cast<int>(n + it.row()), it.value());
    }
  SparseMatrix K(n + m, n + m);
  K.setFromTriplets(t.begin(), t.end());
  Eigen::MatrixXd rhs(n + m, 3);
  rhs.topRows(n) = p.g;
  rhs.bottomRows(m) = p.constraints.C;
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
  if (!ok || !sol.allFinite()) {
    out.summary.message = "KKT system is singular (dependent constraints, or nothing pins the deformation)";
    out.delta = Eigen::MatrixXd::Zero(n, 3);
    return out;
  }
  out.delta = sol.topRows(n);
  out.summary = {Termination::Converged, 1, relative_residual(K, rhs, sol), ""};
  out.constrained_vertices = static_cast<int>(m);
  return out;
}

}  // namespace

EditSolution solve_edit(const EditProblem& p, ConstraintMode mode, Solver& free_solver, Backend backend,
                        const IterationCallback& cb, const Eigen::MatrixXd* initial) {
  if (p.constraints.A.rows() == 0)
    throw InvalidInput("edit: no constraint: the deformation is undetermined (add a point or fixed constraint)");
  if (p.H.rows() != p.H.cols() || p.g.rows() != p.H.rows() || p.constraints.A.cols() != p.H.rows())
    throw InvalidInput("edit: H, g and the constraints disagree in size");
  EditSolution out =
      mode == ConstraintMode::Kkt ? solve_kkt(p, backend) : solve_paper(p, free_solver, backend, cb, initial);
  out.constraint_residual = (p.constraints.A * out.delta - p.constraints.C).norm();
  return out;
}

}  // namespace fairshape
