// The KKT and QR-penalty solvers keep their factorizations across a drag step (same H and A,
// new targets) and factor again when the rows or the energy change (papers/welch-witkin/README.md,
// "A drag step and its checks").
#include <catch2/catch.hpp>

#include "fairshape/bspline/sheet_geometry.h"
#include "fairshape/bspline/variational_sheet.h"
#include "fairshape/qp/kkt_solver.h"
#include "fairshape/qp/qr_penalty_solver.h"

using namespace fairshape;
using namespace fairshape::bspline;

namespace {

std::vector<SheetConstraint> pins(const VariationalSheet& sheet, double lift) {
  std::vector<SheetConstraint> out;
  for (double u : {0.5, 7.5})
    for (double v : {0.5, 7.5}) {
      SheetConstraint c;
      c.u = u, c.v = v;
      c.target = sheet.surface().position(sheet.coefficients(), u, v);
      out.push_back(c);
    }
  SheetConstraint handle;  // the dragged one
  handle.u = 4, handle.v = 3;
  handle.target = sheet.surface().position(sheet.coefficients(), 4, 3) + Vec3(0, 0, lift);
  out.push_back(handle);
  return out;
}

Eigen::MatrixXd fresh_solve(const qp::QuadraticProgram& p) {
  qp::KktSolver fresh(Backend::Optimized);
  fresh.analyze(p);
  return fresh.solve(p.f, p.b).p;
}

}  // namespace

TEST_CASE("KKT: a drag step reuses the factored system and equals a fresh solve, changed rows or energy refactor",
          "[qp][kkt_reuse]") {
  const SheetShape shape{8, 8, 3, false, {0.25, 0.25}};
  SheetPlacement placement;
  placement.size_u = placement.size_v = 2;
  VariationalSheet sheet(shape, initial_coefficients(placement, HierarchicalSurface(shape)));
  SheetEnergy energy;
  energy.weights.alpha = 0.01 * Eigen::Matrix2d::Identity();
  qp::KktSolver kkt(Backend::Optimized);

  const qp::QuadraticProgram first = assemble(sheet, energy, pins(sheet, 0.3), Backend::Optimized);
  kkt.analyze(first);
  CHECK_FALSE(kkt.reused_factorization());
  const int factored = kkt.factorizations();
  REQUIRE(factored >= 1);

  for (const double lift : {0.31, 0.35, -0.2}) {  // drag steps: only the handle's target moves
    INFO("lift " << lift);
    const qp::QuadraticProgram step = assemble(sheet, energy, pins(sheet, lift), Backend::Optimized);
    kkt.analyze(step);
    CHECK(kkt.reused_factorization());
    CHECK(kkt.factorizations() == factored);
    const qp::QpReport r = kkt.solve(step.f, step.b);
    REQUIRE(r.summary.termination == Termination::Converged);
    CHECK((r.p - fresh_solve(step)).cwiseAbs().maxCoeff() <= 1e-12);
  }

  // A constraint added: A changes, the system is factored again.
  std::vector<SheetConstraint> more = pins(sheet, 0.3);
  SheetConstraint extra;
  extra.u = 2, extra.v = 6;
  extra.target = Vec3(0.5, 1.5, 0.1);
  more.push_back(extra);
  const qp::QuadraticProgram added = assemble(sheet, energy, more, Backend::Optimized);
  kkt.analyze(added);
  CHECK_FALSE(kkt.reused_factorization());
  CHECK(kkt.factorizations() > factored);
  CHECK((kkt.solve(added.f, added.b).p - fresh_solve(added)).cwiseAbs().maxCoeff() <= 1e-12);

  // Other weights: H changes, the system is factored again.
  const int before = kkt.factorizations();
  SheetEnergy stiffer = energy;
  stiffer.weights.alpha = 0.1 * Eigen::Matrix2d::Identity();
  const qp::QuadraticProgram reweighted = assemble(sheet, stiffer, more, Backend::Optimized);
  kkt.analyze(reweighted);
  CHECK_FALSE(kkt.reused_factorization());
  CHECK(kkt.factorizations() > before);
  CHECK((kkt.solve(reweighted.f, reweighted.b).p - fresh_solve(reweighted)).cwiseAbs().maxCoeff() <= 1e-12);

  // Refined: the unknowns change, the system is factored again.
  const int before_refine = kkt.factorizations();
  sheet.refine({{0, 3, 3}});
  const qp::QuadraticProgram refined = assemble(sheet, energy, more, Backend::Optimized);
  kkt.analyze(refined);
  CHECK_FALSE(kkt.reused_factorization());
  CHECK(kkt.factorizations() > before_refine);
  CHECK((kkt.solve(refined.f, refined.b).p - fresh_solve(refined)).cwiseAbs().maxCoeff() <= 1e-12);
}

