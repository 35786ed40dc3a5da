// A KSP configured from Settings on any communicator: the in-process solve (one rank) and the
// distributed job build it the same way. petsc_mg gets fairshape's restricted prolongations as
// PCMG's interpolations (level 1 = the coarsest's, as MultigridLevels); petsc_gamg may get a
// near-null space (orthonormal vectors: PETSc requires it).
#pragma once

#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "fairshape/solver/iterative.h"
#include "fairshape/solver/petsc_runtime.h"
#include "fairshape/solver/petsc_settings.h"

namespace fairshape::petsc {

//! A fresh options prefix ("fs<k>_"): two solvers in one process never read each other's options.
std::string unique_prefix();

class ConfiguredKsp {
 public:
  //! `prolongations[l]`: level l from level l − 1 (l ≥ 1; [0] unused), for petsc_mg.
  //! \throw InvalidConfig when an option of Settings::extra_options is not used by PETSc.
  ConfiguredKsp(MPI_Comm comm, const Settings& s, Mat A, const std::vector<Mat>& prolongations,
                const std::vector<Vec>& near_null_space);
  KSP get() const { return ksp_.get(); }
  double setup_seconds() const { return setup_s_; }
  //! KSPConvergedReason as text ("CONVERGED_RTOL", "DIVERGED_ITS", …).
  static std::string reason_name(KSPConvergedReason r);

 private:
  KspHandle ksp_;
  double setup_s_ = 0;
};

//! The Hestenes–Stiefel estimate of CG's relative A-norm error, formed from the iterates: CG's
//! steps x_{j+1} − x_j are A-orthogonal, so ‖x* − x_k‖²_A = Σ_{j≥k} ‖x_{j+1} − x_j‖²_A, and the
//! last `delay` steps' sum bounds the error of the iterate `delay` steps back from below (the
//! estimate fairshape's own CG forms from its step lengths α_j r_jᵀz_j, which PETSc's CG does not
//! expose). Costs one product with A per iteration; collective on A's communicator.
class IterateErrorEstimate {
 public:
  IterateErrorEstimate(Mat A, int delay) : A_(A), terms_(delay) {}
  //! After each iteration, with its iterate (the first call: the start). The relative estimate
  //! once `delay` steps are in, else −1.
  double push(Vec x);

 private:
  Mat A_;
  CgErrorEstimate terms_;
  VecHandle previous_, step_, a_step_, a_x_;  // a_x_ = A x_k, kept by adding A·step
};

//! What PETSc's convergence test sees of fairshape's stopping rules: every iteration goes
//! through an IterationMonitor (tolerance, max_iterations, energy_tolerance, the callback and,
//! with `estimate`, error_tolerance), in this process and in the distributed job alike.
struct MonitoredTest {
  IterationMonitor* monitor = nullptr;
  Eigen::MatrixXd* x = nullptr;  // the whole iterate, this column updated when the monitor looks (null: never)
  Eigen::Index column = 0;
  double b_norm = 1;
  IterateErrorEstimate* estimate = nullptr;  // error_tolerance: the estimate the monitor stops on
  std::exception_ptr error;                  // a throw must not cross PETSc's C frames
  static PetscErrorCode test(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason* reason, void* context);
};

}  // namespace fairshape::petsc
