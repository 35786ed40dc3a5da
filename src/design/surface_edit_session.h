// Boier-Martin et al.'s edit as a session: the hierarchy, the designer's constraints (each with
// its region of influence, §4.2) and the prepared problem — H and the propagated rows on the
// ladder's levels, the factorizations and multigrid set-ups of §4.3 and §5 — kept across steps,
// so a drag step (the handles' targets change, the rows do not) is a solve with the analysis in
// hand. The command line's run kind, the Python module and the editor drive the same steps:
//   move(handle, offset)  a handle's target (its displacement from rest) changes;
//   scale(s)              every target s × its configured value (problem.drag_steps' k/N);
//   add / remove          a constraint arrives or leaves: its rows are propagated again,
//                         H is kept, the next solve prepares anew;
//   solve(), solve(mode)  §5's interactive / improved / converged (each prepared once, on
//                         first use), or the configured single-level solve.
// Every solve measures its own result (papers/boier-martin/README.md, "Folds and reversed
// normals"): the constraint residual on the result, flipped faces and reversed normals on the
// finest level synthesized with its details, the energy of the result; a fold or a reversed
// normal turns a success into `folded`.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "fairshape/design/edit_assembly.h"
#include "fairshape/design/edit_solve.h"
#include "fairshape/design/multilevel_edit.h"
#include "fairshape/design/orientation_check.h"
#include "fairshape/design/regional_edit.h"
#include "fairshape/design/rotation_aware_edit.h"

namespace fairshape {

struct SessionEnergy {
  std::shared_ptr<const Energy> energy;
  double weight = 1.0;
};

//! A designer's constraint and its region of influence (design/influence.h).
struct SessionConstraint {
  std::shared_ptr<const Constraint> constraint;
  Influence influence = {};
};

//! How a session solves; a config's problem: and solver: blocks map onto it.
struct SurfaceEditOptions {
  int level = -1;                             // the edit level (-1: the finest)
  ConstraintMode mode = ConstraintMode::Kkt;  // §4.3's split (paper) or a QP mode
  std::shared_ptr<Solver> solver;             // paper mode's free vertices, the converged ladder's finest level
  Backend backend = Backend::Optimized;
  Config qp_options;                          // the QP mode's own options (problem.<mode>)
  //! §5's ladder (its `finest` is `solver`); solve() then solves with ladder->accuracy.
  std::optional<PassLadder> ladder;
  RotationAwareOptions rotations;
  double constraint_tolerance = kDefaultConstraintTolerance;  // regional edits
  bool positions = false;       // the energies measure P_rest + ΔP (problem.formulation: position)
  bool levels = false;          // attach the levels below for a multilevel solver (EditTerms::levels)
  //! A normal left to rows `auto` and met by its reverse: solved again with frame rows
  //! (design/orientation_check.h). A front end that retries itself (the run kind, which writes
  //! each attempt's outputs) sets this false and frame_rows true on its second session.
  bool orient_normals = true;
  bool frame_rows = false;      // EditTerms::frame_rows_for_auto_normals from the start
  Eigen::MatrixXd initial;      // the first solve's start for iterative solvers (empty: zero)
};

//! One solve of the session, measured on its result.
struct SurfaceEditStep {
  EditSolution solution;    // the edit level's deformation and the solver's own summary
  SolveSummary summary;     // solution.summary with what the checks found (folded)
  std::string accuracy;     // single-level, interactive, improved or converged
  OrientationCheck orientation;
  double energy = 0;        // of the result (≥ 0; configs/README.md, "energy")
  double constraint_residual = 0;  // ‖A ΔP − C‖ (regional: what every constraint still misses)
  double solve_s = 0, check_s = 0;
  int rotation_rounds = 0;  // rotation-aware edits
  // Regional edits (design/regional_edit.h).
  std::vector<RegionalPass> passes;
  Eigen::VectorXi region;
  double outside_region_move = 0;
  bool regional = false;
};

class SurfaceEditSession {
 public:
  //! Assembles H and the rows (regional edits: checks them; the passes assemble per solve).
  //! \throw InvalidInput as assemble_edit_ladder / check_regional_edit.
  SurfaceEditSession(std::shared_ptr<const MultiresSurface> rest, std::vector<SessionEnergy> energies,
                     std::vector<SessionConstraint> constraints, SurfaceEditOptions options);
  ~SurfaceEditSession();
  SurfaceEditSession(const SurfaceEditSession&) = delete;
  SurfaceEditSession& operator=(const SurfaceEditSession&) = delete;

