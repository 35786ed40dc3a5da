#include "fairshape/experiment/kinds/surface_edit/open_session.h"

#include <random>

#include "fairshape/core/config.h"
#include "fairshape/experiment/components.h"

namespace fairshape {

SolverFactory ladder_direct_solver(Backend backend) {
  return [backend] {
    Config none;
    return components().solvers.create("cholesky", backend, none);
  };
}

SolverFactory ladder_relaxer(const AccuracyOptions& a, Backend backend) {
  // The cascade's smoother: a fixed count, no residual checks (the paper's fixed iterations).
  // `a` is copied: a session outlives the spec it was opened from (Python).
  return [a, backend] {
    YAML::Node n;
    n["max_iterations"] = a.relaxation_sweeps;
    n["check_every"] = a.relaxation_sweeps;
    n["tolerance"] = 0.0;
    n["sor"]["omega"] = a.relaxation_omega;
    Config c(n, "problem.relaxation");
    return components().solvers.create(a.relaxation, backend, c);
  };
}

PassLadder pass_ladder(const SurfaceEditSpec& spec, Solver* finest) {
  const AccuracyOptions& a = spec.accuracy;
  return {a.ladder(), a.coarse_level, ladder_direct_solver(spec.implementation),
          ladder_relaxer(a, spec.implementation), finest, a.coarse_constraint_mode};
}

namespace {

// solver.initial_guess: random, from the run's seed.
Eigen::MatrixXd random_start(const SurfaceEditSpec& spec, Eigen::Index rows) {
  std::mt19937_64 gen(static_cast<std::uint64_t>(spec.seed));
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  Eigen::MatrixXd x(rows, 3);
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = d(gen);
  return x;
}

}  // namespace

std::unique_ptr<SurfaceEditSession> open_session(const SurfaceEditSpec& spec, std::shared_ptr<const MultiresSurface> rest,
                                                 bool orient_normals) {
  SurfaceEditOptions o;
  if (spec.initial_guess == InitialGuess::Random)
    o.initial = random_start(spec, rest->mesh(spec.edit_level < 0 ? rest->levels() : spec.edit_level).n_vertices());
  o.level = spec.edit_level;
  o.mode = spec.constraint_mode;
  o.solver = spec.solver;
  o.backend = spec.implementation;
  o.qp_options = spec.qp_config();
  if (spec.accuracy.multilevel()) o.ladder = pass_ladder(spec, spec.solver.get());
  o.rotations = spec.rotations;
  o.constraint_tolerance = spec.constraint_tolerance;
  const EditTerms terms = spec.edit_terms();
  o.positions = terms.positions;
  o.levels = terms.levels;
  o.orient_normals = orient_normals;
  o.frame_rows = spec.frame_rows_for_auto_normals;
  std::vector<SessionEnergy> energies;
  for (const EnergyTerm& e : spec.energies) energies.push_back({e.energy, e.weight});
  std::vector<SessionConstraint> constraints;
  for (const ConstraintTerm& c : spec.constraints) constraints.push_back({c.constraint, c.influence});
  return std::make_unique<SurfaceEditSession>(std::move(rest), std::move(energies), std::move(constraints), std::move(o));
}

void apply_step(const EditStepSpec& step, SurfaceEditSession& session) {
  if (step.scale) session.scale(*step.scale);
  for (const auto& [handle, offset] : step.offsets) session.move(handle, offset);
}

SurfaceEditStep solve_step(const EditStepSpec& step, SurfaceEditSession& session, const IterationCallback& cb) {
  if (!step.accuracy || *step.accuracy == AccuracyMode::SingleLevel) return session.solve(cb);
  AccuracyOptions mode;
  mode.mode = *step.accuracy;
  return session.solve(mode.ladder(), cb);
}

}  // namespace fairshape
