// The hierarchical B-spline surface of Welch & Witkin, "Variational surface modeling" §3: a
// sum of uniform tensor-product layers, layer L with spans of width 2^-L (base-span units),
// each layer a sparse set of spans Ω_L (nested: Ω_{L+1} lies in the children of Ω_L).
//
// Control points of layer L are created when a span references them, and only those whose
// whole support lies in Ω_L are unknowns: the others are the paper's r-wide band of zero
// control points, which keeps the sum C^{r−1} however layers overlap. Regions of one layer
// that grow to meet are one set of spans, so they merge by construction.
//
// Improvement on the paper (documented in papers/welch-witkin/README.md): a coarse basis
// function whose support lies wholly inside Ω_{L+1} is a combination of layer-(L+1)
// functions, so the plain sum of layers is a linearly dependent generating set and H is
// singular along directions no constraint pins. Such coarse functions are dropped (Kraft's
// hierarchical basis) and refine() hands their coefficients to the finer layer through the
// B-spline refinement mask, so the surface does not change. Same function space, unique
// coefficients.
//
// Domain: u ∈ [0, spans_u], v ∈ [0, spans_v]; open in v, open or periodic in u (cylinders).
#pragma once

#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "fairshape/core/types.h"

namespace fairshape::bspline {

struct SheetShape {
  int spans_u = 4, spans_v = 4;
  int degree = 3;
  bool periodic_u = false;
  //! The length of one base span in the sheet's design units (u, v): the energy, tangent
  //! targets and every (u, v) a designer gives are in those units, so the same design at 8 or
  //! 32 spans is one problem (papers/welch-witkin/README.md, "Units"). The basis itself works
  //! in base-span units; VariationalSheet converts.
  Eigen::Vector2d span_size{1, 1};
};

struct SpanId {
  int level, i, j;
};
struct ControlId {
  int level, i, j;
};

//! One basis function that is nonzero at a point: its unknown and its value and derivatives
//! (in the base-span parameter units).
struct BasisEntry {
  int dof;
  double value, du, dv, duu, duv, dvv;
};
using BasisRow = std::vector<BasisEntry>;

class HierarchicalSurface {
 public:
  //! \throw InvalidInput for spans < 1, degree outside [2, 5], or a periodic direction with
  //! fewer than degree + 1 spans (a basis function would overlap itself).
  explicit HierarchicalSurface(const SheetShape& shape);
  //! The surface whose layer L is exactly spans_per_level[L] (any order), e.g. one read back
  //! from a sheet file: Ω is set directly rather than replayed through refine(), whose widening
  //! could not reproduce every nested set. Layer 0 must be the whole base grid, and no layer
  //! empty. \throw InvalidInput for a span outside its layer's grid, a span listed twice, a
  //! span whose parent is not in the layer below (Ω_{L+1} must lie in the children of Ω_L), or
  //! more than kMaxLevel + 1 layers, naming the span.
  static HierarchicalSurface from_layers(const SheetShape& shape, const std::vector<std::vector<SpanId>>& spans_per_level);

  const SheetShape& shape() const { return shape_; }
  int degree() const { return shape_.degree; }
  int level_count() const { return static_cast<int>(levels_.size()); }
  int spans_u(int level) const { return shape_.spans_u << level; }
  int spans_v(int level) const { return shape_.spans_v << level; }
  bool has_span(const SpanId& s) const;
  std::size_t span_count(int level) const { return levels_[level].spans.size(); }
  //! Ω_level, sorted by (i, j) so that files written from it are deterministic.
  std::vector<SpanId> spans(int level) const;
  //! Whether layer `level` can exist for this shape: its span and control-point counts fit an
  //! int (a wide base grid 2^level times finer would overflow them).
  bool level_fits(int level) const;

  int dof_count() const { return static_cast<int>(dofs_.size()); }
  const std::vector<ControlId>& dofs() const { return dofs_; }
  int dof_index(const ControlId& c) const;  // −1 when c is not an unknown

  //! Adds layer-(L+1) spans over the given layer-L spans, widened by r fine spans on every
  //! side (a single refined span would otherwise get no free control point) and clipped to
  //! the domain and to Ω_L. Returns T (new dofs × old dofs): the old surface's coefficients
  //! in the new basis are T p, exactly.
  //! \throw InvalidInput for a span that is not in Ω_L or a level beyond kMaxLevel.
  SparseMatrix refine(const std::vector<SpanId>& spans);
  static constexpr int kMaxLevel = 12;
  //! The largest base grid accepted: spans_u × spans_v ≤ 2^18 base spans (a 512 × 512 sheet,
  //! about 265k control points per coordinate before any refinement). Measured on the 24 GiB,
  //! 2-core machine (tests/cli/limits_slow.sh): 512 × 512 solves by KKT in 3 minutes and 4.3 GB;
  //! 1024 × 1024 took 12.5 GB and 6 minutes and its KKT system was then called singular.
  static constexpr long long kMaxBaseSpans = 1LL << 18;

  //! The cells on which the surface is one polynomial patch: spans of some layer with no
  //! finer span inside, tiling the domain (used for integration and per-span errors).
  std::vector<SpanId> leaf_cells() const;
  //! The leaf cell containing (u, v).
  SpanId leaf_cell_at(double u, double v) const;

  bool in_domain(double u, double v) const;
  //! The nonzero basis functions at (u, v), every layer. \pre in_domain(u, v).
  void basis(double u, double v, BasisRow& out) const;
  //! Σ value·P.row(dof) and its first derivatives.
  Vec3 position(const Eigen::MatrixXd& P, double u, double v) const;
  void derivatives(const Eigen::MatrixXd& P, double u, double v, Vec3& du, Vec3& dv) const;

 private:
  struct Layer {
    std::unordered_set<std::int64_t> spans;
  };
  std::int64_t key(int level, int i, int j) const { return static_cast<std::int64_t>(i) * spans_v(level) + j; }
  int wrap_u(int level, int i) const;
  int controls_u(int level) const { return shape_.periodic_u ? spans_u(level) : spans_u(level) + shape_.degree; }
  int controls_v(int level) const { return spans_v(level) + shape_.degree; }
  //! Every span (clipped or wrapped) of a control point's support lies in Ω_level.
  bool support_inside(int level, int ci, int cj, int region_level) const;
  bool is_unknown(int level, int ci, int cj) const;
  void rebuild_dofs();
  void add_leaf_cells(int level, int i, int j, std::vector<SpanId>& out) const;

  SheetShape shape_;
  std::vector<Layer> levels_;
  std::vector<ControlId> dofs_;
  std::vector<std::unordered_map<std::int64_t, int>> dof_of_;  // per level: control key → dof
};

}  // namespace fairshape::bspline
