// What a curve experiment reports about a result (the CSV columns of configs/sauvage).
#pragma once

#include <vector>

#include "fairshape/core/types.h"

namespace fairshape {

struct CurveMetrics {
  double length_error_max = 0;     // max_i | |Δc_i| − l_i | / l_i
  double length_error_rms = 0;     // the same, root mean square over segments
  double total_length_change = 0;  // (L − L_ref) / L_ref, signed
  double bending_energy = 0;       // Sauvage et al. §3's E
  double distance_to_attractor = 0;  // Sauvage et al. §3's D = Σ|c_i − a_i|²
  int wrinkles = 0;                // sign changes of the discrete curvature
};

CurveMetrics measure_curve(const MatrixX3& X, bool closed, const Eigen::VectorXd& reference_lengths,
                           const MatrixX3& attractor);

//! Sign changes of the signed turning angle along the curve, measured about the normal of the
//! curve's best-fit plane (the z axis for curves in the xy plane). Turns below 1e-4 rad count
//! as straight and keep the previous sign, so numerical noise on straight runs is not counted.
int count_wrinkles(const MatrixX3& X, bool closed);

//! How much of the edit the result shows at its handles: min over moved points p of
//! (X_p − R_p)·(D_p − R_p) / |D_p − R_p|² (R the reference, D the edited curve): 1 where a
//! handle went where it was put, 0 where it came back. Handles not moved by the edit (D_p = R_p)
//! are left out; 1 without any.
double handle_reach(const MatrixX3& reference, const MatrixX3& edited, const MatrixX3& X, const std::vector<int>& moved);

//! How far an edit over-stretches the curve: max over moved points p and control points q
//! (every `stride`-th point) of |X_p − X_q| / (the arc length between them, from `lengths`) − 1,
//! closed curves taking the shorter arc. > 0: no curve with these lengths puts p there.
double worst_overstretch(const MatrixX3& X, const Eigen::VectorXd& lengths, bool closed, int stride, const std::vector<int>& moved);

//! Below this handle_reach an edit counts as undone (edit_undone): the result kept less than
//! half of the displacement asked.
inline constexpr double kUndoneReach = 0.5;

}  // namespace fairshape
