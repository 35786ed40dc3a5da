// What a petsc_* solver is asked to do, read from its config block, and the same thing as PETSc
// options (`-<prefix>ksp_type cg …`): the one description both the in-process solve and the
// distributed job (petsc_distributed.h) configure their KSP from, so the two cannot drift.
// All three solvers are preconditioned conjugate gradients stopping on the true relative residual
// ‖b − A x‖ / ‖b‖ (PETSc's default for preconditioned CG is the preconditioned residual, which
// would stop at another accuracy than fairshape's solvers at the same `tolerance`).
#pragma once

#include <string>
#include <vector>

#include "fairshape/core/config.h"
#include "fairshape/solver/iterative.h"
#include "fairshape/solver/multigrid.h"

namespace fairshape::petsc {

enum class Preconditioner {
  Mg,         // PCMG over fairshape's own restricted prolongations, Galerkin coarse operators
  Gamg,       // PETSc's smoothed-aggregation algebraic multigrid
  BoomerAmg,  // hypre's classical algebraic multigrid, through PCHYPRE
};

//! Levels an every-level option of Settings::extra_options ("-mg_levels_…") reaches: 1 to this.
constexpr int kMaxLevelOptionCopies = 24;

struct Settings {
  Preconditioner preconditioner = Preconditioner::Mg;
  IterativeOptions iterative;
  // petsc_mg
  MultigridOptions::CoarseSpace coarse_space = MultigridOptions::CoarseSpace::Nested;
  int max_levels = 0;          // coarse levels used (0: all)
  int smoother_iterations = 1;  // symmetric SOR sweeps (forward + backward) before and after the coarse correction
  std::string smoother = "sor";  // sor | chebyshev (Chebyshev around Jacobi)
  std::string cycle = "v";
  // petsc_gamg
  double gamg_threshold = 0.0;
  int gamg_smoothings = 1;
  double gamg_eigenvalue_safety = 1.5;  // 1.1 (PETSc's) made an indefinite preconditioner on the cow at level 1
  bool linear_near_null_space = true;
  // petsc_boomeramg
  double strong_threshold = 0.25;
  std::string coarsen = "HMIS";
  std::string interpolation = "ext+i";
  int aggressive_levels = 0;
  // every solver
  std::string extra_options;  // user's PETSc options, prefixed like ours
  int ranks = 1;              // >1: a distributed MPI job
  std::string launcher = "mpirun -np {ranks}";
  std::string job_dir;        // where a distributed job's files go ("" : the system's temporary folder)
  std::string worker;         // the MPI program ("": found next to fairshape's executables)
  bool keep_job = false;
  // Keys of the solver block this solver cannot honour (each names its key); the solver refuses
  // to run while any is set. Not thrown by from_config: the block may be meant for another solver.
  std::vector<std::string> refusals;

  static Settings from_config(Config& cfg, Preconditioner preconditioner);
  //! PETSc's options for a KSP with options prefix `prefix` (e.g. "fs3_"); `mg_levels`: petsc_mg's
  //! level count (the coarsest included).
  std::string option_string(const std::string& prefix, int mg_levels = 1) const;
  //! The options of `extra_options` as PETSc's database names them: prefixed, without the leading
  //! '-' (PetscOptionsUsed's form) and without values.
  std::vector<std::string> extra_option_names(const std::string& prefix) const;
  //! "petsc_mg", … (for messages).
  std::string solver_name() const;
  //! What a distributed job needs to configure the same KSP (JSON text, petsc_distributed.h).
  std::string to_json() const;
  static Settings from_json(const std::string& text);
};

}  // namespace fairshape::petsc
