// The reference back end of a fairshape built without TBB: one Catmull-Clark step of the cube
// (26 vertices, 24 quads, S's rows summing to one) and the stretch + bend Hessian of the result
// (symmetric, the constant vector in its kernel).
#include <fairshape/energy/local_quadratic.h>
#include <fairshape/subdivision/subdivider.h>

#include <cmath>
#include <iostream>

#include "cube.h"

int main() {
  using namespace fairshape;
  static_assert(!kOptimizedBackendBuilt, "this program tests a build without TBB");
  SparseMatrix S;
  const SurfaceMesh fine = subdivide_once(unit_cube(), SubdivisionOptions{}, Backend::Reference, &S);
  const double row_sum_error = (S * Eigen::VectorXd::Ones(S.cols()) - Eigen::VectorXd::Ones(S.rows())).cwiseAbs().maxCoeff();
  const SparseMatrix H = stretch_bend_hessian(fine, StretchBendWeights{}, Backend::Reference);
  const double asymmetry = SparseMatrix(H - SparseMatrix(H.transpose())).norm();
  const double constant = (H * Eigen::VectorXd::Ones(H.cols())).norm();
  std::cout << fine.n_vertices() << " vertices, " << fine.n_faces() << " faces, |S1 - 1| " << row_sum_error
            << ", H " << H.rows() << "x" << H.cols() << " with " << H.nonZeros() << " entries, |H - H'| " << asymmetry
            << ", |H1| " << constant << "\n";
  const bool ok = fine.n_vertices() == 26 && fine.n_faces() == 24 && row_sum_error < 1e-12 && H.rows() == 26 &&
                  H.nonZeros() > 0 && asymmetry < 1e-12 && constant < 1e-9;
  return ok ? 0 : 1;
}
