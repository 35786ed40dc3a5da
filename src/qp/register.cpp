#include <algorithm>

#include "fairshape/core/config.h"
#include "fairshape/qp/kkt_solver.h"
#include "fairshape/qp/qr_penalty_solver.h"
#include "fairshape/qp/range_space_solver.h"
#include "fairshape/qp/split_solver.h"

namespace fairshape::qp {

namespace {
bool read_reuse_factorization(Config& cfg) {
  return cfg.get<bool>("reuse_factorization", true,
                       "keep the factorization while H and A are unchanged (a drag step: only targets move); false: "
                       "factor at every step (for measurements)");
}

QrPenaltyOptions read_penalty(Config& cfg) {
  QrPenaltyOptions o;
  o.mu = cfg.get_number("mu", o.mu, 1e-6, 1e12,
                        "penalty weight of the constraint rows, relative to the energy's scale (sqrt(max diag H) / max|A|)");
  o.refinement_steps = cfg.get_int("refinement_steps", o.refinement_steps, 0, 100,
                                   "Van Loan weighting-method steps refining the constraint residual with one factorization, at most "
                                   "(fewer once constraint_tolerance is met)");
  o.max_mu = cfg.get_number("max_mu", std::max(o.max_mu, o.mu), o.mu, 1e12,
                            "mu grows tenfold up to this while refinement stalls (max_mu = mu: never)");
  o.solution_tolerance = cfg.get_number("solution_tolerance", o.solution_tolerance, 1e-15, 1,
                                        "refinement continues while a step moves the answer by more than this (relative, max-norm); "
                                        "still moving at max_mu: ill_conditioned");
  static const NameTable<bool> solves{{false, "semi_normal"}, {true, "orthogonal"}};
  o.orthogonal = cfg.get_enum("solve", false, solves,
                              "semi_normal: R only (corrected semi-normal equations, fast); orthogonal: through Q (slow, accurate)");
  o.policy = read_constraint_policy(cfg);
  o.reuse_factorization = read_reuse_factorization(cfg);
  return o;
}
// Every linear solver, both back ends: the split's free unknowns.
const SolverRegistry& linear_solvers() {
  static const SolverRegistry registry = [] {
    SolverRegistry r("solver");
    register_solvers(r);
    reference::register_solvers(r);
    return r;
  }();
  return registry;
}

std::unique_ptr<QpSolver> make_split(Backend backend, Config& cfg) {
  Config fc = cfg.child("free_solver", "the free unknowns' linear solver: {type, tolerance, max_iterations, <type>: {...}}");
  const std::string type = fc.get_choice("type", "cholesky", linear_solvers().names(), "linear solver name");
  auto free = linear_solvers().create(type, linear_solvers().has(type, backend) ? backend : kFastestBackend, fc);
  fc.check_no_unknown_keys();
  return std::make_unique<SplitSolver>(std::move(free), backend);
}

}  // namespace

void register_qp_solvers(QpSolverRegistry& r) {
  for (const Backend backend : built_backends()) {
    const bool ref = backend == Backend::Reference;
    r.add("kkt", backend,
          ref ? "Lagrange system (eq. 9): dependent rows dropped by a rank-revealing QR (dense pivoted, Eigen SparseQR when large), "
                "Eigen SparseLU factors"
              : "Lagrange system (eq. 9): dependent rows dropped by a rank-revealing QR (dense pivoted, SuiteSparseQR when large), "
                "UMFPACK factors (symbolic analysis reused)",
          [backend](Config& cfg) -> std::unique_ptr<QpSolver> {
            const ConstraintPolicy policy = read_constraint_policy(cfg);
            return std::make_unique<KktSolver>(backend, policy, read_reuse_factorization(cfg));
          });
    r.add("qr_penalty", backend,
          ref ? "penalty least squares [mu A; K] (eq. 10) by Eigen SparseQR, Van Loan refinement"
              : "penalty least squares [mu A; K] (eq. 10) by SuiteSparseQR, Van Loan refinement",
          [backend](Config& cfg) -> std::unique_ptr<QpSolver> {
            return std::make_unique<QrPenaltySolver>(backend, read_penalty(cfg));
          });
    r.add("paper", backend,
          ref ? "Boier-Martin et al. 4.3's split: the unknowns the rows reach by minimum-norm least squares (Eigen SparseQR), "
                "then fixed; the others by free_solver (the paper's answer, not the minimizer)"
              : "Boier-Martin et al. 4.3's split: the unknowns the rows reach by minimum-norm least squares (CHOLMOD on A "
                "A' / SuiteSparseQR), then fixed; the others by free_solver (the paper's answer, not the minimizer)",
          [backend](Config& cfg) { return make_split(backend, cfg); });
  }
#if FAIRSHAPE_WITH_TBB  // a build without TBB has the reference back ends alone
  r.add("range_space", Backend::Optimized,
        "CHOLMOD on H + rho A'A and the dense Schur complement of the constraints; added rows border it, removed ones "
        "downdate the factor (cholmod_updown)",
        [](Config& cfg) -> std::unique_ptr<QpSolver> { return std::make_unique<RangeSpaceSolver>(read_constraint_policy(cfg)); });
#endif
}

const QpSolverRegistry& qp_solver_registry() {
  static const QpSolverRegistry registry = [] {
    QpSolverRegistry r("constrained solver");
    register_qp_solvers(r);
    return r;
  }();
  return registry;
}

}  // namespace fairshape::qp