TEST_CASE("QR-penalty: a drag step reuses R and equals a fresh solve, changed rows refactor", "[qp][kkt_reuse]") {
  const SheetShape shape{8, 8, 3, false, {0.25, 0.25}};
  SheetPlacement placement;
  placement.size_u = placement.size_v = 2;
  VariationalSheet sheet(shape, initial_coefficients(placement, HierarchicalSurface(shape)));
  SheetEnergy energy;
  energy.weights.alpha = 0.01 * Eigen::Matrix2d::Identity();
  qp::QrPenaltySolver qr(Backend::Optimized, {});
  const auto fresh = [](const qp::QuadraticProgram& p) {
    qp::QrPenaltySolver solver(Backend::Optimized, {});
    solver.analyze(p);
    return solver.solve(p.f, p.b).p;
  };
  const qp::QuadraticProgram first = assemble(sheet, energy, pins(sheet, 0.3), Backend::Optimized);
  qr.analyze(first);
  (void)qr.solve(first.f, first.b);
  for (const double lift : {0.31, 0.29}) {
    const qp::QuadraticProgram step = assemble(sheet, energy, pins(sheet, lift), Backend::Optimized);
    const int before = qr.factorizations();
    qr.analyze(step);
    CHECK(qr.reused_factorization());
    CHECK(qr.factorizations() == before);
    const qp::QpReport r = qr.solve(step.f, step.b);
    REQUIRE(r.summary.termination == Termination::Converged);
    CHECK((r.p - fresh(step)).cwiseAbs().maxCoeff() <= 1e-12);
  }
  std::vector<SheetConstraint> more = pins(sheet, 0.3);
  more.front().target.z() = 0.05;
  SheetConstraint extra;
  extra.u = 2, extra.v = 6;
  extra.target = Vec3(0.5, 1.5, 0.1);
  more.push_back(extra);
  const qp::QuadraticProgram added = assemble(sheet, energy, more, Backend::Optimized);
  qr.analyze(added);
  CHECK_FALSE(qr.reused_factorization());
  CHECK((qr.solve(added.f, added.b).p - fresh(added)).cwiseAbs().maxCoeff() <= 1e-12);
  // Asked not to reuse: every analyze() factors.
  qp::QrPenaltyOptions always;
  always.reuse_factorization = false;
  qp::QrPenaltySolver every(Backend::Optimized, always);
  every.analyze(added);
  every.analyze(added);
  CHECK_FALSE(every.reused_factorization());
  CHECK(every.factorizations() == 2);
}

TEST_CASE("the energy's square root K is assembled only for QR-penalty, once per surface", "[qp][kkt_reuse]") {
  const SheetShape shape{8, 8, 3, false, {0.25, 0.25}};
  SheetPlacement placement;
  placement.size_u = placement.size_v = 2;
  VariationalSheet sheet(shape, initial_coefficients(placement, HierarchicalSurface(shape)));
  SheetEnergy energy;
  const std::vector<SheetConstraint> constraints = pins(sheet, 0.3);
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
