#include "fairshape/curve_design/self_crossings.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace fairshape {
namespace {

using P2 = Eigen::Vector2d;

double cross(const P2& a, const P2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Closed segments [a, b] and [c, d] share a point (collinear overlaps included).
bool segments_meet(const P2& a, const P2& b, const P2& c, const P2& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a), d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  const auto on = [](const P2& p, const P2& q, const P2& r, double orient) {  // r on [p, q], collinear
    return orient == 0 && std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
           std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
  };
  return on(a, b, c, d1) || on(a, b, d, d2) || on(c, d, a, d3) || on(c, d, b, d4);
}

}  // namespace

int count_self_crossings(const MatrixX3& X, bool closed, const CurvePlane& plane) {
  const int n = static_cast<int>(X.rows()), m = closed ? n : n - 1;
  if (m < 3) return 0;
  const Vec3 e1 = plane.normal.unitOrthogonal(), e2 = plane.normal.cross(e1);
  std::vector<P2> p(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const Vec3 x = X.row(i).transpose() - plane.origin;
    p[static_cast<std::size_t>(i)] = P2(x.dot(e1), x.dot(e2));
  }
  const auto a = [&](int s) { return p[static_cast<std::size_t>(s)]; };
  const auto b = [&](int s) { return p[static_cast<std::size_t>((s + 1) % n)]; };
  double total = 0;
  for (int s = 0; s < m; ++s) total += (b(s) - a(s)).norm();
  const double h = std::max(total / m, 1e-300);  // about one segment per cell
  const auto cell = [&](double v) { return static_cast<long long>(std::floor(v / h)); };
  const auto key = [](long long i, long long j) { return static_cast<long long>(i * 73856093LL ^ j * 19349663LL); };
  std::unordered_map<long long, std::vector<int>> grid;
  grid.reserve(static_cast<std::size_t>(2 * m));
  int crossings = 0;
  std::vector<int> seen(static_cast<std::size_t>(m), -1);  // the segment s whose cells listed t last
  for (int s = 0; s < m; ++s) {
    const P2 lo = a(s).cwiseMin(b(s)), hi = a(s).cwiseMax(b(s));
    for (long long i = cell(lo.x()); i <= cell(hi.x()); ++i)
      for (long long j = cell(lo.y()); j <= cell(hi.y()); ++j) {
        std::vector<int>& in = grid[key(i, j)];
        for (int t : in) {
          if (seen[static_cast<std::size_t>(t)] == s) continue;  // met in another cell already
          seen[static_cast<std::size_t>(t)] = s;
          const bool adjacent = t == s - 1 || (closed && s == m - 1 && t == 0);
          if (!adjacent && segments_meet(a(s), b(s), a(t), b(t))) ++crossings;
        }
        in.push_back(s);
      }
  }
  return crossings;
}

}  // namespace fairshape
