// The rules are learned from OpenSubdiv's Sdc::Crease and Sdc::Scheme (not copied); see the
// header for the statement of each.
#include "fairshape/subdivision/crease_rules.h"

#include <algorithm>

namespace fairshape {

float decayed_sharpness(float s) {
  if (s <= 0.0f) return 0.0f;
  if (s >= kInfiniteSharpness) return kInfiniteSharpness;
  return s > 1.0f ? s - 1.0f : 0.0f;  // float subtraction, as OpenSubdiv does it
}

namespace {
bool semi_sharp(float s) { return s > 0.0f && s < kInfiniteSharpness; }
}  // namespace

// OpenSubdiv's Chaikin rule (Sdc::Crease, learned, not copied): each semi-sharp edge among
// two or more becomes 3/4 of itself plus 1/4 of the mean of the other semi-sharp ones, then
// decays by one; smooth and infinite edges, and a lone semi-sharp edge, decay uniformly. The
// float operations are OpenSubdiv's, in the same order, so the values agree bit for bit.
std::vector<float> child_sharpness_around(const std::vector<float>& parent, CreaseMethod method) {
  std::vector<float> child(parent.size());
  float sum = 0.0f;
  int count = 0;
  if (method == CreaseMethod::Chaikin)
    for (float s : parent)
      if (semi_sharp(s)) {
        sum += s;
        ++count;
      }
  for (std::size_t i = 0; i < parent.size(); ++i) {
    const float s = parent[i];
    if (count < 2 || !semi_sharp(s)) {
      child[i] = decayed_sharpness(s);
      continue;
    }
    const float others = (sum - s) / static_cast<float>(count - 1);
    const float c = ((0.75f * s) + (0.25f * others)) - 1.0f;
    child[i] = c > 0.0f ? c : 0.0f;
  }
  return child;
}

float effective_edge_sharpness(const SurfaceMesh& m, int e) {
  return m.is_boundary_edge(e) ? kInfiniteSharpness : m.edge_sharpness(e);
}

float effective_vertex_sharpness(const SurfaceMesh& m, int v, BoundaryMode boundary) {
  if (boundary == BoundaryMode::EdgeAndCorner && !m.is_isolated(v) && m.is_boundary_vertex(v) &&
      m.valence(v) == 2)
    return kInfiniteSharpness;
  return m.vertex_sharpness(v);
}

VertexRule vertex_rule(float vertex_sharpness, int sharp_edges) {
  if (vertex_sharpness > 0.0f || sharp_edges > 2) return VertexRule::Corner;
  return sharp_edges == 2 ? VertexRule::Crease : sharp_edges == 1 ? VertexRule::Dart : VertexRule::Smooth;
}

namespace {

// Sharpness of v and of its edges in the order of outgoing_halfedges (ccw from halfedge(v)).
struct VertexSharpness {
  float vertex = 0;
  std::vector<float> edges;
  std::vector<int> neighbours;
};

VertexSharpness gather(const SurfaceMesh& m, int v, BoundaryMode boundary) {
  VertexSharpness s;
  s.vertex = effective_vertex_sharpness(m, v, boundary);
  m.for_each_outgoing(v, [&](int h) {
    s.edges.push_back(effective_edge_sharpness(m, SurfaceMesh::edge(h)));
    s.neighbours.push_back(m.to_vertex(h));
  });
  return s;
}

VertexRule rule_of(float vertex, const std::vector<float>& edges) {
  const int sharp = static_cast<int>(std::count_if(edges.begin(), edges.end(), [](float s) { return s > 0.0f; }));
  return vertex_rule(vertex, sharp);
}

// The first and the last sharp edge in ccw order (the two of a crease): on a boundary vertex
// these are the outgoing and the incoming boundary edge.
void crease_ends(const VertexSharpness& s, const std::vector<float>& edges, VertexMaskBlend& out) {
  const int n = static_cast<int>(edges.size());
  int first = 0, last = n - 1;
  while (edges[first] <= 0.0f) ++first;
  while (edges[last] <= 0.0f) --last;
  out.crease_a = s.neighbours[first];
  out.crease_b = s.neighbours[last];
}

void add_mask(VertexRule rule, double w, const VertexSharpness& s, const std::vector<float>& edges,
              VertexMaskBlend& out) {
  switch (rule) {
    case VertexRule::Smooth:
    case VertexRule::Dart: out.smooth += w; break;
    case VertexRule::Crease:
      out.crease += w;
      crease_ends(s, edges, out);
      break;
    case VertexRule::Corner: out.corner += w; break;
  }
}

// The parent's share when the rule changes: the mean of the sharpness values (vertex and
// edges) that reach zero in this step, at most 1. (With the uniform method an edge reaches
// zero exactly when its sharpness is at most 1; with Chaikin's, possibly from above 1.)
float fractional_weight(float parent_vertex, float child_vertex, const std::vector<float>& parent_edges,
                        const std::vector<float>& child_edges) {
  int count = 0;
  float sum = 0.0f;
  if (parent_vertex > 0.0f && child_vertex <= 0.0f) {
    count = 1;
    sum = parent_vertex;
  }
  for (std::size_t i = 0; i < parent_edges.size(); ++i)
    if (parent_edges[i] > 0.0f && child_edges[i] <= 0.0f) {
      sum += parent_edges[i];
      ++count;
    }
  if (count == 0) return 0.0f;
  return std::min(1.0f, sum / static_cast<float>(count));
}

}  // namespace

VertexRule vertex_rule(const SurfaceMesh& m, int v, BoundaryMode boundary) {
  const VertexSharpness s = gather(m, v, boundary);
  return rule_of(s.vertex, s.edges);
}

VertexMaskBlend vertex_mask_blend(const SurfaceMesh& m, int v, BoundaryMode boundary, CreaseMethod method) {
  VertexMaskBlend out;
  if (m.is_isolated(v)) {
    out.corner = 1.0;
    return out;
  }
  if (!m.has_sharpness() && !m.is_boundary_vertex(v)) {  // the common case, without allocating
    out.smooth = 1.0;
    return out;
  }
  const VertexSharpness s = gather(m, v, boundary);
  const VertexRule parent = rule_of(s.vertex, s.edges);
  if (parent == VertexRule::Smooth || parent == VertexRule::Dart) {
    out.smooth = 1.0;
    return out;
  }
  const std::vector<float> child_edges = child_sharpness_around(s.edges, method);
  const float child_vertex = decayed_sharpness(s.vertex);
  const VertexRule child = rule_of(child_vertex, child_edges);
  if (child == parent) {
    add_mask(parent, 1.0, s, s.edges, out);
    return out;
  }
  const double p = fractional_weight(s.vertex, child_vertex, s.edges, child_edges);
  add_mask(parent, p, s, s.edges, out);
  add_mask(child, 1.0 - p, s, child_edges, out);
  return out;
}

bool crease_neighbours(const SurfaceMesh& m, int v, int& a, int& b) {
  if (m.is_isolated(v)) return false;
  int sharp = 0;
  m.for_each_outgoing(v, [&](int h) {
    if (effective_edge_sharpness(m, SurfaceMesh::edge(h)) <= 0.0f) return;
    (sharp == 0 ? a : b) = m.to_vertex(h);
    ++sharp;
  });
  return sharp == 2;
}

float child_edge_sharpness(const SurfaceMesh& m, int e, int v, CreaseMethod method) {
  const float s = effective_edge_sharpness(m, e);
  if (method == CreaseMethod::Uniform || !semi_sharp(s)) return decayed_sharpness(s);
  std::vector<float> around;
  int at = -1;
  m.for_each_outgoing(v, [&](int h) {
    if (SurfaceMesh::edge(h) == e) at = static_cast<int>(around.size());
    around.push_back(effective_edge_sharpness(m, SurfaceMesh::edge(h)));
  });
  return child_sharpness_around(around, method)[static_cast<std::size_t>(at)];
}

double edge_crease_weight(const SurfaceMesh& m, int e, CreaseMethod method) {
  const float s = effective_edge_sharpness(m, e);
  if (s <= 0.0f) return 0.0;
  if (s >= kInfiniteSharpness) return 1.0;
  // The edge point's rule in the child is a crease when both halves stay sharp (OpenSubdiv's
  // Sdc::Scheme::ComputeEdgeVertexMask with the child's rule): then the midpoint alone.
  const int h = 2 * e;
  if (child_edge_sharpness(m, e, m.from_vertex(h), method) > 0.0f &&
      child_edge_sharpness(m, e, m.to_vertex(h), method) > 0.0f)
    return 1.0;
  return static_cast<double>(s);
}

void child_sharpness(const SurfaceMesh& coarse, SurfaceMesh& fine, CreaseMethod method) {
  if (!coarse.has_sharpness()) return;
  std::vector<float> edges, vertices;
  bool any_edge = false, any_vertex = false;
  if (!coarse.edge_sharpness_array().empty()) {
    edges.assign(fine.n_edges(), 0.0f);
    for (int e = 0; e < coarse.n_edges(); ++e) {
      // refine_topology: the halves of e are 2e (at from_vertex(2e)) and 2e + 1 (at
      // to_vertex(2e)). A boundary edge keeps its decayed tag: its effective sharpness is
      // infinite on every level anyway.
      const float tag = coarse.edge_sharpness(e);
      if (tag <= 0.0f) continue;
      const bool plain = method == CreaseMethod::Uniform || coarse.is_boundary_edge(e);
      const float a = plain ? decayed_sharpness(tag) : child_edge_sharpness(coarse, e, coarse.from_vertex(2 * e), method);
      const float b = plain ? a : child_edge_sharpness(coarse, e, coarse.to_vertex(2 * e), method);
      edges[2 * e] = a;
      edges[2 * e + 1] = b;
      any_edge |= a > 0.0f || b > 0.0f;
    }
  }
  if (!coarse.vertex_sharpness_array().empty()) {
    vertices.assign(fine.n_vertices(), 0.0f);
    for (int v = 0; v < coarse.n_vertices(); ++v) {
      vertices[v] = decayed_sharpness(coarse.vertex_sharpness(v));  // a vertex keeps its id
      any_vertex |= vertices[v] > 0.0f;
    }
  }
  if (!any_edge) edges.clear();
  if (!any_vertex) vertices.clear();
  fine.set_sharpness(std::move(edges), std::move(vertices));
}

bool has_sharp_edges(const SurfaceMesh& m) {
  for (float s : m.edge_sharpness_array())
    if (s > 0.0f) return true;
  return false;
}

}  // namespace fairshape
