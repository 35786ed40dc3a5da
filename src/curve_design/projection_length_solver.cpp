#include "fairshape/curve_design/projection_length_solver.h"

#include <cmath>
#include <limits>

#include <Eigen/SparseCholesky>

#include "fairshape/core/message_format.h"
#include "fairshape/core/timer.h"
#include "fairshape/curve_design/curve_plane.h"

namespace fairshape {
namespace {

// One projection target: D X = X_b − X_a (a segment) or X_b (a pin, a = −1), to be p.
struct Projection {
  int a = -1, b = 0;
  double length = 0;  // a segment's reference length (pins: unused)
  Vec3 target = Vec3::Zero();  // a pin's position
};

// The projections of the problem's constraints; false (and `why`) for a kind it cannot project.
// A planar problem's in-plane rows (curve_plane.h) are not penalized but met exactly: after
// each global step their points are projected onto the plane (the rows' own projection). The
// rest of the data lie in the plane, so the global step leaves it by rounding only.
bool collect(const LengthProblem& p, std::vector<Projection>& out, std::vector<const InPlane*>& planes, std::string& why) {
  for (const auto& c : p.constraints()) {
    if (const auto* plane = dynamic_cast<const InPlane*>(c.get())) {
      planes.push_back(plane);
      continue;
    }
    if (const auto* s = dynamic_cast<const SegmentLengths*>(c.get())) {
      const int n = p.n_points(), segments = static_cast<int>(s->lengths().size());
      for (int i = 0; i < segments; ++i) out.push_back({i, (i + 1) % n, s->lengths()[i], Vec3::Zero()});
    } else if (const auto* pins = dynamic_cast<const PinnedPoints*>(c.get())) {
      for (std::size_t k = 0; k < pins->points().size(); ++k)
        out.push_back({-1, pins->points()[k], 0, pins->targets().row(static_cast<Eigen::Index>(k)).transpose()});
    } else if (c->has_dense_rows()) {
      why = "solver projection does not take the total_length constraint (its local step projects a few points per "
            "constraint); the solvers that do: linearized, trust_region";
      return false;
    } else {
      why = "the projection baseline projects segment lengths and pins only (and a planar problem's plane); this problem has "
            "another constraint kind";
      return false;
    }
  }
  return true;
}

}  // namespace

LengthSolveReport ProjectionLengthSolver::solve(const LengthProblem& p, const MatrixX3& start) const {
  const Timer timer;
  LengthSolveReport rep;
  rep.points = start;
  std::vector<Projection> proj;
  std::vector<const InPlane*> planes;
  std::string why;
  if (!collect(p, proj, planes, why)) {
    rep.summary.termination = Termination::InvalidInput;
    rep.summary.message = why;
    return rep;
  }
  const int N = p.n_points();
  const double w = o_.weight * std::max(p.objective_hessian().diagonal().cwiseAbs().maxCoeff(), 1e-300);
  // The global matrix, the same for x, y and z: Q + w Σ D_cᵀ D_c.
  Triplets t;
  for (const Projection& c : proj) {
    t.emplace_back(c.b, c.b, w);
    if (c.a < 0) continue;
    t.emplace_back(c.a, c.a, w);
    t.emplace_back(c.a, c.b, -w);
    t.emplace_back(c.b, c.a, -w);
  }
  SparseMatrix A(N, N);
  A.setFromTriplets(t.begin(), t.end());
  A += p.objective_hessian();
  Eigen::SimplicialLDLT<SparseMatrix> global(A);
  if (global.info() != Eigen::Success) {
    rep.summary.termination = Termination::NumericalFailure;
    rep.summary.message = "the global matrix Q + w·Σ DᵀD could not be factored";
    return rep;
  }
  MatrixX3 X = start;
  double best = INFINITY;
  int since_progress = 0;
  const auto finish = [&](Termination term, const std::string& message) {
    rep.points = X;
    rep.length_error = p.max_relative_length_error(X);
    rep.pin_error = p.max_relative_pin_error(X);
    rep.summary.residual = rep.length_error;
    rep.summary.termination = term;
    rep.summary.iterations = rep.solves;
    rep.outer_iterations = rep.solves;
    const double stat = p.stationarity(X);
    if (!rep.history.empty()) rep.history.back().stationarity = stat;
    rep.summary.message = message + ": length error " + sci(rep.length_error) + ", pins " +
                          sci(rep.pin_error) + ", stationarity " + sci(stat) + " after " +
                          std::to_string(rep.solves) + " local-global iterations (weight " + sci(o_.weight) +
                          " × Q's scale; a penalty meets hard constraints only as the weight grows)";
    return rep;
  };
  while (rep.solves < o_.tolerances.max_solves) {
    // Local step: each constraint's projection of the current curve.
    MatrixX3 rhs = p.objective_linear_term();
    for (const Projection& c : proj) {
      if (c.a < 0) {
        rhs.row(c.b) += w * c.target.transpose();
        continue;
      }
      const Vec3 d = (X.row(c.b) - X.row(c.a)).transpose();
      const double len = d.norm();
      const Vec3 pc = len > 0 ? Vec3(d * (c.length / len)) : Vec3(c.length, 0, 0);
      rhs.row(c.b) += w * pc.transpose();
      rhs.row(c.a) -= w * pc.transpose();
    }
    // Global step.
    X = global.solve(rhs);
    for (const InPlane* plane : planes)
      for (int q : plane->points()) {
        const Vec3& n = plane->plane().normal;
        X.row(q) -= n.dot(X.row(q).transpose() - plane->plane().origin) * n.transpose();
      }
    ++rep.solves;
    if (!X.allFinite()) return finish(Termination::NumericalFailure, "non-finite iterate");
    const double length_error = p.max_relative_length_error(X), err = std::max(length_error, p.max_relative_pin_error(X));
    // Stationarity (a least-squares solve) is measured on the last iterate only: NaN here.
    rep.history.push_back({rep.solves, length_error, std::numeric_limits<double>::quiet_NaN(), timer.seconds(), p.objective(X)});
    if (err <= o_.tolerances.length) {
      const double stat = p.stationarity(X);
      if (stat <= o_.tolerances.stationarity || o_.tolerances.stationarity == 0)
        return finish(Termination::Converged, "tolerances met");
    }
    if (err < 0.999 * best) {
      best = err;
      since_progress = 0;
    } else if (++since_progress >= o_.stall_window) {
      return finish(Termination::Stalled, "no progress over " + std::to_string(o_.stall_window) + " iterations");
    }
  }
  return finish(Termination::MaxIterations, "max_solves reached");
}

}  // namespace fairshape
