#include "fairshape/design/edit_solve.h"

#include <cmath>
#include <limits>
#include <optional>

#include "fairshape/core/timer.h"
#include "fairshape/design/constrained_freedom.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/problem/least_squares.h"
#include "fairshape/qp/qp_solver.h"
#include "fairshape/qp/split_solver.h"

namespace fairshape {

namespace {

// Columns x, y, z stacked into one: an n × 3 matrix is, column-major, already [x; y; z].
Eigen::VectorXd stack(const Eigen::MatrixXd& M) { return Eigen::Map<const Eigen::VectorXd>(M.data(), M.size()); }
Eigen::MatrixXd unstack(const Eigen::MatrixXd& v) { return Eigen::Map<const Eigen::MatrixXd>(v.data(), v.size() / 3, 3); }

// The one coupled system of §5 on [Δx; Δy; Δz]: H three times on the diagonal, each point
// row three times, then the normal rows.
EditProblem stacked(const EditProblem& p) {
  const LinearConstraints& lc = p.constraints;
  EditProblem s;
  s.levels = p.levels;
  s.anchored = p.anchored;
  s.H = block_diagonal(p.H, 3);
  s.g = stack(p.g);
  const SparseMatrix A3 = block_diagonal(lc.A, 3);
  s.constraints.A = stack_rows({&A3, &lc.A_coupled});
  s.constraints.C = stacked_targets(lc, lc.C);
  return s;
}

void check_sizes(const EditProblem& p) {
  if (!p.anchored) require_fixed_position(p.constraints);
  if (p.H.rows() != p.H.cols() || p.g.rows() != p.H.rows() || p.constraints.A.cols() != p.H.rows() ||
      (p.constraints.coupled() && p.constraints.A_coupled.cols() != 3 * p.H.rows()))
    throw InvalidInput("edit: H, g and the constraints disagree in size");
}

}  // namespace

double edit_energy(const EditProblem& p, const Eigen::MatrixXd& delta) {
  return quadratic_energy(p.H, p.g, delta) + p.energy_at_rest;
}

Eigen::MatrixXd stacked_targets(const LinearConstraints& lc, const Eigen::MatrixXd& C) {
  Eigen::MatrixXd out(3 * C.rows() + lc.C_coupled.rows(), 1);
  out << stack(C), lc.C_coupled;
  return out;
}

const NameTable<ConstraintMode>& constraint_mode_names() {
  static const NameTable<ConstraintMode> t{{ConstraintMode::Paper, "paper"},
                                           {ConstraintMode::Kkt, "kkt"},
                                           {ConstraintMode::QrPenalty, "qr_penalty"},
                                           {ConstraintMode::RangeSpace, "range_space"}};
  return t;
}

PreparedEdit::PreparedEdit(const EditProblem& p, ConstraintMode mode, Solver& solver, Backend backend, Config qp_options) {
  Timer setup;
  check_sizes(p);
  original_ = &p;
  if (p.constraints.coupled()) stacked_ = stacked(p);
  const EditProblem& s = solved();
  // Every mode is a constrained solver of src/qp on one program: the paper's split with this
  // run's linear solver for the free vertices, the others the registered solver of that name.
  if (mode == ConstraintMode::Paper) {
    qp_ = std::make_unique<qp::SplitSolver>(solver, backend);
  } else {
    const std::string name(constraint_mode_names().name(mode));
    const auto& registry = qp::qp_solver_registry();
    qp_ = registry.create(name, registry.has(name, backend) ? backend : kFastestBackend, qp_options);
  }
  // H is lent, not copied: the problem outlives this edit (documented in edit_solve.h).
  qp::QuadraticProgram program{{}, s.g, s.constraints.A, Eigen::MatrixXd::Zero(s.constraints.A.rows(), s.g.cols()), {}, {}};
  program.borrowed_H = &s.H;
  program.levels = s.levels;
  qp_->analyze(program);
  constrained_vertices_ = static_cast<int>(reached_columns(s.constraints.A).size());
  paper_ = mode == ConstraintMode::Paper;
  analyze_s_ = setup.seconds();
}

PreparedEdit::~PreparedEdit() = default;

EditSolution PreparedEdit::solve(const Eigen::MatrixXd& C, const IterationCallback& cb, const Eigen::MatrixXd* initial,
                                 ConstrainedStart constrained) {
  const EditProblem& s = solved();
  const bool coupled = stacked_.has_value();
  const Eigen::MatrixXd targets = coupled ? stacked_targets(original_->constraints, C) : C;
  const Eigen::MatrixXd start = initial ? (coupled ? Eigen::MatrixXd(stack(*initial)) : *initial) : Eigen::MatrixXd();
  // Callers see the n × 3 deformation, not the coupled system's stacked [Δx; Δy; Δz].
  Eigen::MatrixXd unstacked;
  const IterationCallback as_columns = [&](const IterationRecord& r) {
    unstacked = unstack(*r.x);
    return cb({r.iteration, r.residual, r.seconds, r.energy, &unstacked});
  };
  qp::QpSolveOptions options;
  options.initial = initial ? &start : nullptr;
  options.callback = cb && coupled ? as_columns : cb;
  options.nearest_to_initial = constrained == ConstrainedStart::NearestToInitial;
  options.measure_residual = false;  // measured below, when asked
  EditSolution out;
  Timer t;
  const qp::QpReport r = qp_->solve(g_ ? *g_ : s.g, targets, options);
  out.solve_s = t.seconds() - r.summary.observe_s;
  out.delta = r.p;
  out.summary = r.summary;
  if (!paper_) out.summary.residual = r.constraint_residual;  // a direct solve: its constraint residual
  out.constrained_vertices = constrained_vertices_;
  out.analyze_s = analyze_s_;
  out.constraint_residual = measure_constraints_ ? (s.constraints.A * out.delta - targets).norm()
                                                 : std::numeric_limits<double>::quiet_NaN();
  if (coupled) out.delta = unstack(out.delta);
  return out;
}

EditSolution PreparedEdit::solve_to_optimum(const Eigen::MatrixXd& C, const IterationCallback& cb,
                                            const Eigen::MatrixXd* initial) {
  EditSolution out = solve(C, cb, initial, ConstrainedStart::NearestToInitial);
  if (!paper_ || !is_success(out.summary.termination)) return out;
  const EditProblem& s = solved();
  // The freedom depends on the rows only; found once per analysis.
  if (!freedom_) freedom_ = constrained_freedom(s.constraints.A, 4 * kMaxFreedom);
  const Eigen::Index d = freedom_->basis.cols();
  if (freedom_->columns.empty() || d == 0) return out;
  if (d > kMaxFreedom) {
    out.summary.message += (out.summary.message.empty() ? "" : "; ") + std::string("the constrained unknowns keep the "
                           "split's values (") + std::to_string(d) + " free directions, above " + std::to_string(kMaxFreedom) + ")";
    return out;
  }
  Timer t;
  const bool coupled = stacked_.has_value();
  const Eigen::Index k = s.g.cols();
  Eigen::MatrixXd x = coupled ? Eigen::MatrixXd(stack(out.delta)) : out.delta;
  // W's column j: the constrained unknowns moved along basis column j, the free ones following
  // (the split of the homogeneous problem started there keeps the constrained values: they meet
  // the zero rows). The same for every coordinate column, so the first one is taken.
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(x.rows(), d);
  const Eigen::MatrixXd zero_f = Eigen::MatrixXd::Zero(s.g.rows(), k);
  const Eigen::MatrixXd zero_b = Eigen::MatrixXd::Zero(s.constraints.A.rows(), k);
  int iterations = out.summary.iterations;
  for (Eigen::Index j = 0; j < d; ++j) {
    Eigen::MatrixXd start = Eigen::MatrixXd::Zero(x.rows(), k);
    for (std::size_t c = 0; c < freedom_->columns.size(); ++c)
      start.row(freedom_->columns[c]).setConstant(freedom_->basis(static_cast<Eigen::Index>(c), j));
    qp::QpSolveOptions o;
    o.initial = &start;
    o.nearest_to_initial = true;
    o.measure_residual = false;
    const qp::QpReport r = qp_->solve(zero_f, zero_b, o);
    if (!is_success(r.summary.termination)) {
      out.summary.message += (out.summary.message.empty() ? "" : "; ") + std::string("the constrained unknowns keep the "
                             "split's values (a free direction's solve ended ") + std::string(to_string(r.summary.termination)) + ")";
      return out;
    }
    W.col(j) = r.p.col(0);
    iterations += r.summary.iterations;
  }
  const SparseMatrix& H = s.H;
  const Eigen::MatrixXd HW = H * W;
  // The energy's minimum over x + W y: (WᵀHW) y = −Wᵀ(Hx − g).
  const Eigen::MatrixXd y = (W.transpose() * HW).ldlt().solve(-(HW.transpose() * x - W.transpose() * (g_ ? *g_ : s.g)));
  x += W * y;
  out.delta = coupled ? unstack(x) : x;
  out.summary.iterations = iterations;
  out.summary.message += (out.summary.message.empty() ? "" : "; ") + std::string("constrained unknowns optimized over ") +
                         std::to_string(d) + " free direction(s) of their rows";
  if (measure_constraints_) {
    const Eigen::MatrixXd targets = coupled ? stacked_targets(original_->constraints, C) : C;
    out.constraint_residual = (s.constraints.A * x - targets).norm();
  }
  out.solve_s += t.seconds();
  return out;
}

void PreparedEdit::set_linear_term(const Eigen::MatrixXd& g) {
  if (g.rows() != original_->g.rows() || g.cols() != original_->g.cols())
    throw InvalidInput("edit: a linear term of " + std::to_string(g.rows()) + " x " + std::to_string(g.cols()) +
                       " for a problem of " + std::to_string(original_->g.rows()) + " x " + std::to_string(original_->g.cols()));
  g_ = stacked_ ? Eigen::MatrixXd(stack(g)) : g;
}

double PreparedEdit::constraint_residual(const Eigen::MatrixXd& delta, const Eigen::MatrixXd& C) const {
  if (!stacked_) return (original_->constraints.A * delta - C).norm();
  return (stacked_->constraints.A * stack(delta) - stacked_targets(original_->constraints, C)).norm();
}

EditSolution solve_edit(const EditProblem& p, ConstraintMode mode, Solver& free_solver, Backend backend,
                        const IterationCallback& cb, const Eigen::MatrixXd* initial, Config qp_options) {
  return PreparedEdit(p, mode, free_solver, backend, std::move(qp_options)).solve(p.constraints.C, cb, initial);
}

MultiresSurface with_deformation(const MultiresSurface& rest, int level, const Eigen::MatrixXd& delta) {
  MultiresSurface edited = rest;
  edited.set_level_positions(level, rest.mesh(level).positions() + MatrixX3(delta));
  edited.synthesize_from(level, DetailSpace::Local);
  return edited;
}

}  // namespace fairshape
