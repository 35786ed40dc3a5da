#include "fairshape/curves/multires_polyline.h"

#include "fairshape/core/backend.h"
#if FAIRSHAPE_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#endif

#include "fairshape/core/error.h"

namespace fairshape {
namespace {

// Reference: the formulas, one point at a time.
void analysis_reference(const MatrixX3& f, bool closed, MatrixX3& c, MatrixX3& d) {
  const Eigen::Index n = f.rows(), m = closed ? n / 2 : (n - 1) / 2;
  c.resize(closed ? m : m + 1, 3);
  d.resize(m, 3);
  for (Eigen::Index i = 0; i < c.rows(); ++i) c.row(i) = f.row(2 * i);
  for (Eigen::Index i = 0; i < m; ++i) d.row(i) = f.row(2 * i + 1) - 0.5 * (f.row(2 * i) + f.row((2 * i + 2) % n));
}

MatrixX3 synthesis_reference(const MatrixX3& c, const MatrixX3& d, bool closed) {
  const Eigen::Index m = d.rows(), n = closed ? 2 * m : 2 * m + 1;
  MatrixX3 f(n, 3);
  for (Eigen::Index i = 0; i < c.rows(); ++i) f.row(2 * i) = c.row(i);
  for (Eigen::Index i = 0; i < m; ++i) f.row(2 * i + 1) = d.row(i) + 0.5 * (c.row(i) + c.row((i + 1) % c.rows()));
  return f;
}

#if FAIRSHAPE_WITH_TBB
// Optimized: the same arithmetic, split over TBB threads (every output row is independent).
void analysis_parallel(const MatrixX3& f, bool closed, MatrixX3& c, MatrixX3& d) {
  const Eigen::Index n = f.rows(), m = closed ? n / 2 : (n - 1) / 2;
  c.resize(closed ? m : m + 1, 3);
  d.resize(m, 3);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, c.rows(), 8192), [&](const auto& r) {
    for (Eigen::Index i = r.begin(); i != r.end(); ++i) {
      c.row(i) = f.row(2 * i);
      if (i < m) d.row(i) = f.row(2 * i + 1) - 0.5 * (f.row(2 * i) + f.row((2 * i + 2) % n));
    }
  });
}

MatrixX3 synthesis_parallel(const MatrixX3& c, const MatrixX3& d, bool closed) {
  const Eigen::Index m = d.rows(), n = closed ? 2 * m : 2 * m + 1;
  MatrixX3 f(n, 3);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, c.rows(), 8192), [&](const auto& r) {
    for (Eigen::Index i = r.begin(); i != r.end(); ++i) {
      f.row(2 * i) = c.row(i);
      if (i < m) f.row(2 * i + 1) = d.row(i) + 0.5 * (c.row(i) + c.row((i + 1) % c.rows()));
    }
  });
  return f;
}
#endif

}  // namespace

int max_polyline_levels(int n, bool closed) {
  int levels = 0;
  int segments = closed ? n : n - 1;
  while (segments % 2 == 0 && segments / 2 >= (closed ? 3 : 1)) {
    segments /= 2;
    ++levels;
  }
  return levels;
}

void analysis_step(const MatrixX3& fine, bool closed, MatrixX3& coarse, MatrixX3& detail, Backend backend) {
  require_backend(backend);
#if FAIRSHAPE_WITH_TBB
  if (backend == Backend::Reference) analysis_reference(fine, closed, coarse, detail);
  else analysis_parallel(fine, closed, coarse, detail);
#else
  analysis_reference(fine, closed, coarse, detail);
#endif
}

MatrixX3 synthesis_step(const MatrixX3& coarse, const MatrixX3& detail, bool closed, Backend backend) {
  require_backend(backend);
#if FAIRSHAPE_WITH_TBB
  return backend == Backend::Reference ? synthesis_reference(coarse, detail, closed)
                                       : synthesis_parallel(coarse, detail, closed);
#else
  return synthesis_reference(coarse, detail, closed);
#endif
}

PolylineHierarchy decompose(const Polyline& curve, int levels, Backend backend) {
  const int n = curve.n_points();
  if (!curve.points.allFinite()) throw InvalidInput("decompose: the curve has a NaN or infinite coordinate");
  if (levels < 0 || levels > max_polyline_levels(n, curve.closed)) {
    const std::string form = curve.closed ? "2^n·k points (k ≥ 3)" : "2^n·k + 1 points (k ≥ 1)";
    throw InvalidInput("decompose: " + std::string(curve.closed ? "a closed" : "an open") + " curve of " +
                       std::to_string(n) + " points allows " + std::to_string(max_polyline_levels(n, curve.closed)) +
                       " levels, not " + std::to_string(levels) + " (n levels need " + form + ")");
  }
  PolylineHierarchy h;
  h.closed = curve.closed;
  h.details.resize(levels);
  MatrixX3 current = curve.points;
  for (int j = levels - 1; j >= 0; --j) {
    MatrixX3 coarse;
    analysis_step(current, curve.closed, coarse, h.details[j], backend);
    current = std::move(coarse);
  }
  h.coarse = std::move(current);
  return h;
}

Polyline reconstruct(const PolylineHierarchy& h, int level, Backend backend) {
  if (level < 0 || level > h.levels())
    throw InvalidInput("reconstruct: level " + std::to_string(level) + " outside [0, " + std::to_string(h.levels()) + "]");
  Polyline out;
  out.closed = h.closed;
  out.points = h.coarse;
  for (int j = 0; j < level; ++j) out.points = synthesis_step(out.points, h.details[j], h.closed, backend);
  return out;
}

SparseMatrix synthesis_operator(int coarse_points, bool closed) {
  const int n = coarse_points, fine = closed ? 2 * n : 2 * n - 1;
  Triplets t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(2 * i, i, 1.0);
    if (2 * i + 1 < fine) {  // odd points: the midpoint of their coarse neighbours
      t.emplace_back(2 * i + 1, i, 0.5);
      t.emplace_back(2 * i + 1, (i + 1) % n, 0.5);
    }
  }
  SparseMatrix S(fine, n);
  S.setFromTriplets(t.begin(), t.end());
  return S;
}

}  // namespace fairshape
