// Every tolerance the conformance tests use, in one place.
#pragma once

namespace fairshape::test {

// Iterative solvers stop at this relative residual in conformance runs...
constexpr double kSolveResidual = 1e-12;
// ...and must then be this close (relative, Frobenius) to a direct solve, for either back end.
constexpr double kSolutionAgreement = 1e-8;
// Direct solvers (CHOLMOD vs Eigen LDLT) agree to this relative error.
constexpr double kDirectAgreement = 1e-10;

}  // namespace fairshape::test
