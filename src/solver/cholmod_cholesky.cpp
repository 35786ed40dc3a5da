// Optimized `cholesky`: CHOLMOD supernodal LLᵀ (SuiteSparse), factored in analyze() and again
// whenever a solve brings another matrix (solver.h); a new matrix with the analyzed pattern
// keeps the symbolic analysis (the fill-reducing ordering) and is only refactored.
#include <Eigen/CholmodSupport>

#include "fairshape/problem/constrained_system.h"
#include "fairshape/solver/matrix_fingerprint.h"
#include "fairshape/solver/solver.h"

namespace fairshape {
namespace {

class CholmodCholesky : public Solver {
 public:
  void analyze(const SparseMatrix& A) override { factor(A, MatrixFingerprint(A)); }
  SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                     const IterationCallback&) override {
    if (const MatrixFingerprint f(A); f != analyzed_.fingerprint()) factor(A, f);
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
  void factor(const SparseMatrix& A, const MatrixFingerprint& f) {
    if (!f.same_pattern(analyzed_.fingerprint())) llt_.analyzePattern(A);
    llt_.factorize(A);
    analyzed_.remember(f);
  }

  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> llt_;
  AnalyzedMatrix analyzed_;
};

}  // namespace

std::unique_ptr<Solver> make_cholmod_cholesky(Config&) { return std::make_unique<CholmodCholesky>(); }

}  // namespace fairshape
