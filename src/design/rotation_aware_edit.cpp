#include "fairshape/design/rotation_aware_edit.h"

#include <algorithm>
#include <memory>
#include <sstream>

#include "fairshape/energy/local_rotations.h"
#include "fairshape/problem/anderson_acceleration.h"

namespace fairshape {
namespace {

// The objective of the rotation-aware edit at a deformation x with every rotation at its best
// for x: ½ tr(xᵀHx) − ⟨g + Σ b(R), x⟩ + Σ c(R), R = fit(P + x) — E_R of the turning energies
// plus the others' quadratic. `fits` receives the rotations, which the next global step uses.
class RotationObjective {
 public:
  RotationObjective(const EditProblem& p, const SurfaceMesh& rest, std::vector<std::unique_ptr<LocalRotations>> turning)
      : p_(p), rest_(rest), turning_(std::move(turning)) {}

  struct Value {
    double energy = 0;
    Eigen::MatrixXd linear_term;  // g + Σ b(R): the global step's for these rotations
  };

  Value operator()(const Eigen::MatrixXd& x, RotationFit how = RotationFit::Exact) const {
    const MatrixX3 deformed = rest_.positions() + MatrixX3(x);
    Value v;
    v.linear_term = p_.g;
    for (const auto& r : turning_) {
      const std::vector<Mat3> R = r->fit(deformed, how);
      v.linear_term += r->linear_term(R);
      v.energy += r->constant_term(R);
    }
    v.energy += 0.5 * (x.transpose() * (p_.H * x)).trace() - v.linear_term.cwiseProduct(x).sum();
    return v;
  }