  //! Handles are numbered 0, 1, … in the order the session made them (the constructor's first);
  //! a removed handle's number is not reused. Returns the new handle.
  int add(SessionConstraint c);
  void remove(int handle);
  //! Every point `handle` placed moves by `offset` from rest on the next solve.
  //! \throw InvalidInput for no such handle, or when the edit cannot take a new target
  //! (regional or rotation-aware edits solve their constraints as configured) or another
  //! constraint holds one of its vertices at another target.
  void move(int handle, const Vec3& offset);
  //! Every target s × its configured value, moves forgotten: the drag of problem.drag_steps.
  void scale(double s);

  SurfaceEditStep solve(const IterationCallback& cb = {});
  //! §5's mode, on the ladder of the options. \throw InvalidInput without a ladder.
  SurfaceEditStep solve(Accuracy mode, const IterationCallback& cb = {});

  const MultiresSurface& rest() const { return *rest_; }
  //! The hierarchy after the last solve (rest before the first), finer levels with their details.
  const MultiresSurface& current() const;
  int level() const { return level_; }
  bool regional() const;
  std::vector<int> handles() const;  // the live ones, in order
  //! The edit level's problem with the current targets' rows (not for regional edits).
  const EditProblem& problem() const;
  const EditLadder& ladder() const { return ladder_; }
  int coarse_level() const { return coarse_; }
  const DesignConstraints& placed() const { return placed_; }
  const Eigen::MatrixXd& targets() const { return targets_; }
  //! How many times a solve prepared its problem (factorizations, multigrid set-ups): a drag
  //! step adds none, the first solve after add / remove (or in a mode not used yet) one.
  int preparations() const { return preparations_; }
  //! After a solve in one of §5's modes: its deformation on each level of the ladder (Figure 8
  //! d–f; empty entries for levels the mode did not solve); empty after any other solve.
  const std::vector<Eigen::MatrixXd>& level_solutions() const;

 private:
  struct Handle {
    SessionConstraint c;
    bool live = true;
    std::size_t first = 0, last = 0;  // its points in placed_.points
    std::optional<Vec3> moved;
  };
  EditTerms terms() const;
  void prepare_rows();     // H once (not for regional edits), then place()
  void place();            // placed_, the rows on every level of the ladder, targets_
  void apply_targets();    // targets_ and placed_ offsets from scale_ and the moves
  void forget_prepared();
  Handle& handle(int h);
  SurfaceEditStep solve_step(std::optional<Accuracy> mode, const IterationCallback& cb);
  EditSolution solve_assembled(std::optional<Accuracy> mode, const IterationCallback& cb, int& rounds);
  void solve_regional(SurfaceEditStep& step);
  void finish(SurfaceEditStep& step);

  std::shared_ptr<const MultiresSurface> rest_;
  std::vector<SessionEnergy> energies_;
  std::vector<Handle> handles_;
  SurfaceEditOptions options_;
  int level_ = 0, coarse_ = 0;
  int preparations_ = 0;
  bool frame_rows_ = false;
  EditLadder ladder_;                 // coarse_..level_, H of each; empty for regional edits
  DesignConstraints placed_, configured_;  // as placed now, and with their configured targets
  std::vector<int> rows_;             // point i of placed_ → its row
  Eigen::MatrixXd configured_C_, targets_;
  double scale_ = 1.0;
  std::unique_ptr<PreparedEdit> prepared_;                     // single-level
  std::map<Accuracy, std::unique_ptr<MultilevelEdit>> modes_;  // §5's, each on first use
  std::optional<Accuracy> last_mode_;  // the mode of the last solve
  Eigen::MatrixXd previous_;          // the last step's deformation: the next one's start
  std::unique_ptr<StepOrientationCheck> check_;
  std::optional<MultiresSurface> regional_result_;
  std::optional<EditProblem> energy_only_;  // regional edits: H of the edit level, for the energy
};

}  // namespace fairshape
