// The one-dimensional hierarchical B-spline basis of a variational space curve (
// Welch & Witkin, "Variational surface modeling", §3 and §5: curves are variational objects
// "refined as needed" like the sheets). The same construction as the sheets'
// (bspline/hierarchical_surface.h) on t ∈ [0, 1]: layer L has `spans` · 2^L equal spans of
// degree r, clamped at both ends; Ω_L is a set of its spans, Ω_0 all of them, Ω_{L+1} inside
// the children of Ω_L. A layer-L function is an unknown when its support lies in Ω_L but not
// wholly in Ω_{L+1} (Kraft's selection: the finer layer spans it there), so the basis is
// linearly independent and C^{r−1} however the layers nest.
//
// Evaluation goes through one clamped knot basis on the leaf cells' breaks (the union of the
// layers' knots where they are active): every hierarchical function is a spline on those
// knots, so X(t) = Σ_i T_i(t) x_i with x = R q, R (knot functions × unknowns) exact. Energies,
// constraint rows and the mortar coupling to a sheet are assembled on the knot basis and
// mapped by R — one integration path for uniform and refined curves.
#pragma once

#include <set>
#include <vector>

#include "fairshape/bspline/knot_basis.h"
#include "fairshape/core/types.h"

namespace fairshape::bspline {

struct CurveSpan {
  int level = 0, index = 0;  // span `index` of layer `level`: [index, index + 1] / (spans · 2^level)
  double t0 = 0, t1 = 0;     // its parameter interval
};

class HierarchicalCurveBasis {
 public:
  //! \throw InvalidInput for spans < 1 or beyond kMaxSpans, or a degree outside [2, 5].
  HierarchicalCurveBasis(int spans, int degree);
  static constexpr int kMaxSpans = 1 << 16;
  static constexpr int kMaxLevel = 12;

  int base_spans() const { return spans_; }
  int degree() const { return degree_; }
  int level_count() const { return static_cast<int>(omega_.size()); }
  int spans(int level) const { return spans_ << level; }
  int dof_count() const { return static_cast<int>(dofs_.size()); }

  //! The spans on which X is one polynomial (a layer's span with no finer span inside), in t order.
  const std::vector<CurveSpan>& leaf_cells() const { return leaves_; }
  //! The leaf cell holding t ∈ [0, 1] (the last one at t = 1).
  const CurveSpan& leaf_cell_at(double t) const;

  //! The clamped basis on the leaf cells' breaks and R (knot_basis().size() × dof_count()).
  const ClampedKnotBasis& knot_basis() const { return knots_; }
  const SparseMatrix& to_knot_basis() const { return R_; }

  //! Adds layer-(L+1) spans over the given leaf cells (each of layer L), widened by r fine
  //! spans on either side so a refined cell gets free functions of its own, clipped to the
  //! domain and to the children of Ω_L, and closed under siblings (a parent refines whole, so
  //! the leaf cells tile [0, 1]). Returns the number of spans added.
  //! \throw InvalidInput for a cell that is not a leaf or a level beyond kMaxLevel.
  int refine(const std::vector<CurveSpan>& cells);

 private:
  struct Function {
    int level, index;  // layer-L clamped uniform B-spline `index`, 0 ≤ index < spans(L) + r
  };
  //! Its support as layer-L spans [first, last] (clipped to the layer).
  void support(const Function& f, int& first, int& last) const;
  //! The knots τ_0..τ_{r+1} of a layer function (clamped: repeated 0 and 1 at the ends).
  std::vector<double> function_knots(const Function& f) const;
  bool support_in(const Function& f, int level) const;
  void rebuild();

  int spans_, degree_;
  std::vector<std::set<int>> omega_;  // Ω_L, span indices of layer L
  std::vector<Function> dofs_;
  std::vector<CurveSpan> leaves_;
  ClampedKnotBasis knots_;
  SparseMatrix R_;
};

//! One B-spline of degree r on its own knots τ_0 ≤ … ≤ τ_{r+1} at x (Cox–de Boor; 0 outside
//! [τ_0, τ_{r+1})).
double single_bspline(const std::vector<double>& knots, double x);

}  // namespace fairshape::bspline