 private:
  const EditProblem& p_;
  const SurfaceMesh& rest_;
  std::vector<std::unique_ptr<LocalRotations>> turning_;
};

Eigen::VectorXd flat(const Eigen::MatrixXd& m) { return Eigen::Map<const Eigen::VectorXd>(m.data(), m.size()); }

}  // namespace

RotationAwareSolution solve_rotation_aware(const EditProblem& p, const std::vector<WeightedEnergy>& energies,
                                           const SurfaceMesh& rest, ConstraintMode mode, Solver& solver,
                                           Backend backend, const Config& qp_options, const RotationAwareOptions& o) {
  std::vector<std::unique_ptr<LocalRotations>> turning;
  for (const WeightedEnergy& e : energies)
    if (auto r = e.energy->local_rotations(rest, e.weight)) turning.push_back(std::move(r));
  if (turning.empty())
    throw InvalidInput("problem.rotation_iterations: no energy of this edit has details to turn (use an energy of "
                       "the deformation, detail_preserving)");
  const RotationObjective objective(p, rest, std::move(turning));
  PreparedEdit prepared(p, mode, solver, backend, qp_options);
  RotationAwareSolution out;
  out.solution = prepared.solve(p.constraints.C);
  double solve_s = out.solution.solve_s;
  int iterations = out.solution.summary.iterations;
  if (o.iterations == 0 || !is_success(out.solution.summary.termination)) return out;

  // Local/global rounds x ← G(x) (fit the rotations to x, solve with them). Two local steps:
  //  - the exact one (LocalRotations::fit, RotationFit::Exact) minimizes E_R over the
  //    rotations, so every round lowers E_R (a block descent) and its fixed points are
  //    stationary points of E_R — but it crawls when a long part turns far (a 60-degree turn
  //    of the cow: E_R from 7e5 to only 1e2 in 200 rounds);
  //  - the tangent frame's (RotationFit::TangentFrame) turns a long part in a few dozen rounds
  //    but is no descent (on a 45-degree tilt its rounds did not settle).
  // So the tangent frame leads while E_R falls, and the exact step takes over from the first
  // round where it does not, or when the tangent frame's rounds stop moving. Anderson
  // acceleration extrapolates from the last rounds; an extrapolated iterate is kept only when
  // its E_R is below the plain round's (the safeguard of Peng et al., "Anderson acceleration for
  // geometry optimization and physics simulation"). Every iterate is an affine combination of
  // constrained solutions, so it meets the (linear) constraints.
  const double model_size = rest.positions().norm();
  AndersonAcceleration accelerate(6);
  RotationFit how = RotationFit::TangentFrame;
  Eigen::MatrixXd x = out.solution.delta;
  // x's E_R with the exact fit, and the global step's linear term for those rotations: the
  // exact rounds reuse it rather than fit x again.
  RotationObjective::Value at_x = objective(x);
  bool settled = false;
  int extrapolated = 0, frame_rounds = 0;
  const auto switch_to_exact = [&] {
    how = RotationFit::Exact;
    accelerate.reset();
  };
  for (int round = 1; round <= o.iterations; ++round) {
    prepared.set_linear_term(how == RotationFit::Exact ? at_x.linear_term : objective(x, how).linear_term);
    EditSolution next = prepared.solve(p.constraints.C, {}, &x, ConstrainedStart::NearestToInitial);
    solve_s += next.solve_s;
    if (!is_success(next.summary.termination)) {
      out.solution = std::move(next);
      break;
    }
    iterations += next.summary.iterations;
    // Relative to the deformation, but not below rounding of the model's size: an edit whose
    // answer is no motion at all (a straight curve turned about itself) would otherwise
    // compare noise with noise and never settle (measured on an open cylinder).
    const double size = std::max(next.delta.norm(), 1e-12 * model_size);
    out.last_change = size > 0 ? (next.delta - x).norm() / size : 0.0;
    out.rounds = round;
    frame_rounds += how == RotationFit::TangentFrame;
    out.energy_history.push_back(at_x.energy);
    RotationObjective::Value at_g = objective(next.delta);
    if (how == RotationFit::TangentFrame && at_g.energy >= at_x.energy) {
      switch_to_exact();  // x stays: the tangent frame's round did not lower E_R
      continue;
    }
    out.solution = std::move(next);  // G(x): the answer when the rounds stop here
    const Eigen::MatrixXd& g = out.solution.delta;
    if (out.last_change <= o.tolerance) {
      if (how == RotationFit::Exact) {
        settled = true;
        break;
      }
      switch_to_exact();  // a fixed point of the tangent frame's rounds is not one of E_R's
      x = g, at_x = std::move(at_g);
      continue;
    }
    const Eigen::VectorXd next_x = accelerate.next(flat(x), flat(g));
    Eigen::MatrixXd xa = Eigen::Map<const Eigen::MatrixXd>(next_x.data(), x.rows(), x.cols());
    if ((xa - g).norm() == 0) {  // no history yet: the extrapolation is G(x) itself
      x = g, at_x = std::move(at_g);
      continue;
    }
    RotationObjective::Value at_a = objective(xa);
    if (at_a.energy < at_g.energy) {
      x = std::move(xa), at_x = std::move(at_a);
      ++extrapolated;
    } else {
      if (at_a.energy > at_g.energy) accelerate.reset();
      x = g, at_x = std::move(at_g);
    }
  }
  out.energy = objective(out.solution.delta).energy;
  out.energy_history.push_back(out.energy);
  out.solution.summary.iterations = iterations;
  out.solution.solve_s = solve_s;
  if (is_success(out.solution.summary.termination)) {
    std::ostringstream os;
    os << "rotation-aware: " << out.rounds << " rounds (" << frame_rounds << " with the tangent frame's fit, "
       << extrapolated << " extrapolated), E_R " << std::scientific << out.energy << ", last change "
       << std::scientific << out.last_change;
    if (!settled) {
      os << " above the tolerance " << o.tolerance;
      out.solution.summary.termination = Termination::MaxIterations;
    }
    out.solution.summary.message += (out.solution.summary.message.empty() ? "" : "; ") + os.str();
  }
  return out;
}

}  // namespace fairshape
