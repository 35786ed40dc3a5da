#include "fairshape/bspline/hierarchical_surface.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <string>

#include "fairshape/bspline/uniform_basis.h"
#include "fairshape/core/error.h"

namespace fairshape::bspline {

HierarchicalSurface::HierarchicalSurface(const SheetShape& shape) : shape_(shape) {
  if (shape.spans_u < 1 || shape.spans_v < 1)
    throw InvalidInput("B-spline sheet needs at least one span in u and v (got " + std::to_string(shape.spans_u) +
                       " x " + std::to_string(shape.spans_v) + ")");
  if (static_cast<long long>(shape.spans_u) * shape.spans_v > kMaxBaseSpans)
    throw InvalidInput("B-spline sheet of " + std::to_string(shape.spans_u) + " x " + std::to_string(shape.spans_v) +
                       " base spans is above the limit of " + std::to_string(kMaxBaseSpans) + " spans");
  if (shape.degree < kMinDegree || shape.degree > kMaxDegree)
    throw InvalidInput("B-spline degree " + std::to_string(shape.degree) + " is outside [" +
                       std::to_string(kMinDegree) + ", " + std::to_string(kMaxDegree) + "]");
  if (shape.periodic_u && shape.spans_u < shape.degree + 1)
    throw InvalidInput("a sheet periodic in u needs at least degree + 1 = " + std::to_string(shape.degree + 1) +
                       " spans in u (got " + std::to_string(shape.spans_u) + ")");
  Layer base;
  for (int i = 0; i < shape.spans_u; ++i)
    for (int j = 0; j < shape.spans_v; ++j) base.spans.insert(key(0, i, j));
  levels_.push_back(std::move(base));
  rebuild_dofs();
}

namespace {
std::string span_name(const SpanId& s) {
  return "span (level " + std::to_string(s.level) + ", " + std::to_string(s.i) + ", " + std::to_string(s.j) + ")";
}
}  // namespace

HierarchicalSurface HierarchicalSurface::from_layers(const SheetShape& shape,
                                                     const std::vector<std::vector<SpanId>>& spans_per_level) {
  HierarchicalSurface out(shape);
  const int levels = static_cast<int>(spans_per_level.size());
  if (levels < 1 || levels > kMaxLevel + 1)
    throw InvalidInput("a sheet has 1 to " + std::to_string(kMaxLevel + 1) + " layers (got " + std::to_string(levels) + ")");
  std::vector<Layer> layers(levels);
  for (int level = 0; level < levels; ++level) {
    if (!out.level_fits(level))
      throw InvalidInput("layer " + std::to_string(level) + " of a sheet of " + std::to_string(shape.spans_u) + " x " +
                         std::to_string(shape.spans_v) + " base spans would have more spans than an int counts");
    if (spans_per_level[level].empty()) throw InvalidInput("layer " + std::to_string(level) + " has no spans");
    for (const SpanId& s : spans_per_level[level]) {
      if (s.level != level) throw InvalidInput(span_name(s) + " is listed under layer " + std::to_string(level));
      if (s.i < 0 || s.i >= out.spans_u(level) || s.j < 0 || s.j >= out.spans_v(level))
        throw InvalidInput(span_name(s) + " is outside the layer's " + std::to_string(out.spans_u(level)) + " x " +
                           std::to_string(out.spans_v(level)) + " grid");
      if (level > 0 && !layers[level - 1].spans.count(out.key(level - 1, s.i / 2, s.j / 2)))
        throw InvalidInput(span_name(s) + " is not nested: its parent (" + std::to_string(s.i / 2) + ", " +
                           std::to_string(s.j / 2) + ") is not in layer " + std::to_string(level - 1));
      if (!layers[level].spans.insert(out.key(level, s.i, s.j)).second) throw InvalidInput(span_name(s) + " is listed twice");
    }
  }
  // Distinct and in range, so equal counts mean the whole grid.
  if (layers[0].spans.size() != out.levels_[0].spans.size())
    throw InvalidInput("layer 0 must be the whole " + std::to_string(shape.spans_u) + " x " + std::to_string(shape.spans_v) +
                       " base grid (got " + std::to_string(layers[0].spans.size()) + " spans)");
  out.levels_ = std::move(layers);
  out.rebuild_dofs();
  return out;
}

std::vector<SpanId> HierarchicalSurface::spans(int level) const {
  std::vector<SpanId> out;
  out.reserve(levels_[level].spans.size());
  for (const std::int64_t k : levels_[level].spans)
    out.push_back({level, static_cast<int>(k / spans_v(level)), static_cast<int>(k % spans_v(level))});
  std::sort(out.begin(), out.end(), [](const SpanId& a, const SpanId& b) { return a.i != b.i ? a.i < b.i : a.j < b.j; });
  return out;
}

bool HierarchicalSurface::level_fits(int level) const {
  if (level < 0 || level > kMaxLevel) return false;
  const long long most = std::numeric_limits<int>::max() - shape_.degree;
  return (static_cast<long long>(shape_.spans_u) << level) <= most &&
         (static_cast<long long>(shape_.spans_v) << level) <= most;
}

int HierarchicalSurface::wrap_u(int level, int i) const {
  const int n = spans_u(level);
  return ((i % n) + n) % n;
}

bool HierarchicalSurface::has_span(const SpanId& s) const {
  if (s.level < 0 || s.level >= level_count()) return false;
  if (s.i < 0 || s.i >= spans_u(s.level) || s.j < 0 || s.j >= spans_v(s.level)) return false;
  return levels_[s.level].spans.count(key(s.level, s.i, s.j)) > 0;
}

int HierarchicalSurface::dof_index(const ControlId& c) const {
  if (c.level < 0 || c.level >= level_count()) return -1;
  const auto& map = dof_of_[c.level];
  const auto it = map.find(static_cast<std::int64_t>(c.i) * controls_v(c.level) + c.j);
  return it == map.end() ? -1 : it->second;
}

bool HierarchicalSurface::support_inside(int level, int ci, int cj, int region_level) const {
  if (region_level >= level_count()) return false;
  const int r = shape_.degree, f = 1 << (region_level - level);
  const int nu = spans_u(region_level), nv = spans_v(region_level);
  const int v0 = std::max(f * (cj - r), 0), v1 = std::min(f * (cj + 1) - 1, nv - 1);
  int u0 = f * (ci - r), u1 = f * (ci + 1) - 1;
  if (!shape_.periodic_u) u0 = std::max(u0, 0), u1 = std::min(u1, nu - 1);
  for (int a = u0; a <= u1; ++a)
    for (int b = v0; b <= v1; ++b)
      if (!has_span({region_level, shape_.periodic_u ? wrap_u(region_level, a) : a, b})) return false;
  return true;
}

bool HierarchicalSurface::is_unknown(int level, int ci, int cj) const {
  return support_inside(level, ci, cj, level) && !support_inside(level, ci, cj, level + 1);
}

void HierarchicalSurface::rebuild_dofs() {
  const int r = shape_.degree;
  dofs_.clear();
  dof_of_.assign(level_count(), {});
  for (int level = 0; level < level_count(); ++level) {
    std::set<std::pair<int, int>> candidates;  // ordered: deterministic numbering
    for (const std::int64_t k : levels_[level].spans) {
      const int i = static_cast<int>(k / spans_v(level)), j = static_cast<int>(k % spans_v(level));
      for (int a = 0; a <= r; ++a)
        for (int b = 0; b <= r; ++b)
          candidates.insert({shape_.periodic_u ? wrap_u(level, i + a) : i + a, j + b});
    }
    for (const auto& [ci, cj] : candidates) {
      if (!is_unknown(level, ci, cj)) continue;
      dof_of_[level][static_cast<std::int64_t>(ci) * controls_v(level) + cj] = dof_count();
      dofs_.push_back({level, ci, cj});
    }
  }
}

SparseMatrix HierarchicalSurface::refine(const std::vector<SpanId>& spans) {
  const int r = shape_.degree;
  for (const SpanId& s : spans) {
    if (!has_span(s))
      throw InvalidInput("cannot refine span (level " + std::to_string(s.level) + ", " + std::to_string(s.i) + ", " +
                         std::to_string(s.j) + "): it is not part of that layer");
    if (s.level + 1 > kMaxLevel)
      throw InvalidInput("cannot refine beyond layer " + std::to_string(kMaxLevel) + " (the maximum depth)");
    if (!level_fits(s.level + 1))
      throw InvalidInput("cannot refine to layer " + std::to_string(s.level + 1) + ": on a sheet of " +
                         std::to_string(shape_.spans_u) + " x " + std::to_string(shape_.spans_v) +
                         " base spans it would have more spans than an int counts");
  }
  const std::vector<ControlId> old_dofs = dofs_;
  for (const SpanId& s : spans) {
    const int fine = s.level + 1;
    if (fine == level_count()) levels_.emplace_back();
    for (int a = 2 * s.i - r; a <= 2 * s.i + 1 + r; ++a) {
      if (!shape_.periodic_u && (a < 0 || a >= spans_u(fine))) continue;
      const int fa = shape_.periodic_u ? wrap_u(fine, a) : a;
      for (int b = std::max(2 * s.j - r, 0); b <= std::min(2 * s.j + 1 + r, spans_v(fine) - 1); ++b)
        if (has_span({s.level, fa / 2, b / 2})) levels_[fine].spans.insert(key(fine, fa, b));
    }
  }
  rebuild_dofs();

  // T: each old basis function in the new basis; a dropped one through the refinement mask.
  const std::vector<double> mask = refinement_mask(r);
  Triplets t;
  std::function<void(int, int, int, int, double)> expand = [&](int old, int level, int ci, int cj, double w) {
    const int d = dof_index({level, ci, cj});
    if (d >= 0) {
      t.emplace_back(d, old, w);
      return;
    }
    FAIRSHAPE_ASSERT(support_inside(level, ci, cj, level + 1), "refinement dropped a basis function it cannot express");
    const int fine = level + 1;
    for (int a = 0; a <= r + 1; ++a) {
      int fi = 2 * ci - r + a;
      if (shape_.periodic_u) fi = wrap_u(fine, fi);
      else if (fi < 0 || fi >= controls_u(fine)) continue;  // support outside the domain
      for (int b = 0; b <= r + 1; ++b) {
        const int fj = 2 * cj - r + b;
        if (fj < 0 || fj >= controls_v(fine)) continue;
        expand(old, fine, fi, fj, w * mask[a] * mask[b]);
      }
    }
  };
  for (int k = 0; k < static_cast<int>(old_dofs.size()); ++k) expand(k, old_dofs[k].level, old_dofs[k].i, old_dofs[k].j, 1.0);
  SparseMatrix T(dof_count(), static_cast<Eigen::Index>(old_dofs.size()));
  T.setFromTriplets(t.begin(), t.end());
  return T;
}

void HierarchicalSurface::add_leaf_cells(int level, int i, int j, std::vector<SpanId>& out) const {
  const int fine = level + 1;
  bool refined = false;
  for (int a = 0; a < 2 && !refined; ++a)
    for (int b = 0; b < 2; ++b)
      if (has_span({fine, 2 * i + a, 2 * j + b})) refined = true;
  if (!refined) {
    out.push_back({level, i, j});
    return;
  }
  for (int a = 0; a < 2; ++a)
    for (int b = 0; b < 2; ++b) {
      const SpanId child{fine, 2 * i + a, 2 * j + b};
      if (has_span(child)) add_leaf_cells(fine, child.i, child.j, out);
      else out.push_back(child);  // only layers ≤ level reach here: one polynomial piece
    }
}

std::vector<SpanId> HierarchicalSurface::leaf_cells() const {
  std::vector<SpanId> out;
  for (int i = 0; i < shape_.spans_u; ++i)
    for (int j = 0; j < shape_.spans_v; ++j) add_leaf_cells(0, i, j, out);
  return out;
}

bool HierarchicalSurface::in_domain(double u, double v) const {
  if (!std::isfinite(u) || !std::isfinite(v)) return false;
  if (v < 0 || v > shape_.spans_v) return false;
  return shape_.periodic_u || (u >= 0 && u <= shape_.spans_u);
}

namespace {
// The span index of coordinate x at a level with n spans of width 1/scale (x = n at the end).
int span_of(double x, double scale, int n) { return std::min(static_cast<int>(std::floor(x * scale)), n - 1); }
}  // namespace

SpanId HierarchicalSurface::leaf_cell_at(double u, double v) const {
  if (shape_.periodic_u) u -= shape_.spans_u * std::floor(u / shape_.spans_u);
  SpanId cell{0, span_of(u, 1, spans_u(0)), span_of(v, 1, spans_v(0))};
  for (int level = 1; level < level_count(); ++level) {
    const double s = std::ldexp(1.0, level);
    const SpanId fine{level, span_of(u, s, spans_u(level)), span_of(v, s, spans_v(level))};
    if (!has_span(fine)) {
      // Inside a refined parent but outside Ω_level: the leaf is this child cell.
      if (has_span({level, 2 * cell.i, 2 * cell.j}) || has_span({level, 2 * cell.i + 1, 2 * cell.j}) ||
          has_span({level, 2 * cell.i, 2 * cell.j + 1}) || has_span({level, 2 * cell.i + 1, 2 * cell.j + 1}))
        return fine;
      break;
    }
    cell = fine;
  }
  return cell;
}

void HierarchicalSurface::basis(double u, double v, BasisRow& out) const {
  FAIRSHAPE_ASSERT(in_domain(u, v), "basis evaluated outside the parameter domain");
  out.clear();
  if (shape_.periodic_u) u -= shape_.spans_u * std::floor(u / shape_.spans_u);
  const int r = shape_.degree;
  for (int level = 0; level < level_count(); ++level) {
    const double s = std::ldexp(1.0, level);
    const int i = span_of(u, s, spans_u(level)), j = span_of(v, s, spans_v(level));
    if (!has_span({level, i, j})) break;  // nested layers: no finer one reaches here either
    const SpanBasis bu = uniform_span_basis(r, u * s - i), bv = uniform_span_basis(r, v * s - j);
    for (int a = 0; a <= r; ++a) {
      const int ci = shape_.periodic_u ? wrap_u(level, i + a) : i + a;
      for (int b = 0; b <= r; ++b) {
        const int d = dof_index({level, ci, j + b});
        if (d < 0) continue;
        out.push_back({d, bu.value[a] * bv.value[b], s * bu.d1[a] * bv.value[b], s * bu.value[a] * bv.d1[b],
                       s * s * bu.d2[a] * bv.value[b], s * s * bu.d1[a] * bv.d1[b], s * s * bu.value[a] * bv.d2[b]});
      }
    }
  }
}

Vec3 HierarchicalSurface::position(const Eigen::MatrixXd& P, double u, double v) const {
  BasisRow row;
  basis(u, v, row);
  Vec3 x = Vec3::Zero();
  for (const BasisEntry& e : row) x += e.value * P.row(e.dof).transpose();
  return x;
}

void HierarchicalSurface::derivatives(const Eigen::MatrixXd& P, double u, double v, Vec3& du, Vec3& dv) const {
  BasisRow row;
  basis(u, v, row);
  du.setZero();
  dv.setZero();
  for (const BasisEntry& e : row) {
    du += e.du * P.row(e.dof).transpose();
    dv += e.dv * P.row(e.dof).transpose();
  }
}

}  // namespace fairshape::bspline
