// Optimized `cholesky`: CHOLMOD supernodal LLᵀ (SuiteSparse), factored once in analyze().
#include <Eigen/CholmodSupport>

#include "solver/solver.h"
#include "problem/constrained_system.h"

namespace fairshape {
namespace {

class CholmodCholesky : public Solver {
 public:
  void analyze(const SparseMatrix& A) override {
    llt_.compute(A);
    analyzed_rows_ = A.rows();
  }
  SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                     const IterationCallback&) override {
    if (analyzed_rows_ != A.rows()) analyze(A);
    SolveSummary s;
    if (llt_.info() != Eigen::Success) {
      s.message = "CHOLMOD: matrix is not positive definite (singular: is anything fixed?)";
      return s;
    }
    x = llt_.solve(b);
    s.iterations = 1;
    s.residual = relative_residual(A, b, x);
    s.termination = x.allFinite() ? Termination::Converged : Termination::NumericalFailure;
    if (!x.allFinite()) s.message = "CHOLMOD produced non-finite values";
    return s;
  }

 private:
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> llt_;
  Eigen::Index analyzed_rows_ = -1;
};

}  // namespace

std::unique_ptr<Solver> make_cholmod_cholesky(Config&) { return std::make_unique<CholmodCholesky>(); }

}  // namespace fairshape
