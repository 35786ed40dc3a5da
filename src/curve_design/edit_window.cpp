#include "fairshape/curve_design/edit_window.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "fairshape/curve_design/curve_plane.h"

namespace fairshape {
namespace {

// The window's share of every stencil that touches one of its free points; the fixed points'
// share becomes the stencil's constant.
std::vector<WeightedStencils> window_energies(const LengthProblem& whole, const std::vector<int>& where,
                                              const std::vector<char>& free) {
  const MatrixX3& A = whole.attractor();
  std::vector<WeightedStencils> out;
  for (const auto& term : whole.energies()) {
    WeightedStencils w{term.name, term.weight, {}};
    for (const auto& s : term.stencils) {
      bool touches_free = false;
      for (int j = 0; j < s.size; ++j) touches_free |= free[static_cast<std::size_t>(s.points[j])] != 0;
      if (!touches_free) continue;
      CurveStencil t;
      t.constant = s.constant;
      for (int j = 0; j < s.size; ++j) {
        const int p = s.points[j], q = where[static_cast<std::size_t>(p)];
        if (q < 0) {
          t.constant -= s.coeffs[j] * A.row(p).transpose();
          continue;
        }
        t.points[t.size] = q;
        t.coeffs[t.size++] = s.coeffs[j];
      }
      if (s.attractor_point >= 0) {
        const int q = where[static_cast<std::size_t>(s.attractor_point)];
        if (q >= 0) t.attractor_point = q;
        else t.constant += A.row(s.attractor_point).transpose();
      }
      w.stencils.push_back(t);
    }
    out.push_back(std::move(w));
  }
  return out;
}

EditWindow build_window(const LengthProblem& whole, std::vector<int> pts, bool closed_window, const std::vector<char>& support) {
  const int n = whole.n_points(), nw = static_cast<int>(pts.size());
  std::vector<int> where(static_cast<std::size_t>(n), -1);
  for (int k = 0; k < nw; ++k) where[static_cast<std::size_t>(pts[static_cast<std::size_t>(k)])] = k;
  // Pins: the window's fixed points at their place in C_A, and the user's pins inside it.
  std::map<int, Vec3> pins;
  for (int k = 0; k < nw; ++k)
    if (!support[static_cast<std::size_t>(pts[static_cast<std::size_t>(k)])])
      pins[k] = whole.attractor().row(pts[static_cast<std::size_t>(k)]).transpose();
  for (const auto& c : whole.constraints())
    if (const auto* p = dynamic_cast<const PinnedPoints*>(c.get()))
      for (std::size_t k = 0; k < p->points().size(); ++k) {
        const int q = where[static_cast<std::size_t>(p->points()[k])];
        if (q >= 0 && !pins.count(q)) pins[q] = p->targets().row(static_cast<Eigen::Index>(k)).transpose();
      }
  std::vector<char> free(static_cast<std::size_t>(n), 0);
  for (int k = 0; k < nw; ++k) free[static_cast<std::size_t>(pts[static_cast<std::size_t>(k)])] = !pins.count(k);

  MatrixX3 attractor(nw, 3);
  for (int k = 0; k < nw; ++k) attractor.row(k) = whole.attractor().row(pts[static_cast<std::size_t>(k)]);
  const Eigen::VectorXd& l = whole.reference_lengths();
  Eigen::VectorXd lengths(closed_window ? nw : nw - 1);
  for (int k = 0; k < lengths.size(); ++k) lengths[k] = l[pts[static_cast<std::size_t>(k)]];  // segment p → p+1
  std::vector<std::unique_ptr<CurveConstraint>> constraints;
  constraints.push_back(std::make_unique<SegmentLengths>(lengths, closed_window));
  if (!pins.empty()) {
    std::vector<int> idx;
    MatrixX3 targets(static_cast<Eigen::Index>(pins.size()), 3);
    for (const auto& [k, x] : pins) {
      targets.row(static_cast<Eigen::Index>(idx.size())) = x.transpose();
      idx.push_back(k);
    }
    constraints.push_back(std::make_unique<PinnedPoints>(std::move(idx), std::move(targets)));
  }
  // A planar problem's in-plane rows on the window's free points (pinned ones are held already).
  for (const auto& c : whole.constraints())
    if (const auto* plane = dynamic_cast<const InPlane*>(c.get())) {
      std::vector<int> idx;
      for (int p : plane->points()) {
        const int q = where[static_cast<std::size_t>(p)];
        if (q >= 0 && !pins.count(q)) idx.push_back(q);
      }
      if (!idx.empty()) constraints.push_back(std::make_unique<InPlane>(std::move(idx), plane->plane()));
    }
  EditWindow w;
  w.problem = std::make_unique<LengthProblem>(std::move(attractor), closed_window,
                                              window_energies(whole, where, free), std::move(constraints));
  w.points = std::move(pts);
  return w;
}

}  // namespace

std::vector<EditWindow> edit_windows(const LengthProblem& whole, const std::vector<char>& support) {
  const int n = whole.n_points();
  const bool closed = whole.closed();
  if (std::all_of(support.begin(), support.end(), [](char s) { return s != 0; })) return {};
  for (const auto& c : whole.constraints())  // a window rebuilds lengths and pins; others would be dropped
    if (!dynamic_cast<const SegmentLengths*>(c.get()) && !dynamic_cast<const PinnedPoints*>(c.get()) &&
        !dynamic_cast<const InPlane*>(c.get()))
      throw InvalidInput("solve_region support: only segment lengths and pins are solved on the edit's support; "
                         "use solve_region: curve for other constraints (tangent)");
  const auto fixed = [&](int i) {
    if (closed) i = ((i % n) + n) % n;
    return i >= 0 && i < n && !support[static_cast<std::size_t>(i)];
  };
  // Cut points: fixed points with a fixed neighbour (runs of ≥ 2 separate the windows).
  std::vector<char> cut(static_cast<std::size_t>(n), 0);
  int first_cut = -1;
  for (int i = 0; i < n; ++i) {
    cut[static_cast<std::size_t>(i)] = fixed(i) && (fixed(i - 1) || fixed(i + 1));
    if (cut[static_cast<std::size_t>(i)] && first_cut < 0) first_cut = i;
  }
  std::vector<EditWindow> out;
  if (first_cut < 0) {  // every fixed point alone: the whole curve, those points pinned
    std::vector<int> all(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) all[static_cast<std::size_t>(i)] = i;
    out.push_back(build_window(whole, std::move(all), closed, support));
    return out;
  }
  // Scan from a cut point (closed) or from the start (open); a run of non-cut points plus the
  // cut neighbour on each side is a window.
  const int start = closed ? first_cut : 0;
  const auto at = [&](int k) { return closed ? (start + k) % n : k; };
  for (int k = 0; k < n;) {
    if (cut[static_cast<std::size_t>(at(k))]) {
      ++k;
      continue;
    }
    int end = k;
    while (end < n && !cut[static_cast<std::size_t>(at(end))]) ++end;  // [k, end)
    std::vector<int> pts;
    if (k > 0 || closed) pts.push_back(at((k - 1 + n) % n));
    bool any_free = false;
    for (int j = k; j < end; ++j) {
      pts.push_back(at(j));
      any_free |= support[static_cast<std::size_t>(at(j))] != 0;
    }
    if (end < n || closed) pts.push_back(at(end % n));
    if (any_free) out.push_back(build_window(whole, std::move(pts), false, support));
    k = end;
  }
  return out;
}

LengthSolveReport solve_windows(const LengthProblem& whole, const std::vector<EditWindow>& windows,
                                const LengthSolver& solver) {
  LengthSolveReport out;
  out.points = whole.attractor();
  out.summary.termination = Termination::Converged;
  out.min_reduced_hessian_eig = std::numeric_limits<double>::infinity();
  std::string messages;
  for (std::size_t w = 0; w < windows.size(); ++w) {
    const EditWindow& win = windows[w];
    const LengthSolveReport r = solver.solve(*win.problem, win.problem->attractor());
    for (std::size_t k = 0; k < win.points.size(); ++k)
      out.points.row(win.points[k]) = r.points.row(static_cast<Eigen::Index>(k));
    for (LengthSolveStep s : r.history) {
      s.solves += out.solves;
      out.history.push_back(s);
    }
    out.solves += r.solves;
    out.outer_iterations += r.outer_iterations;
    out.saddle_escapes += r.saddle_escapes;
    out.summary.iterations += r.summary.iterations;
    out.summary.observe_s += r.summary.observe_s;
    out.min_reduced_hessian_eig = std::isnan(r.min_reduced_hessian_eig) || std::isnan(out.min_reduced_hessian_eig)
                                      ? std::nan("")
                                      : std::min(out.min_reduced_hessian_eig, r.min_reduced_hessian_eig);
    if (out.summary.termination == Termination::Converged && !r.converged()) out.summary.termination = r.summary.termination;
    messages += (windows.size() > 1 ? (w ? "; window " : "window ") + std::to_string(w + 1) + ": " : std::string()) + r.summary.message;
  }
  if (windows.empty()) out.min_reduced_hessian_eig = std::nan("");
  out.summary.message = "support solve (" + std::to_string(windows.size()) + " window" + (windows.size() == 1 ? "" : "s") +
                        ", " + std::to_string(windows.empty() ? 0 : windows.front().points.size()) +
                        (windows.size() == 1 ? " points" : " points in the first") + "): " + messages;
  out.length_error = whole.max_relative_length_error(out.points);
  out.pin_error = whole.max_relative_pin_error(out.points);
  return out;
}

}  // namespace fairshape
