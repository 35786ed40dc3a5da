#include "fairshape/feature/plane_section.h"

namespace fairshape::feature {
namespace {

// Signed heights above the plane; a face is crossed where its corners are on both sides.
struct Cut {
  const TriangleSurface& s;
  std::vector<double> height;
  bool above(int v) const { return height[static_cast<std::size_t>(v)] >= 0; }
  // Edge i of f runs from corner i to corner i + 1.
  bool going_down(int f, int i) const {
    const auto& c = s.corners(f);
    return above(c[i]) && !above(c[(i + 1) % 3]);
  }
  bool going_up(int f, int i) const {
    const auto& c = s.corners(f);
    return !above(c[i]) && above(c[(i + 1) % 3]);
  }
  int edge_where(int f, bool down) const {
    for (int i = 0; i < 3; ++i)
      if (down ? going_down(f, i) : going_up(f, i)) return i;
    return -1;
  }
  bool crossed(int f) const { return edge_where(f, true) >= 0; }
  // The plane's point on edge i of f, as weights of f's corners. Computed from the edge's end
  // points in a fixed order so that both faces of the edge get the very same point.
  Vec3 crossing(int f, int i) const {
    const auto& c = s.corners(f);
    int a = c[i], b = c[(i + 1) % 3];
    const bool swapped = a > b;
    if (swapped) std::swap(a, b);
    const double ha = height[static_cast<std::size_t>(a)], hb = height[static_cast<std::size_t>(b)];
    const double t = ha / (ha - hb);  // weight of b
    Vec3 w = Vec3::Zero();
    w[s.corner_of(f, a)] = 1 - t;
    w[s.corner_of(f, b)] = t;
    return w;
  }
  // A crossed face's piece enters where the corners go down and leaves where they go up.
  FacePiece piece(int f) const { return {f, crossing(f, edge_where(f, true)), crossing(f, edge_where(f, false))}; }
  int next_face(int f) const { return s.across(f, edge_where(f, false)); }
  int previous_face(int f) const { return s.across(f, edge_where(f, true)); }
};

}  // namespace

std::vector<SurfacePolyline> plane_section(const TriangleSurface& s, const Vec3& point, const Vec3& normal) {
  const Vec3 n = normal.normalized();
  Cut cut{s, {}};
  for (int v = 0; v < s.mesh().n_vertices(); ++v) cut.height.push_back((s.vertex(v) - point).dot(n));
  std::vector<char> done(static_cast<std::size_t>(s.n_faces()), 0);
  std::vector<SurfacePolyline> out;
  for (int f0 = 0; f0 < s.n_faces(); ++f0) {
    if (done[static_cast<std::size_t>(f0)] || !cut.crossed(f0)) continue;
    // Back to the start of an open curve (or once around a loop).
    int first = f0;
    for (int g = cut.previous_face(f0); g >= 0 && g != f0; g = cut.previous_face(g)) first = g;
    SurfacePolyline line;
    int f = first;
    do {
      done[static_cast<std::size_t>(f)] = 1;
      line.pieces.push_back(cut.piece(f));
      f = cut.next_face(f);
    } while (f >= 0 && f != first);
    line.closed = f == first;
    // A vertex on the plane makes a piece of length zero in the faces around it.
    std::erase_if(line.pieces, [&](const FacePiece& p) { return s.point({p.face, p.from}) == s.point({p.face, p.to}); });
    if (!line.pieces.empty()) out.push_back(std::move(line));
  }
  return out;
}

}  // namespace fairshape::feature
