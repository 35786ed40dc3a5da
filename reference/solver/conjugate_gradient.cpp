// Reference `conjugate_gradient`: the shared CG algorithm with Eigen's serial product. It keeps
// nothing from analyze(): every solve works on the A it is given (solver.h).
#include "fairshape/solver/conjugate_gradient.h"

namespace fairshape::reference {
namespace {

class SerialCg : public Solver {
 public:
  explicit SerialCg(IterativeOptions opt) : opt_(opt) {}
  void analyze(const SparseMatrix&) override {}
  SolveSummary solve(const SparseMatrix& A, const Eigen::MatrixXd& b, Eigen::MatrixXd& x,
                     const IterationCallback& cb) override {
    auto multiply = [&A](const Eigen::MatrixXd& p) -> Eigen::MatrixXd { return A * p; };
    return conjugate_gradient(multiply, Eigen::VectorXd(A.diagonal()), b, x, opt_, cb);
  }

 private:
  IterativeOptions opt_;
};

}  // namespace

std::unique_ptr<Solver> make_serial_cg(Config& cfg) {
  return std::make_unique<SerialCg>(IterativeOptions::from_config(cfg));
}

}  // namespace fairshape::reference
