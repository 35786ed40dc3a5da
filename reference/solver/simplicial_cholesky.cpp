// Reference `cholesky`: Eigen's SimplicialLDLT, the plainest sparse direct solve. Factored in
// analyze() and again whenever a solve brings another matrix (solver.h); a new matrix with the
// analyzed pattern keeps the symbolic analysis and is only refactored.
#include <Eigen/SparseCholesky>

#include "fairshape/problem/constrained_system.h"
#include "fairshape/solver/matrix_fingerprint.h"
#include "fairshape/solver/solver.h"

namespace fairshape::reference {
namespace {

class SimplicialCholesky : public Solver {
 public:
  void analyze(const SparseMatrix& A) override { factor(A, MatrixFingerprint(A)); }
  SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                     const IterationCallback&) override {
    if (const MatrixFingerprint f(A); f != analyzed_.fingerprint()) factor(A, f);
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
  void factor(const SparseMatrix& A, const MatrixFingerprint& f) {
    if (!f.same_pattern(analyzed_.fingerprint())) ldlt_.analyzePattern(A);
    ldlt_.factorize(A);
    analyzed_.remember(f);
  }

  Eigen::SimplicialLDLT<SparseMatrix> ldlt_;
  AnalyzedMatrix analyzed_;
};

}  // namespace

std::unique_ptr<Solver> make_simplicial_cholesky(Config&) { return std::make_unique<SimplicialCholesky>(); }

}  // namespace fairshape::reference
