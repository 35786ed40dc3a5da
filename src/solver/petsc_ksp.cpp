#include "fairshape/solver/petsc_ksp.h"

#include <atomic>
#include <sstream>

#include "fairshape/core/error.h"
#include "fairshape/core/timer.h"

namespace fairshape::petsc {

std::string unique_prefix() {
  static std::atomic<int> next{0};
  return "fs" + std::to_string(next++) + "_";
}

std::string ConfiguredKsp::reason_name(KSPConvergedReason r) {
  // KSPConvergedReasons is indexed by the reason itself, negative ones included.
  if (r < KSP_DIVERGED_PC_FAILED || r > KSP_CONVERGED_ATOL_NORMAL || !KSPConvergedReasons[r])
    return "reason " + std::to_string(static_cast<int>(r));
  return KSPConvergedReasons[r];
}

ConfiguredKsp::ConfiguredKsp(MPI_Comm comm, const Settings& s, Mat A, const std::vector<Mat>& prolongations,
                             const std::vector<Vec>& near_null_space) {
  const Timer timer;
  const std::string prefix = unique_prefix();
  const int levels = std::max<int>(1, static_cast<int>(prolongations.size()));
  const std::string options = s.option_string(prefix, levels);
  FS_PETSC(PetscOptionsInsertString(nullptr, options.c_str()));
  // PETSc 3.18's options database holds at most 512 entries: this solver's leave it once read.
  struct Forget {
    const std::string& options;
    const std::string& prefix;
    ~Forget() {
      std::istringstream words(options);
      for (std::string w; words >> w;)
        if (w.rfind("-" + prefix, 0) == 0) PetscOptionsClearValue(nullptr, w.c_str());
    }
  } forget{options, prefix};
  if (!near_null_space.empty()) {
    Handle<MatNullSpace, MatNullSpaceDestroy> space;
    FS_PETSC(MatNullSpaceCreate(comm, PETSC_FALSE, static_cast<PetscInt>(near_null_space.size()), near_null_space.data(),
                                space.out()));
    FS_PETSC(MatSetNearNullSpace(A, space.get()));
  }
  FS_PETSC(KSPCreate(comm, ksp_.out()));
  FS_PETSC(KSPSetOptionsPrefix(ksp_.get(), prefix.c_str()));
  FS_PETSC(KSPSetOperators(ksp_.get(), A, A));
  FS_PETSC(KSPSetFromOptions(ksp_.get()));
  if (s.preconditioner == Preconditioner::Mg) {
    PC pc = nullptr;
    FS_PETSC(KSPGetPC(ksp_.get(), &pc));
    for (int l = 1; l < levels; ++l) FS_PETSC(PCMGSetInterpolation(pc, l, prolongations[static_cast<std::size_t>(l)]));
    for (int l = 1; l < levels; ++l) {  // the level smoothers read their options here (created by -pc_mg_levels)
      KSP smoother = nullptr;
      FS_PETSC(PCMGGetSmoother(pc, l, &smoother));
      FS_PETSC(KSPSetFromOptions(smoother));
    }
    KSP coarse = nullptr;
    FS_PETSC(PCMGGetCoarseSolve(pc, &coarse));
    FS_PETSC(KSPSetFromOptions(coarse));
  }
  FS_PETSC(KSPSetUp(ksp_.get()));
  for (const std::string& name : s.extra_option_names(prefix)) {
    PetscBool used = PETSC_FALSE;  // an every-level option ("mg_levels_…") counts once any level read it
    FS_PETSC(PetscOptionsUsed(nullptr, name.c_str(), &used));
    if (!used)
      throw InvalidConfig("petsc.options: -" + name.substr(prefix.size()) + " was not used by " + s.solver_name() +
                          " (misspelt, or not an option of this preconditioner)");
  }
  setup_s_ = timer.seconds();
}

double IterateErrorEstimate::push(Vec x) {
  if (!previous_) {
    FS_PETSC(VecDuplicate(x, previous_.out()));
    FS_PETSC(VecDuplicate(x, step_.out()));
    FS_PETSC(VecDuplicate(x, a_step_.out()));
    FS_PETSC(VecDuplicate(x, a_x_.out()));
    FS_PETSC(VecCopy(x, previous_.get()));
    FS_PETSC(MatMult(A_, x, a_x_.get()));
    return -1.0;
  }
  FS_PETSC(VecWAXPY(step_.get(), -1.0, previous_.get(), x));
  FS_PETSC(MatMult(A_, step_.get(), a_step_.get()));
  PetscScalar term = 0, x_a_x = 0;
  FS_PETSC(VecDot(step_.get(), a_step_.get(), &term));
  FS_PETSC(VecAXPY(a_x_.get(), 1.0, a_step_.get()));
  FS_PETSC(VecCopy(x, previous_.get()));
  terms_.push(term);
  if (!terms_.ready()) return -1.0;
  FS_PETSC(VecDot(x, a_x_.get(), &x_a_x));
  return terms_.estimate(x_a_x);
}

PetscErrorCode MonitoredTest::test(KSP ksp, PetscInt it, PetscReal rnorm, KSPConvergedReason* reason, void* context) {
  auto* t = static_cast<MonitoredTest*>(context);
  *reason = KSP_CONVERGED_ITERATING;
  try {
    if (t->x && t->monitor->wants_iterate())
      t->monitor->observe([&] {
        Vec current = nullptr;
        FS_PETSC(KSPBuildSolution(ksp, nullptr, &current));
        copy_to_column(current, *t->x, t->column);
      });
    static const Eigen::MatrixXd kNotLookedAt;
    if (!t->monitor->record(static_cast<int>(it), rnorm / t->b_norm, t->x ? *t->x : kNotLookedAt)) {
      *reason = t->monitor->summary().succeeded() ? KSP_CONVERGED_RTOL : KSP_DIVERGED_ITS;
    } else if (t->estimate) {
      Vec current = nullptr;
      FS_PETSC(KSPBuildSolution(ksp, nullptr, &current));
      if (const double e = t->estimate->push(current); e >= 0 && !t->monitor->record_error(static_cast<int>(it), e))
        *reason = KSP_CONVERGED_RTOL;
    }
  } catch (...) {
    t->error = std::current_exception();
    *reason = KSP_DIVERGED_BREAKDOWN;
  }
  return 0;
}

}  // namespace fairshape::petsc
