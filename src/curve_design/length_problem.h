// The optimization problem of Sauvage, Hahmann and Bonneau, "Length preserving
// multiresolution editing of curves" (§3, eq. 2): minimize Σ_t w_t E_t(X) — by default
// (1−β)·bending + β·D, D the distance to the attracting curve — subject to constraint rows
// f_r(X) = 0 (segment lengths, pinned points). Built once per edit; solvers only read it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "fairshape/core/types.h"
#include "fairshape/curve_design/curve_constraint.h"
#include "fairshape/curve_design/curve_energy.h"

namespace fairshape {

struct WeightedStencils {
  std::string name;
  double weight = 1.0;
  std::vector<CurveStencil> stencils;
};

// β = 0 would leave rigid motions free (neither bending nor lengths see them): D keeps at
// least this weight so the curve stays where the attracting curve puts it.
inline constexpr double kMinimumAttractorWeight = 1e-9;

class LengthProblem {
 public:
  //! \throw InvalidInput when no segment-length constraint is given, or when pinned points are
  //! farther apart than the curve between them is long (no curve can satisfy the edit).
  LengthProblem(MatrixX3 attractor, bool closed, std::vector<WeightedStencils> energies,
                std::vector<std::unique_ptr<CurveConstraint>> constraints);

  int n_points() const { return static_cast<int>(attractor_.rows()); }
  bool closed() const { return closed_; }
  const MatrixX3& attractor() const { return attractor_; }
  const std::vector<WeightedStencils>& energies() const { return energies_; }
  const std::vector<std::unique_ptr<CurveConstraint>>& constraints() const { return constraints_; }
  const SegmentLengths& lengths() const { return *lengths_; }
  int n_constraint_rows() const { return n_rows_; }

  // The objective F(X) = ½ Σ_c X_cᵀ Q X_c − Σ_c b_cᵀ X_c + const.
  const SparseMatrix& objective_hessian() const { return Q_; }  // N×N, shared by x, y, z
  const MatrixX3& objective_linear_term() const { return b_; }
  double objective(const MatrixX3& X) const;
  double energy(const std::string& name, const MatrixX3& X) const;  // one unweighted term
  MatrixX3 objective_gradient(const MatrixX3& X) const { return Q_ * X - b_; }

  //! Every constraint row at X, in order (constraint by constraint).
  std::vector<ConstraintRow> rows(const MatrixX3& X) const;
  //! Adds Σ_r scale_r ∇²f_r over interleaved unknowns (3·point + coordinate).
  void add_constraint_hessians(const Eigen::VectorXd& scale, Triplets& out) const;
  void add_row_hessian(int row, double scale, Triplets& out) const;  // one row's share of the above
  double row_scale(int row) const;

  //! max_i | |X_{i+1} − X_i| − l_i | / l_i
  double max_relative_length_error(const MatrixX3& X) const;
  //! The largest relative error of the constraints other than the lengths: pins (distance
  //! over the curve's length), tangents (angle); 0 without them.
  double max_relative_pin_error(const MatrixX3& X) const;
  //! How far X is from a constrained stationary point: min_λ |∇F + Jᵀλ| (least squares)
  //! over |QX| + |b|. Zero exactly at a KKT point.
  double stationarity(const MatrixX3& X) const;

 private:
  void check_pins_reachable() const;

  MatrixX3 attractor_;
  bool closed_;
  std::vector<WeightedStencils> energies_;
  std::vector<std::unique_ptr<CurveConstraint>> constraints_;
  const SegmentLengths* lengths_ = nullptr;
  int n_rows_ = 0;
  SparseMatrix Q_;
  MatrixX3 b_;
};

//! The constraint Jacobian (rows × 3N, interleaved unknowns) of evaluated rows.
SparseMatrix constraint_jacobian(const std::vector<ConstraintRow>& rows, int n_points);

}  // namespace fairshape
