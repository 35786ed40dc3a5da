// The KKT and QR-penalty solvers keep their factorizations across a drag step (same H and A,
// new targets) and factor again when the rows, the energy or the unknowns change
// (papers/welch-witkin/README.md, "A drag step and its checks"); the energy's square root K is
// assembled only for QR-penalty ("Memory of deep refinement").
#include <catch2/catch.hpp>

#include <functional>

#include "fairshape/qp/kkt_solver.h"
#include "fairshape/qp/qr_penalty_solver.h"
#include "sheet_test_support.h"

using namespace fairshape;
using namespace fairshape::bspline;

namespace {

// Corner pins and a handle lifted by `lift` (the dragged one).
std::vector<SheetConstraint> drag_design(const VariationalSheet& sheet, double lift) {
  std::vector<SheetConstraint> out = test::corner_pins(sheet);
  SheetConstraint handle;
  handle.u = 4, handle.v = 3;
  handle.target = sheet.surface().position(sheet.coefficients(), 4, 3) + Vec3(0, 0, lift);
  out.push_back(handle);
  return out;
}

// A solver under test: its analyze/solve, whether the last analyze() kept the factorization,
// how many it made, and a fresh solver's answer for comparison.
struct Probe {
  qp::QpSolver& solver;
  std::function<bool()> reused;
  std::function<int()> factorizations;
  std::function<Eigen::MatrixXd(const qp::QuadraticProgram&)> fresh;
  //! How close to the fresh answer: KKT's solve repeats to the bit; SuiteSparseQR's threaded
  //! factorization does not, and Van Loan's steps carry that difference (seen: 3.3e-9).
  double tolerance = 1e-12;
};

// analyze() then solve(): whether it reused, and that the answer is a fresh solver's.
void step(Probe& probe, const qp::QuadraticProgram& program, bool expect_reuse) {
  const int before = probe.factorizations();
  probe.solver.analyze(program);
  CHECK(probe.reused() == expect_reuse);
  CHECK((probe.factorizations() == before) == expect_reuse);
  const qp::QpReport r = probe.solver.solve(program.f, program.b);
  REQUIRE(r.summary.termination == Termination::Converged);
  CHECK((r.p - probe.fresh(program)).cwiseAbs().maxCoeff() <= probe.tolerance);
}

// Drags (reused), an added constraint (A changes), other weights (H changes), a refinement.
void check_reuse(Probe& probe) {
  VariationalSheet sheet = test::flat_sheet();
  SheetEnergy energy;
  energy.weights.alpha = 0.01 * Eigen::Matrix2d::Identity();
  step(probe, assemble(sheet, energy, drag_design(sheet, 0.3), Backend::Optimized), false);
  for (const double lift : {0.31, 0.35, -0.2}) {
    INFO("lift " << lift);
    step(probe, assemble(sheet, energy, drag_design(sheet, lift), Backend::Optimized), true);
  }
  std::vector<SheetConstraint> more = drag_design(sheet, 0.3);
  SheetConstraint extra;
  extra.u = 2, extra.v = 6;
  extra.target = Vec3(0.5, 1.5, 0.1);
  more.push_back(extra);
  step(probe, assemble(sheet, energy, more, Backend::Optimized), false);
  SheetEnergy stiffer = energy;
  stiffer.weights.alpha = 0.1 * Eigen::Matrix2d::Identity();
  step(probe, assemble(sheet, stiffer, more, Backend::Optimized), false);
  sheet.refine({{0, 3, 3}});
  step(probe, assemble(sheet, energy, more, Backend::Optimized), false);
}

}  // namespace

TEST_CASE("KKT: a drag step reuses the factored system and equals a fresh solve, changed rows, energy or unknowns refactor",
          "[qp][kkt_reuse]") {
  qp::KktSolver kkt(Backend::Optimized);
  Probe probe{kkt, [&] { return kkt.reused_factorization(); }, [&] { return kkt.factorizations(); },
              [](const qp::QuadraticProgram& p) {
                qp::KktSolver fresh(Backend::Optimized);
                fresh.analyze(p);
                return fresh.solve(p.f, p.b).p;
              }};
  check_reuse(probe);
}

TEST_CASE("QR-penalty: a drag step reuses R and equals a fresh solve, changed rows, energy or unknowns refactor",
          "[qp][kkt_reuse]") {
  qp::QrPenaltySolver qr(Backend::Optimized, {});
  Probe probe{qr, [&] { return qr.reused_factorization(); }, [&] { return qr.factorizations(); },
              [](const qp::QuadraticProgram& p) {
                qp::QrPenaltySolver fresh(Backend::Optimized, {});
                fresh.analyze(p);
                return fresh.solve(p.f, p.b).p;
              },
              1e-7};
  check_reuse(probe);
  // Asked not to reuse: every analyze() factors.
  qp::QrPenaltyOptions always;
  always.reuse_factorization = false;
  qp::QrPenaltySolver every(Backend::Optimized, always);
  const VariationalSheet sheet = test::flat_sheet();
  const qp::QuadraticProgram program = assemble(sheet, {}, drag_design(sheet, 0.3), Backend::Optimized);
  every.analyze(program);
  every.analyze(program);
  CHECK_FALSE(every.reused_factorization());
  CHECK(every.factorizations() == 2);
}

TEST_CASE("the energy's square root K is assembled only for QR-penalty, once per surface", "[qp][kkt_reuse]") {
  VariationalSheet sheet = test::flat_sheet();
  const SheetEnergy energy;
  const std::vector<SheetConstraint> constraints = drag_design(sheet, 0.3);
  qp::KktSolver kkt(Backend::Optimized);
  REQUIRE(solve_sheet(sheet, energy, constraints, kkt, {}, Backend::Optimized).qp.summary.termination == Termination::Converged);
  CHECK(sheet.thin_plate(energy.weights, Backend::Optimized).K == nullptr);  // never assembled for KKT
  qp::QrPenaltySolver qr(Backend::Optimized, {});
  const Eigen::MatrixXd kkt_answer = sheet.coefficients();
  REQUIRE(solve_sheet(sheet, energy, constraints, qr, {}, Backend::Optimized).qp.summary.termination == Termination::Converged);
  const auto& plate = sheet.thin_plate(energy.weights, Backend::Optimized);
  REQUIRE(plate.K != nullptr);
  CHECK((SparseMatrix(plate.K->transpose()) * *plate.K - plate.H).norm() <= 1e-10 * plate.H.norm());  // KᵀK = H
  CHECK((sheet.coefficients() - kkt_answer).cwiseAbs().maxCoeff() <= 1e-6);
  const SparseMatrix* first = plate.K.get();
  (void)sheet.thin_plate_square_root(energy.weights, Backend::Optimized);
  CHECK(plate.K.get() == first);  // kept, not assembled again
}
