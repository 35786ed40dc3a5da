#include "fairshape/feature/level_attachment.h"

namespace fairshape::feature {

SurfacePoint child_point(const SurfacePoint& p) {
  // With ab, bc, ca the edge midpoints of (a, b, c), a point b₀a + b₁b + b₂c lies in the corner
  // child of the coordinate that is at least ½, else in the middle child (ab, bc, ca).
  const Vec3& b = p.bary;
  const int first = 4 * p.face;
  if (b[0] >= 0.5) return {first + 0, Vec3(2 * b[0] - 1, 2 * b[1], 2 * b[2])};  // (a, ab, ca)
  if (b[1] >= 0.5) return {first + 1, Vec3(2 * b[0], 2 * b[1] - 1, 2 * b[2])};  // (ab, b, bc)
  if (b[2] >= 0.5) return {first + 2, Vec3(2 * b[0], 2 * b[1], 2 * b[2] - 1)};  // (ca, bc, c)
  return {first + 3, Vec3(1 - 2 * b[2], 1 - 2 * b[0], 1 - 2 * b[1])};           // (ab, bc, ca)
}

std::vector<std::vector<SurfacePoint>> attachments_per_level(const BaseCurve& curve, int drawn_level, int finest) {
  std::vector<SurfacePoint> drawn;
  for (const BaseSegment& s : curve.segments) drawn.push_back({s.face, s.bary_a});
  if (!curve.closed && !curve.segments.empty()) drawn.push_back({curve.segments.back().face, curve.segments.back().bary_b});
  std::vector<std::vector<SurfacePoint>> out{drawn};
  for (int level = drawn_level + 1; level <= finest; ++level) {
    std::vector<SurfacePoint> finer;
    finer.reserve(out.back().size());
    for (const SurfacePoint& p : out.back()) finer.push_back(child_point(p));
    out.push_back(std::move(finer));
  }
  return out;
}

}  // namespace fairshape::feature
