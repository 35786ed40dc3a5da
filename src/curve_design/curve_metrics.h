// What a curve experiment reports about a result (the CSV columns of configs/sauvage).
#pragma once

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

}  // namespace fairshape
