// A KSP configured from Settings on any communicator: the in-process solve (one rank) and the
// distributed job build it the same way. petsc_mg gets fairshape's restricted prolongations as
// PCMG's interpolations (level 1 = the coarsest's, as MultigridLevels); petsc_gamg may get a
// near-null space (orthonormal vectors: PETSc requires it).
#pragma once

#include <string>
#include <vector>

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

}  // namespace fairshape::petsc
