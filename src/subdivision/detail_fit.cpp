// Why conjugate gradients suffice: the columns of a subdivision operator are its basis
// functions' refinement masks, a Riesz basis, so the spectrum of SᵀS is bounded above and below
// independently of the level (measured on the cow's Catmull-Clark ladder: eigenvalues in
// [0.059, 4.37], condition 74). Jacobi-preconditioned CG then needs ~130 iterations for 1e-14
// at any size, each a product with S and one with Sᵀ, where a sparse factorization of SᵀS
// (Eigen's SimplicialLDLT) took most of a level-5 run's wall time and gigabytes of fill.
#include "fairshape/subdivision/detail_fit.h"

#include <Eigen/SparseCholesky>
#include <cmath>
#include <string>

#include "fairshape/core/error.h"
#include "fairshape/core/parallel_for.h"

namespace fairshape {
namespace {

using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// y = M x for a row-major M, rows in parallel (each writes its own row).
void multiply(const RowMajor& M, const MatrixX3& x, MatrixX3& y) {
  y.resize(M.rows(), 3);
  for_each_range<Eigen::Index>(0, M.rows(), 4096, [&](const IndexRange<Eigen::Index>& r) {
    for (Eigen::Index i = r.begin(); i != r.end(); ++i) {
      Eigen::RowVector3d s = Eigen::RowVector3d::Zero();
      for (RowMajor::InnerIterator it(M, i); it; ++it) s += it.value() * x.row(it.index());
      y.row(i) = s;
    }
  });
}

// The least-squares solution from the factored normal equations.
MatrixX3 fit_direct(const SparseMatrix& S, const MatrixX3& X) {
  const SparseMatrix St = S.transpose();
  const Eigen::SimplicialLDLT<SparseMatrix> fit(SparseMatrix(St * S));
  if (fit.info() != Eigen::Success) throw InvalidInput("analyze: the least-squares fit of a level is singular");
  return fit.solve(St * X);
}

// Relative residual of the normal equations at which the iteration stops: the fit is then as
// exact as the factorization's (both back ends agree to ~1e-13 of the coordinates).
constexpr double kTolerance = 1e-15;
constexpr int kMaxIterations = 2000;

MatrixX3 fit_iterative(const SparseMatrix& S, const MatrixX3& X) {
  const RowMajor Sr = S;
  const RowMajor St = S.transpose();
  const Eigen::Index n = S.cols();
  Eigen::VectorXd inverse_diagonal(n);  // (SᵀS)_jj = ‖S e_j‖²
  for (Eigen::Index j = 0; j < n; ++j) {
    double d = 0;
    for (SparseMatrix::InnerIterator it(S, j); it; ++it) d += it.value() * it.value();
    if (!(d > 0)) throw InvalidInput("analyze: coarse vertex " + std::to_string(j) + " has no finer point");
    inverse_diagonal(j) = 1.0 / d;
  }
  // Start: a coarse vertex's own point on the finer level (ids nest), close on a smooth surface.
  MatrixX3 c = X.topRows(n);
  MatrixX3 Sc, r, z, p, q;
  multiply(Sr, c, Sc);
  multiply(St, MatrixX3(X - Sc), r);
  MatrixX3 rhs;
  multiply(St, X, rhs);
  const Eigen::Array3d target = kTolerance * rhs.colwise().norm().transpose().array();
  z = inverse_diagonal.asDiagonal() * r;
  p = z;
  Eigen::Array3d rz = (r.array() * z.array()).colwise().sum().transpose();
  for (int it = 0; it < kMaxIterations; ++it) {
    const Eigen::Array3d norm = r.colwise().norm().transpose().array();
    if ((norm <= target).all()) return c;
    multiply(Sr, p, Sc);
    multiply(St, Sc, q);
    const Eigen::Array3d pq = (p.array() * q.array()).colwise().sum().transpose();
    for (int k = 0; k < 3; ++k) {
      if (norm(k) <= target(k) || !(pq(k) > 0)) continue;  // this column is done
      const double alpha = rz(k) / pq(k);
      c.col(k) += alpha * p.col(k);
      r.col(k) -= alpha * q.col(k);
    }
    z = inverse_diagonal.asDiagonal() * r;
    const Eigen::Array3d rz_new = (r.array() * z.array()).colwise().sum().transpose();
    for (int k = 0; k < 3; ++k) {
      const double beta = rz(k) > 0 ? rz_new(k) / rz(k) : 0.0;
      p.col(k) = z.col(k) + beta * p.col(k);
    }
    rz = rz_new;
  }
  // Rounding can hold the recursive residual just above 1e-15 of a badly scaled column: the
  // factorization decides then (the same answer, slower), never an unconverged fit.
  return fit_direct(S, X);
}

}  // namespace

MatrixX3 fit_coarse_points(const SparseMatrix& S, const MatrixX3& X, Backend backend) {
  if (X.rows() != S.rows()) throw InvalidInput("analyze: finer points and subdivision operator disagree in size");
  return backend == Backend::Reference ? fit_direct(S, X) : fit_iterative(S, X);
}

}  // namespace fairshape
