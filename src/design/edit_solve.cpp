#include "design/edit_solve.h"

#include <cmath>
#include <limits>
#include <optional>

#include "core/timer.h"
#include "problem/constrained_system.h"
#include "problem/least_squares.h"
#include "qp/qp_solver.h"

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
  s.H = block_diagonal(p.H, 3);
  s.g = stack(p.g);
  const SparseMatrix A3 = block_diagonal(lc.A, 3);
  s.constraints.A = stack_rows({&A3, &lc.A_coupled});
  s.constraints.C = stacked_targets(lc, lc.C);
  return s;
}

void check_sizes(const EditProblem& p) {
  if (p.constraints.A.rows() == 0)
    throw InvalidInput(p.constraints.coupled()
                           ? "edit: normal constraints fix no position: add a point or fixed constraint"
                           : "edit: no constraint: the deformation is undetermined (add a point or fixed constraint)");
  if (p.H.rows() != p.H.cols() || p.g.rows() != p.H.rows() || p.constraints.A.cols() != p.H.rows() ||
      (p.constraints.coupled() && p.constraints.A_coupled.cols() != 3 * p.H.rows()))
    throw InvalidInput("edit: H, g and the constraints disagree in size");
}

}  // namespace

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

PreparedEdit::PreparedEdit(const EditProblem& p, ConstraintMode mode, Solver& solver, Backend backend, Config qp_options)
    : solver_(solver) {
  Timer setup;
  check_sizes(p);
  original_ = &p;
  if (p.constraints.coupled()) stacked_ = stacked(p);
  const EditProblem& s = solved();
  if (mode != ConstraintMode::Paper) {
    // The QP modes are the registered constrained solvers of src/qp, on the same program.
    const std::string name(constraint_mode_names().name(mode));
    const auto& registry = qp::qp_solver_registry();
    qp_ = registry.create(name, registry.has(name, backend) ? backend : Backend::Optimized, qp_options);
    qp_->analyze({s.H, s.g, s.constraints.A, Eigen::MatrixXd::Zero(s.constraints.A.rows(), s.g.cols()), {}});
    constrained_vertices_ = static_cast<int>(reached_columns(s.constraints.A).size());
    analyze_s_ = setup.seconds();
    return;
  }
  touched_ = reached_columns(s.constraints.A);
  ls_ = std::make_unique<MinNormLeastSquares>(s.constraints.A * row_picker(s.constraints.A.cols(), touched_), backend);
  red_ = reduce({s.H, s.g, touched_, Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(touched_.size()), s.g.cols())});
  if (!red_.free.empty()) {
    if (solver.uses_levels()) {
      if (!s.levels) throw InvalidInput("edit: a multilevel solver needs a hierarchy below the edit level");
      // The solver sees the reduced system: its finest unknowns are the free vertices.
      solver.set_levels(s.levels, {red_.free, static_cast<int>(s.H.rows() / s.levels->prolongation.back().rows())});
    }
    solver.analyze(red_.A);
  }
  analyze_s_ = setup.seconds();
}

PreparedEdit::~PreparedEdit() = default;

EditSolution PreparedEdit::solve(const Eigen::MatrixXd& C, const IterationCallback& cb, const Eigen::MatrixXd* initial,
                                 ConstrainedStart constrained) {
  const EditProblem& s = solved();
  const bool coupled = stacked_.has_value();
  const Eigen::MatrixXd targets = coupled ? stacked_targets(original_->constraints, C) : C;
  const Eigen::MatrixXd start = initial ? (coupled ? Eigen::MatrixXd(stack(*initial)) : *initial) : Eigen::MatrixXd();
  EditSolution out;
  if (qp_) {
    Timer t;
    const qp::QpReport r = qp_->solve(s.g, targets);
    out.delta = r.p;
    out.summary = {r.termination, 1, r.constraint_residual, r.message};
    out.constrained_vertices = constrained_vertices_;
    out.solve_s = t.seconds();
  } else {
    out = solve_paper(targets, initial ? &start : nullptr, constrained, cb);
  }
  out.analyze_s = analyze_s_;
  out.constraint_residual = measure_constraints_ ? (s.constraints.A * out.delta - targets).norm()
                                                 : std::numeric_limits<double>::quiet_NaN();
  if (coupled) out.delta = unstack(out.delta);
  return out;
}

double PreparedEdit::constraint_residual(const Eigen::MatrixXd& delta, const Eigen::MatrixXd& C) const {
  if (!stacked_) return (original_->constraints.A * delta - C).norm();
  return (stacked_->constraints.A * stack(delta) - stacked_targets(original_->constraints, C)).norm();
}

EditSolution PreparedEdit::solve_paper(const Eigen::MatrixXd& targets, const Eigen::MatrixXd* start,
                                       ConstrainedStart constrained, const IterationCallback& cb) {
  const EditProblem& s = solved();
  const bool coupled = stacked_.has_value();
  // Minimum norm: the paper's A⁺C. Nearest to the start: start + A⁺(C − A·start), the
  // smallest change that satisfies the rows (a prolongated coarse solution keeps its shape).
  Eigen::MatrixXd fixed;
  if (constrained == ConstrainedStart::NearestToInitial && start) {
    Eigen::MatrixXd on_touched(static_cast<Eigen::Index>(touched_.size()), start->cols());
    for (std::size_t k = 0; k < touched_.size(); ++k) on_touched.row(static_cast<Eigen::Index>(k)) = start->row(touched_[k]);
    fixed = on_touched + ls_->solve(targets - s.constraints.A * *start).X;
  } else {
    fixed = ls_->solve(targets).X;
  }
  red_.set_fixed_values(fixed);
  EditSolution out;
  out.constrained_vertices = static_cast<int>(touched_.size());
  Eigen::MatrixXd x = start ? red_.restrict_to_free(*start)
                            : Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(red_.free.size()), s.g.cols());
  if (red_.free.empty()) {
    out.summary = {Termination::Converged, 0, 0.0, "every vertex is constrained"};
  } else {
    // Callers see the whole n × 3 deformation, not the solver's reduced unknowns. The
    // reduced energy differs from the full one by a constant (the fixed vertices' part):
    // measured once, so a check costs no product with the full H.
    Eigen::MatrixXd full;
    std::optional<double> energy_offset;
    const IterationCallback expanded = [&](const IterationRecord& r) {
      full = red_.expand(*r.x);
      if (coupled) full = unstack(full);
      if (!std::isnan(r.energy) && !energy_offset)
        energy_offset = quadratic_energy(original_->H, original_->g, full) - r.energy;
      return cb({r.iteration, r.residual, r.seconds, r.energy + energy_offset.value_or(0.0), &full});
    };
    Timer t;
    out.summary = solver_.solve(red_.A, red_.b, x, cb ? expanded : IterationCallback());
    out.solve_s = t.seconds() - out.summary.observe_s;
  }
  out.delta = red_.expand(x);
  return out;
}

EditSolution solve_edit(const EditProblem& p, ConstraintMode mode, Solver& free_solver, Backend backend,
                        const IterationCallback& cb, const Eigen::MatrixXd* initial, Config qp_options) {
  return PreparedEdit(p, mode, free_solver, backend, std::move(qp_options)).solve(p.constraints.C, cb, initial);
}

}  // namespace fairshape
