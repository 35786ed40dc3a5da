#include "fairshape/core/config.h"
#if FAIRSHAPE_WITH_CERES
#include "fairshape/curve_design/ceres_length_solver.h"
#endif
#include "fairshape/curve_design/linearized_length_solver.h"
#include "fairshape/curve_design/projection_length_solver.h"
#include "fairshape/curve_design/trust_region_length_solver.h"

namespace fairshape {
namespace {

LengthTolerances read_tolerances(Config& c) {
  LengthTolerances t;
  t.length = c.get_number("length_tolerance", t.length, 0, 1, "stop when every segment's relative length error is below");
  t.stationarity = c.get_number("stationarity_tolerance", t.stationarity, 0, 1,
                                "and |grad F + J^T lambda| / (|QX| + |b|) is below (0: lengths alone, as the paper)");
  t.max_solves = c.get_int("max_solves", t.max_solves, 1, 1000000, "give up after this many linear solves");
  static const NameTable<SecondOrderMode> modes{
      {SecondOrderMode::Inertia, "inertia"}, {SecondOrderMode::Dense, "dense"}, {SecondOrderMode::Off, "off"}};
  t.second_order = c.get_enum("second_order", SecondOrderMode::Inertia, modes,
                              "how a stationary answer is judged: inertia (LDLT inertia of the banded KKT factor, smallest "
                              "eigenvalue by inertia bisection, O(n) at any size), dense (the reduced Hessian's eigen-solve, "
                              "O(n^3), curves up to 600 points) or off (not checked: first order only)");
  return t;
}

LengthSolverRegistry::Factory linearized(Backend backend) {
  return [backend](Config& c) {
    LinearizedOptions o;
    o.backend = backend;
    o.tolerances = read_tolerances(c);
    Config own = c.child("linearized", "options of the linearized loop");
    static const NameTable<bool> linearizations{{false, "paper"}, {true, "newton"}};
    o.newton = own.get_enum("linearization", false, linearizations,
                            "paper: W = Q as published; newton: W = Q + sum lambda Hess f (quadratic convergence)");
    o.newton_switch = own.get_number("newton_switch", o.newton_switch, 0, 1,
                                   "newton: use the Lagrangian Hessian once the length error is below this");
    o.line_search = own.get<bool>("line_search", o.line_search,
                                  "shorten steps until the l1 merit decreases (false: the paper's full steps, which can cycle)");
    static const NameTable<KktMethod> kkt_methods{{KktMethod::Direct, "direct"}, {KktMethod::Minres, "minres"}};
    o.kkt = own.get_enum("kkt", KktMethod::Direct, kkt_methods, "KKT solve: sparse direct or MINRES");
    o.minres_tolerance = own.get_number("minres_tolerance", o.minres_tolerance, 1e-16, 1e-2, "MINRES relative residual");
    o.saddle_escapes = own.get_int("saddle_escapes", o.saddle_escapes, 0, 100,
                                   "at a stationary point with negative reduced curvature (a saddle), step off it along that "
                                   "direction and go on, at most this many times; then report not_a_minimum");
    o.stall_window = own.get_int("stall_window", o.stall_window, 1, 1000000,
                                 "solves within which the distance to the tolerances must fall by a tenth, else 'stalled'");
    own.check_no_unknown_keys();
    return std::make_unique<LinearizedLengthSolver>(o);
  };
}

LengthSolverRegistry::Factory trust_region(Backend backend) {
  return [backend](Config& c) {
    TrustRegionOptions o;
    o.backend = backend;
    o.tolerances = read_tolerances(c);
    Config own = c.child("trust_region", "options of the globalized (trust-region Newton) solve");
    o.initial_radius = own.get_number("initial_radius", o.initial_radius, 1e-6, 1e6,
                                      "first trust radius, in mean segment lengths times sqrt(points)");
    o.stall_window = own.get_int("stall_window", o.stall_window, 1, 1000000,
                                 "iterations without a decrease of the objective (or stationarity) before 'stalled'");
    o.dense_limit = own.get_int("dense_limit", o.dense_limit, 0, 5000,
                                "with second_order: dense, up to this many points the reduced Hessian is formed densely every iteration");
    o.block_size = own.get_int("block_size", o.block_size, 1, 64,
                               "above dense_limit: soft modes followed by block inverse iteration, the step exact in their span "
                               "(1: one eigenvector per iteration, the method before)");
    o.block_steps = own.get_int("block_steps", o.block_steps, 1, 100, "block inverse-iteration steps per trust-region iteration");
    o.progress_window = own.get_int("progress_window", o.progress_window, 0, 1000000,
                                    "with negative curvature left: iterations within which F must fall by progress_decrease, the "
                                    "stationarity by a tenth or the negative count by half, else 'stalled' (0: off)");
    o.progress_decrease = own.get_number("progress_decrease", o.progress_decrease, 0, 1,
                                         "the relative decrease of F that counts as progress within progress_window");
    own.check_no_unknown_keys();
    return std::make_unique<TrustRegionLengthSolver>(o);
  };
}

}  // namespace

void register_length_solvers(LengthSolverRegistry& r) {
  r.add("linearized", Backend::Reference, "Sauvage et al. §3: linearized Lagrange loop, block KKT + SparseLU per solve",
        linearized(Backend::Reference));
#if FAIRSHAPE_WITH_TBB  // the optimized back ends (banded KKT, TBB assembly)
  r.add("linearized", Backend::Optimized,
        "Sauvage et al. §3: linearized Lagrange loop, banded KKT order, one analysis, LDL^T + refinement",
        linearized(Backend::Optimized));
#endif
  r.add("trust_region", Backend::Reference,
        "globalized (not in the paper): trust-region Newton on the lengths, inertia-controlled, negative-curvature steps; block KKT + SparseLU",
        trust_region(Backend::Reference));
#if FAIRSHAPE_WITH_TBB
  r.add("trust_region", Backend::Optimized,
        "globalized (not in the paper): trust-region Newton on the lengths, inertia-controlled, negative-curvature steps; banded LDL^T",
        trust_region(Backend::Optimized));
#endif
#if FAIRSHAPE_WITH_CERES  // configured with Ceres (FAIRSHAPE_WITH_CERES)
  const auto ceres = [](Config& c) {
    CeresOptions o;
    o.tolerances = read_tolerances(c);
    Config own = c.child("ceres", "options of the augmented-Lagrangian Ceres solve");
    o.initial_penalty = own.get_number("initial_penalty", o.initial_penalty, 1e-6, 1e12, "mu_0 relative to the objective's curvature");
    o.max_rounds = own.get_int("max_rounds", o.max_rounds, 1, 1000, "augmented-Lagrangian rounds");
    o.threads = own.get_int("threads", o.threads, 1, 256, "Ceres threads");
    own.check_no_unknown_keys();
    return std::make_unique<CeresLengthSolver>(o);
  };
  for (Backend b : built_backends())
    r.add("ceres", b, "exact: augmented Lagrangian over Ceres (SPARSE_NORMAL_CHOLESKY, SuiteSparse)", ceres);
#endif
  const auto projection = [](Config& c) {
    ProjectionOptions o;
    o.tolerances = read_tolerances(c);
    Config own = c.child("projection", "options of the local-global projection baseline");
    o.weight = own.get_number("weight", o.weight, 1e-6, 1e12, "penalty weight of every projection, relative to Q's largest diagonal entry");
    o.stall_window = own.get_int("stall_window", o.stall_window, 1, 1000000,
                                 "iterations without the constraint error falling by 0.1 % before 'stalled'");
    own.check_no_unknown_keys();
    return std::make_unique<ProjectionLengthSolver>(o);
  };
  for (Backend b : built_backends())
    r.add("projection", b, "baseline, not the paper's: ShapeOp-style local-global projection with penalty weights", projection);
}

}  // namespace fairshape
