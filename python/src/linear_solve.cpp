// Any registered linear solver on a symmetric positive definite system A x = b, multigrid
// included: its levels are the prolongation operators given (a hierarchy's S_l, or any
// nested transfer operators), its coarse operators Galerkin products PᵀAP.
// Every registered solver assumes a symmetric A: a non-symmetric or empty one is refused by
// name before the solve (a Cholesky factor of the lower triangle solved another matrix and
// called it converged), and a summary whose residual misses the tolerance is never a success.
// Copies: A is converted to the solver's column-major sparse format (scipy.sparse.csc_matrix of
// float64 passes without a format change; its arrays are still copied into Eigen's storage),
// b is copied, x comes back as a new array.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "checks.h"
#include "convert.h"
#include "fairshape/experiment/components.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/solver/level_operators.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace py = pybind11;

namespace fairshape::python {
namespace {

// A backward-stable factorization leaves a relative residual of about machine epsilon times
// the condition number: 1e-6 leaves room for condition numbers up to 1e10 and still catches a
// factor of another matrix. Solvers with a `tolerance` option are judged by theirs.
constexpr double kDirectTolerance = 1e-6;

// Relative to A's largest entry, so rounding in an assembly that sums in another order passes.
void check_symmetric(const SparseMatrix& A, const std::string& solver) {
  double largest = 0;
  for (Eigen::Index k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it) largest = std::max(largest, std::abs(it.value()));
  const SparseMatrix At = A.transpose();
  const SparseMatrix D = A - At;
  for (Eigen::Index k = 0; k < D.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(D, k); it; ++it)
      if (std::abs(it.value()) > 1e-10 * largest) {
        std::ostringstream m;
        m << "solve: solver '" << solver << "' needs a symmetric A (every registered solver does), but A["
          << it.row() << ", " << it.col() << "] = " << A.coeff(it.row(), it.col()) << " and A[" << it.col() << ", "
          << it.row() << "] = " << A.coeff(it.col(), it.row());
        throw InvalidInput(m.str());
      }
}

// The tolerance the summary is judged by: the one given, else the solver's default, else (a
// direct solver) kDirectTolerance; 0 when none is asked (error_tolerance alone, fixed sweeps).
double judged_tolerance(const std::string& type, Backend backend, const py::dict& options) {
  if (options.contains("tolerance")) return options["tolerance"].cast<double>();
  if (options.contains("error_tolerance")) return 0;
  const auto& reg = components().solvers;
  for (const auto& e : reg.entries())
    if (e.name == type && e.backend == backend)
      for (const auto& o : reg.options(e))
        if (o.key == "tolerance") return std::stod(o.default_value);
  return kDirectTolerance;
}

}  // namespace

void bind_linear_solve(py::module_& m) {
  m.def(
      "_solve",
      [](const SparseMatrix& A, const Eigen::MatrixXd& b, const std::string& type, const std::vector<SparseMatrix>& P,
         const std::optional<Eigen::MatrixXd>& x0, const std::string& implementation, const py::dict& options) {
        const Backend backend = backend_arg(implementation);
        if (A.rows() != A.cols()) throw InvalidInput("solve: A must be square, got " + std::to_string(A.rows()) + "×" + std::to_string(A.cols()));
        if (b.rows() != A.rows())
          throw InvalidInput("solve: b has " + std::to_string(b.rows()) + " rows, A " + std::to_string(A.rows()));
        if (b.cols() == 0) throw InvalidInput("solve: b has no column (no right-hand side to solve for)");
        finite_arg(A, "solve: A");
        finite_arg(b, "solve: b");
        if (x0) finite_arg(*x0, "solve: x0");
        for (std::size_t l = 0; l < P.size(); ++l) finite_arg(P[l], "solve: prolongations[" + std::to_string(l) + "]");
        py::dict block(options);
        if (block.contains("type")) throw InvalidConfig("solver options: give the solver by solver=NAME, not type=");
        block["type"] = type;
        Config cfg = to_config(block, "solver");
        const Components& c = components();
        (void)cfg.get_choice("type", "cholesky", c.solvers.names(), "solver name");
        const auto solver = c.solvers.create(type, backend, cfg);
        cfg.check_no_unknown_keys();
        if (A.rows() == 0)
          throw InvalidInput("solve: A is empty (0×0); solver '" + type + "' needs a system of at least one unknown");
        check_symmetric(A, type);
        const double tolerance = judged_tolerance(type, backend, options);
        if (solver->uses_levels()) {
          if (P.empty())
            throw InvalidInput("solve: solver '" + type + "' is multilevel: give prolongations=[P_0, ..., P_{L-1}] "
                               "(P_l: n_{l+1}×n_l, the last ending at A's size)");
          auto ops = std::make_shared<LevelOperators>();
          ops->prolongation = P;
          solver->set_levels(ops, LevelSelection{});
        } else if (!P.empty()) {
          throw InvalidInput("solve: solver '" + type + "' is not multilevel: prolongations are used by multigrid and "
                             "multigrid_cg only");
        }
        Eigen::MatrixXd x = x0 ? *x0 : Eigen::MatrixXd::Zero(b.rows(), b.cols());
        if (x.rows() != b.rows() || x.cols() != b.cols()) throw InvalidInput("solve: x0 must have b's shape");
        SolveSummary s;
        {
          py::gil_scoped_release release;
          solver->analyze(A);
          s = solver->solve(A, b, x);
          if (s.residual < 0) s.residual = relative_residual(A, b, x);
        }
        if (s.termination == Termination::Converged && tolerance > 0 && !(s.residual <= tolerance)) {
          std::ostringstream m;
          m << "solver '" << type << "' reported " << to_string(s.termination) << ", but its relative residual "
            << s.residual << " misses the tolerance " << tolerance << (s.message.empty() ? "" : " (" + s.message + ")");
          s.termination = Termination::NumericalFailure;
          s.message = m.str();
        }
        finite_result(x, "solve: solver '" + type + "' (" + std::string(to_string(s.termination)) + ": " + s.message + ")");
        py::dict summary;
        summary["termination"] = std::string(to_string(s.termination));
        summary["succeeded"] = s.succeeded();
        summary["iterations"] = s.iterations;
        summary["residual"] = s.residual;
        summary["message"] = s.message;
        return py::make_tuple(std::move(x), summary);
      },
      py::arg("A"), py::arg("b"), py::arg("solver"), py::arg("prolongations"), py::arg("x0"), py::arg("implementation"),
      py::arg("options"), "The solve's C++ half; call fairshape.solve().");
}

}  // namespace fairshape::python
