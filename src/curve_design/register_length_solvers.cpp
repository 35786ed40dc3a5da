#include "core/config.h"
#include "curve_design/ceres_length_solver.h"
#include "curve_design/linearized_length_solver.h"

namespace fairshape {
namespace {

LengthTolerances read_tolerances(Config& c) {
  LengthTolerances t;
  t.length = c.get_number("length_tolerance", t.length, 0, 1, "stop when every segment's relative length error is below");
  t.stationarity = c.get_number("stationarity_tolerance", t.stationarity, 0, 1,
                                "and |grad F + J^T lambda| / (|QX| + |b|) is below (0: lengths alone, as the paper)");
  t.max_solves = c.get_int("max_solves", t.max_solves, 1, 1000000, "give up after this many linear solves");
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
    own.check_no_unknown_keys();
    return std::make_unique<LinearizedLengthSolver>(o);
  };
}

}  // namespace

void register_length_solvers(LengthSolverRegistry& r) {
  r.add("linearized", Backend::Reference, "Sauvage et al. §3: linearized Lagrange loop, block KKT + SparseLU per solve",
        linearized(Backend::Reference));
  r.add("linearized", Backend::Optimized,
        "Sauvage et al. §3: linearized Lagrange loop, banded KKT order, one analysis, LDL^T + refinement",
        linearized(Backend::Optimized));
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
  for (Backend b : {Backend::Reference, Backend::Optimized})
    r.add("ceres", b, "exact: augmented Lagrangian over Ceres (SPARSE_NORMAL_CHOLESKY, SuiteSparse)", ceres);
}

}  // namespace fairshape
