// Any registered linear solver on a symmetric positive definite system A x = b, multigrid
// included: its levels are the prolongation operators given (a hierarchy's S_l, or any
// nested transfer operators), its coarse operators Galerkin products PᵀAP.
// Copies: A is converted to the solver's column-major sparse format (scipy.sparse.csc_matrix of
// float64 passes without a format change; its arrays are still copied into Eigen's storage),
// b is copied, x comes back as a new array.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "convert.h"
#include "fairshape/experiment/components.h"
#include "fairshape/solver/level_operators.h"

namespace py = pybind11;

namespace fairshape::python {

void bind_linear_solve(py::module_& m) {
  m.def(
      "_solve",
      [](const SparseMatrix& A, const Eigen::MatrixXd& b, const std::string& type, const std::vector<SparseMatrix>& P,
         const std::optional<Eigen::MatrixXd>& x0, const std::string& implementation, const py::dict& options) {
        const Backend backend = backend_arg(implementation);
        if (A.rows() != A.cols()) throw InvalidInput("solve: A must be square, got " + std::to_string(A.rows()) + "×" + std::to_string(A.cols()));
        if (b.rows() != A.rows())
          throw InvalidInput("solve: b has " + std::to_string(b.rows()) + " rows, A " + std::to_string(A.rows()));
        py::dict block(options);
        if (block.contains("type")) throw InvalidConfig("solver options: give the solver by solver=NAME, not type=");
        block["type"] = type;
        Config cfg = to_config(block, "solver");
        const Components& c = components();
        (void)cfg.get_choice("type", "cholesky", c.solvers.names(), "solver name");
        const auto solver = c.solvers.create(type, backend, cfg);
        cfg.check_no_unknown_keys();
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
        }
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
