#include "fairshape/constraint/crease_normals.h"

#include <sstream>
#include <vector>

#include "fairshape/core/error.h"
#include "fairshape/subdivision/crease_rules.h"

namespace fairshape {
namespace {

bool sharp_spoke(const SurfaceMesh& m, int h) {
  const int e = SurfaceMesh::edge(h);
  return !m.is_boundary_edge(e) && m.edge_sharpness(e) > 0.0f;
}

// The faces around v in ccw order, grouped into the sides the sharp spokes separate. Face(h)
// of an outgoing half-edge h lies between spokes h and rotate_ccw(h).
std::vector<std::vector<int>> sides(const SurfaceMesh& m, int v) {
  std::vector<int> spokes = m.outgoing_halfedges(v);
  // Start at a side's first spoke so that no side wraps around: on the boundary, the boundary
  // half-edge (halfedge(v), with the hole after it), inside, a sharp spoke.
  std::size_t start = 0;
  if (!m.is_boundary_vertex(v))
    for (std::size_t i = 0; i < spokes.size(); ++i)
      if (sharp_spoke(m, spokes[i])) { start = i; break; }
  std::vector<std::vector<int>> out(1);
  for (std::size_t k = 0; k < spokes.size(); ++k) {
    const int h = spokes[(start + k) % spokes.size()];
    if (k > 0 && sharp_spoke(m, h) && !out.back().empty()) out.emplace_back();
    if (!m.is_boundary_halfedge(h)) out.back().push_back(m.face(h));
  }
  if (out.back().empty()) out.pop_back();
  return out;
}

// "at: {face: F, uv: [u, v], level: L}" for v as a corner of face f, or of its child quad one
// level finer when f is not a quad under Catmull-Clark (quad `first + c` has v at (0, 0)).
std::string address(const SurfaceMesh& m, const SubdivisionOptions& rules, int level, int v, int f, bool finer) {
  const auto corners = m.face_vertices(f);
  int c = 0;
  while (corners[static_cast<std::size_t>(c)] != v) ++c;
  const int n = static_cast<int>(corners.size());
  std::ostringstream os;
  if (rules.scheme == SchemeType::CatmullClark && n != 4) {
    if (!finer) return "";
    long first = 0;
    for (int g = 0; g < f; ++g) first += m.face_size(g);
    os << "at: {face: " << first + c << ", uv: [0, 0], level: " << level + 1 << "}";
    return os.str();
  }
  static const int quad[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, tri[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  const int* uv = n == 4 ? quad[c] : tri[c];
  os << "at: {face: " << f << ", uv: [" << uv[0] << ", " << uv[1] << "], level: " << level << "}";
  return os.str();
}

}  // namespace

void refuse_normal_on_crease(const SurfaceMesh& m, const SubdivisionOptions& rules, int level, int v,
                             bool has_finer_level, const std::string& label) {
  if (!m.has_sharpness() || m.is_isolated(v)) return;
  int sharp = 0;
  m.for_each_outgoing(v, [&](int h) { sharp += sharp_spoke(m, h); });
  const bool boundary = m.is_boundary_vertex(v);
  const bool split = boundary ? sharp >= 1 : sharp >= 2;
  const bool corner = m.vertex_sharpness(v) >= kInfiniteSharpness;
  if (!split && !corner) return;
  std::ostringstream os;
  os << label << ": vertex " << v << " of level " << level << " is on a sharp "
     << (split ? "crease: the surface has a different normal on each side there, and a normal fitted across the "
                 "whole ring would bend both sides"
               : "corner: the surface has no tangent plane there")
     << ". Give the normal of one side as a surface point at this vertex instead (or at a point off the crease):";
  int i = 0;
  for (const auto& side : sides(m, v)) {
    ++i;
    os << (i > 1 ? ";" : "") << " side " << i << " (faces";
    for (int f : side) os << " " << f;
    const std::string at = address(m, rules, level, v, side.front(), has_finer_level);
    os << ")" << (at.empty() ? " has no quad to address the vertex on (add a level)" : ": " + at);
  }
  throw InvalidInput(os.str());
}

void refuse_normal_on_crease_point(const SurfaceMesh& m, const SubdivisionOptions& rules, int level,
                                   const FaceParameter& at, bool has_finer_level, const std::string& label) {
  if (!m.has_sharpness()) return;
  constexpr double kOn = 1e-9;  // a parameter this close to a side is on it
  const auto corners = m.face_vertices(at.face);
  const int n = static_cast<int>(corners.size());
  // The sides (corner i to i + 1) the point lies on, in the evaluator's parameterization.
  std::vector<bool> on(static_cast<std::size_t>(n), false);
  if (n == 4) {
    on[0] = at.v <= kOn;
    on[1] = at.u >= 1 - kOn;
    on[2] = at.v >= 1 - kOn;
    on[3] = at.u <= kOn;
  } else {
    on[0] = at.v <= kOn;
    on[1] = at.u + at.v >= 1 - kOn;
    on[2] = at.u <= kOn;
  }
  for (int i = 0; i < n; ++i)  // at corner i: the vertex's own test (its message lists the sides)
    if (on[static_cast<std::size_t>(i)] && on[static_cast<std::size_t>((i + n - 1) % n)])
      refuse_normal_on_crease(m, rules, level, corners[i], has_finer_level,
                              label + " (the closest limit point is vertex " + std::to_string(corners[i]) + ")");
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const int e = m.find_edge(corners[i], corners[j]);
    if (!on[i] || m.is_boundary_edge(e) || m.edge_sharpness(e) <= 0.0f) continue;
    const int other = m.face(2 * e) == at.face ? m.face(2 * e + 1) : m.face(2 * e);
    std::ostringstream os;
    os << label << ": the closest limit point lies on the sharp crease edge " << corners[i] << "-" << corners[j]
       << " of level " << level << ", where the surface has a different normal on each side; give the normal with "
       << "at: {face: F, uv: [u, v], level: " << level << "} on the side meant (face " << at.face << " at (u, v) = ("
       << at.u << ", " << at.v << "), or face " << other << "), or at a point off the crease";
    throw InvalidInput(os.str());
  }
}

}  // namespace fairshape
