#include "fairshape/feature/surface_polyline.h"

#include <algorithm>
#include <cmath>

#include "fairshape/remesh/closest_point.h"

namespace fairshape::feature {
namespace {

Vec3 start_of(const TriangleSurface& s, const FacePiece& p) { return s.point({p.face, p.from}); }
Vec3 end_of(const TriangleSurface& s, const FacePiece& p) { return s.point({p.face, p.to}); }

Vec3 bary_along(const FacePiece& p, double t) { return (1 - t) * p.from + t * p.to; }

// Arc length at the start of every piece, and the total at the end.
std::vector<double> arc_starts(const std::vector<double>& lengths) {
  std::vector<double> start(lengths.size() + 1, 0.0);
  for (std::size_t k = 0; k < lengths.size(); ++k) start[k + 1] = start[k] + lengths[k];
  return start;
}

// The piece holding arc length `arc` (in [0, total]) and the parameter within it.
std::pair<std::size_t, double> locate(const std::vector<double>& start, const std::vector<double>& lengths, double arc) {
  const std::size_t n = lengths.size();
  std::size_t k = static_cast<std::size_t>(std::upper_bound(start.begin(), start.begin() + static_cast<long>(n), arc) -
                                           start.begin());
  k = k == 0 ? 0 : k - 1;
  const double t = lengths[k] > 0 ? std::clamp((arc - start[k]) / lengths[k], 0.0, 1.0) : 0.0;
  return {k, t};
}

}  // namespace

std::vector<double> piece_lengths(const TriangleSurface& s, const SurfacePolyline& line) {
  std::vector<double> out;
  out.reserve(line.pieces.size());
  for (const FacePiece& p : line.pieces) out.push_back((end_of(s, p) - start_of(s, p)).norm());
  return out;
}

double polyline_length(const TriangleSurface& s, const SurfacePolyline& line) {
  double total = 0;
  for (double l : piece_lengths(s, line)) total += l;
  return total;
}

std::vector<SurfacePoint> corner_points(const SurfacePolyline& line) {
  std::vector<SurfacePoint> out;
  for (const FacePiece& p : line.pieces) out.push_back({p.face, p.from});
  if (!line.closed && !line.pieces.empty()) out.push_back({line.pieces.back().face, line.pieces.back().to});
  return out;
}

SurfacePoint point_at_arc(const TriangleSurface& s, const SurfacePolyline& line, double arc) {
  const std::vector<double> lengths = piece_lengths(s, line);
  const std::vector<double> start = arc_starts(lengths);
  const double total = start.back();
  arc = line.closed && total > 0 ? arc - total * std::floor(arc / total) : std::clamp(arc, 0.0, total);
  const auto [k, t] = locate(start, lengths, arc);
  return {line.pieces[k].face, bary_along(line.pieces[k], t)};
}

double closest_arc(const TriangleSurface& s, const SurfacePolyline& line, const Vec3& x) {
  double best = std::numeric_limits<double>::infinity(), arc = 0, done = 0;
  for (const FacePiece& p : line.pieces) {
    const Vec3 a = start_of(s, p), ab = end_of(s, p) - a;
    const double len2 = ab.squaredNorm();
    const double t = len2 > 0 ? std::clamp((x - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    const double d = (x - (a + t * ab)).squaredNorm();
    if (d < best) best = d, arc = done + t * std::sqrt(len2);
    done += std::sqrt(len2);
  }
  return arc;
}

SurfacePolyline between_arcs(const TriangleSurface& s, const SurfacePolyline& line, double a, double b) {
  const std::vector<double> lengths = piece_lengths(s, line);
  const std::vector<double> start = arc_starts(lengths);
  const double total = start.back();
  const std::size_t n = line.pieces.size();
  SurfacePolyline out;
  // Walk piece by piece from a to b; on a closed polyline the piece index runs on past the
  // last piece (mod n) and the arc length with it.
  const std::size_t laps = line.closed ? 2 : 1;
  for (std::size_t j = 0; j < laps * n; ++j) {
    const std::size_t k = j % n;
    const double lo = start[k] + (j / n) * total, hi = lo + lengths[k];
    if (hi <= a || lengths[k] <= 0) continue;
    if (lo >= b) break;
    const double t0 = std::clamp((a - lo) / lengths[k], 0.0, 1.0), t1 = std::clamp((b - lo) / lengths[k], 0.0, 1.0);
    if (t1 > t0) out.pieces.push_back({line.pieces[k].face, bary_along(line.pieces[k], t0), bary_along(line.pieces[k], t1)});
  }
  return out;
}

std::vector<SurfacePoint> resample(const TriangleSurface& s, const SurfacePolyline& line, double spacing,
                                   const std::vector<double>& keep, std::vector<char>* fixed) {
  const double total = polyline_length(s, line);
  const double tiny = 1e-12 * (1 + total);
  // The stretches: between consecutive kept arcs (and the ends of an open polyline).
  std::vector<double> stops;
  std::vector<char> stop_fixed;
  const auto stop_at = [&](double arc, char is_fixed) {
    if (!stops.empty() && arc - stops.back() <= tiny) return;  // the same place twice
    stops.push_back(arc);
    stop_fixed.push_back(is_fixed);
  };
  if (!line.closed) stop_at(0.0, 1);
  for (double arc : keep) stop_at(arc, 1);
  if (line.closed) {
    if (stops.empty()) stop_at(0.0, 0);
    stops.push_back(stops.front() + total);  // around to the first stop
    stop_fixed.push_back(stop_fixed.front());
  } else if (total - stops.back() > tiny) {
    stop_at(total, 1);
  } else {
    stop_fixed.back() = 1;  // the last kept arc is the end
  }
  std::vector<SurfacePoint> out;
  std::vector<char> marks;
  for (std::size_t i = 0; i + 1 < stops.size(); ++i) {
    const double a = stops[i], b = stops[i + 1];
    const int pieces = std::max(1, static_cast<int>(std::lround((b - a) / spacing)));
    for (int j = 0; j < pieces; ++j) {
      out.push_back(point_at_arc(s, line, a + (b - a) * j / pieces));
      marks.push_back(j == 0 ? stop_fixed[i] : 0);
    }
  }
  if (!line.closed) {
    out.push_back(point_at_arc(s, line, stops.back()));
    marks.push_back(1);
  }
  if (fixed) *fixed = std::move(marks);
  return out;
}

void smooth_on_surface(const TriangleSurface& s, std::vector<SurfacePoint>& points, bool closed,
                       const std::vector<char>& fixed, int iterations) {
  const auto n = static_cast<Eigen::Index>(points.size());
  if (n < 3) return;
  MatrixX3 x(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) x.row(i) = s.point(points[static_cast<std::size_t>(i)]).transpose();
  const auto is_fixed = [&](Eigen::Index i) {
    if (!closed && (i == 0 || i == n - 1)) return true;
    return static_cast<std::size_t>(i) < fixed.size() && fixed[static_cast<std::size_t>(i)] != 0;
  };
  std::vector<int> faces;
  for (int it = 0; it < iterations; ++it) {
    MatrixX3 moved = x;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (is_fixed(i)) continue;
      const Eigen::RowVector3d mid = 0.5 * (x.row((i + n - 1) % n) + x.row((i + 1) % n));
      moved.row(i) = 0.5 * (x.row(i) + mid);
    }
    x = s.locator().closest_points(moved, &faces);
    for (Eigen::Index i = 0; i < n; ++i) {
      if (is_fixed(i)) {
        x.row(i) = s.point(points[static_cast<std::size_t>(i)]).transpose();
        continue;
      }
      const int f = faces[static_cast<std::size_t>(i)];
      Vec3 b = s.barycentric(f, x.row(i).transpose());
      for (int k = 0; k < 3; ++k) b[k] = std::max(b[k], 0.0);
      points[static_cast<std::size_t>(i)] = {f, b / b.sum()};
    }
  }
}

}  // namespace fairshape::feature
