// Reference `cholesky`: Eigen's SimplicialLDLT, the plainest sparse direct solve.
#include <Eigen/SparseCholesky>

#include "problem/constrained_system.h"
#include "solver/solver.h"

namespace fairshape::reference {
namespace {

class SimplicialCholesky : public Solver {
 public:
  void analyze(const SparseMatrix& A) override {
    ldlt_.compute(A);
    rows_ = A.rows();
  }
  SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                     const IterationCallback&) override {
    if (rows_ != A.rows()) analyze(A);
    SolveSummary s;
    if (ldlt_.info() != Eigen::Success || (ldlt_.vectorD().array() <= 0).any()) {
      s.message = "LDLT: matrix is not positive definite (singular: is anything fixed?)";
      return s;
    }
    x = ldlt_.solve(b);
    s.iterations = 1;
    s.residual = relative_residual(A, b, x);
    s.termination = Termination::Converged;
    return s;
  }

 private:
  Eigen::SimplicialLDLT<SparseMatrix> ldlt_;
  Eigen::Index rows_ = -1;
};

}  // namespace

std::unique_ptr<Solver> make_simplicial_cholesky(Config&) { return std::make_unique<SimplicialCholesky>(); }

}  // namespace fairshape::reference
