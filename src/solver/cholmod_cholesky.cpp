// Optimized `cholesky`: CHOLMOD supernodal LLᵀ (SuiteSparse), factored in analyze() and again
// whenever a solve brings another matrix (solver.h); a new matrix with the analyzed pattern
// keeps the symbolic analysis (the fill-reducing ordering) and is only refactored.
// Before factoring, the symbolic analysis's own count of the factor's entries is checked against
// the memory the machine has left: a factor that cannot fit ends `out_of_memory` naming both
// sizes, instead of the kernel killing the run part-way. (Its own symbolic analysis must fit
// first: at level 6 of the cow, 11.8M unknowns beside a 17 GB set-up, it did not.)
#include <Eigen/CholmodSupport>

#include <cmath>
#include <sstream>

#include "fairshape/core/memory.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/solver/matrix_fingerprint.h"
#include "fairshape/solver/solver.h"

namespace fairshape {
namespace {

// Eigen keeps CHOLMOD's factor to itself; the symbolic one holds the sizes the numeric
// factorization will allocate.
class InspectableLLT : public Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> {
 public:
  const cholmod_factor* factor() const { return m_cholmodFactor; }
  double lnz() { return cholmod().lnz; }  // entries of L (the simplicial count)
};

// MiB the numeric factorization will hold beyond A: the supernodal values (xsize doubles) and
// row indices (ssize ints), and CHOLMOD's permuted copy of A's lower triangle.
double predicted_factor_mb(InspectableLLT& llt, const SparseMatrix& A) {
  const cholmod_factor* L = llt.factor();
  if (!L) return 0.0;
  const double values = L->is_super ? static_cast<double>(L->xsize) : llt.lnz();
  const double indices = L->is_super ? static_cast<double>(L->ssize) : llt.lnz();
  const double permuted_a = 0.5 * static_cast<double>(A.nonZeros() + A.rows()) * (sizeof(double) + sizeof(int));
  return (values * sizeof(double) + indices * sizeof(int) + permuted_a) / (1024.0 * 1024.0);
}

std::string megabytes(double mb) {
  std::ostringstream s;
  s.precision(3);
  if (mb >= 1024) s << mb / 1024 << " GB";
  else s << mb << " MB";
  return s.str();
}

class CholmodCholesky : public Solver {
 public:
  explicit CholmodCholesky(double memory_limit_mb) : memory_limit_mb_(memory_limit_mb) {}
  void analyze(const SparseMatrix& A) override { factor(A, MatrixFingerprint(A)); }
  SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                     const IterationCallback&) override {
    if (const MatrixFingerprint f(A); f != analyzed_.fingerprint()) factor(A, f);
    SolveSummary s;
    if (!refusal_.empty()) {
      s.termination = Termination::OutOfMemory;
      s.message = refusal_;
      return s;
    }
    if (llt_.info() != Eigen::Success) {
      s.message = "CHOLMOD: matrix is not positive definite (singular: is anything fixed?)";
      return s;
    }
    x = llt_.solve(b);
    s.iterations = 1;
    s.residual = relative_residual(A, b, x);
    s.termination = x.allFinite() ? Termination::Converged : Termination::NumericalFailure;
    s.message = x.allFinite() ? "CHOLMOD factor " + megabytes(factor_mb_) + " (its symbolic analysis)"
                              : "CHOLMOD produced non-finite values";
    return s;
  }

 private:
  void factor(const SparseMatrix& A, const MatrixFingerprint& f) {
    if (!f.same_pattern(analyzed_.fingerprint())) llt_.analyzePattern(A);
    factor_mb_ = predicted_factor_mb(llt_, A);
    const double limit = memory_limit_mb_ > 0 ? memory_limit_mb_ : available_memory_mb();
    refusal_.clear();
    if (limit > 0 && factor_mb_ > limit) {
      refusal_ = "CHOLMOD: its symbolic analysis says the factor of this " + std::to_string(A.rows()) +
                 "-unknown system needs " + megabytes(factor_mb_) + ", more than the " + megabytes(limit) + " " +
                 (memory_limit_mb_ > 0 ? "of solver.cholesky.memory_limit_mb" : "the machine has available") +
                 "; not factored (an iterative solver, e.g. multigrid_cg, needs no factor)";
    } else {
      llt_.factorize(A);
    }
    analyzed_.remember(f);
  }

  double memory_limit_mb_;
  double factor_mb_ = 0;
  std::string refusal_;
  InspectableLLT llt_;
  AnalyzedMatrix analyzed_;
};

}  // namespace

std::unique_ptr<Solver> make_cholmod_cholesky(Config& cfg) {
  Config sub = cfg.child("cholesky", "options of the cholesky solver");
  const double limit = sub.get<double>(
      "memory_limit_mb", 0.0,
      "largest factor (MiB, CHOLMOD's symbolic estimate) to factor; 0: the memory the machine has available");
  if (!(limit >= 0.0) || !std::isfinite(limit))
    throw InvalidConfig(sub.key_path("memory_limit_mb") + ": " + std::to_string(limit) + " must be a finite number >= 0");
  sub.check_no_unknown_keys();
  return std::make_unique<CholmodCholesky>(limit);
}

}  // namespace fairshape
