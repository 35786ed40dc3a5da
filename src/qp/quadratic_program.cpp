#include "fairshape/qp/quadratic_program.h"

#include "fairshape/core/error.h"

namespace fairshape::qp {

void validate(const QuadraticProgram& qp) {
  const auto fail = [](const std::string& what) { throw InvalidInput("quadratic program: " + what); };
  const Eigen::Index n = qp.hessian().rows();
  if (qp.hessian().cols() != n) fail("H is not square");
  if (qp.f.rows() != n) fail("f has " + std::to_string(qp.f.rows()) + " rows, H has " + std::to_string(n));
  if (qp.A.cols() != n) fail("A has " + std::to_string(qp.A.cols()) + " columns, H has " + std::to_string(n));
  if (qp.b.rows() != qp.A.rows() || (qp.A.rows() > 0 && qp.b.cols() != qp.f.cols()))
    fail("b must be " + std::to_string(qp.A.rows()) + " x " + std::to_string(qp.f.cols()));
  if (qp.K.size() > 0 && qp.K.cols() != n) fail("K has " + std::to_string(qp.K.cols()) + " columns, H has " + std::to_string(n));
  const auto finite = [](const SparseMatrix& M) {
    for (Eigen::Index i = 0; i < M.nonZeros(); ++i)
      if (!std::isfinite(M.valuePtr()[i])) return false;
    return true;
  };
  if (!finite(qp.hessian()) || !finite(qp.A) || !finite(qp.K) || !qp.f.allFinite() || !qp.b.allFinite())
    fail("non-finite entries (NaN or infinity)");
}

double objective(const QuadraticProgram& qp, const Eigen::MatrixXd& p) {
  return 0.5 * (p.transpose() * (qp.hessian() * p)).trace() - (qp.f.transpose() * p).trace();
}

double constraint_residual(const SparseMatrix& A, const Eigen::MatrixXd& b, const Eigen::MatrixXd& p) {
  if (A.rows() == 0) return 0;
  return (A * p - b).norm();
}

}  // namespace fairshape::qp
