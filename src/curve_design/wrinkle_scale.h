// Wrinkles as numbers: the scale and size of what length preservation adds
// to the curve the designer asked for. Sauvage, Hahmann and Bonneau's §4 says the wrinkle level
// w, the edit level e and β set the wrinkles' scale; counting curvature sign changes cannot test
// that (it counts the input's own ripple and means nothing for a 3-D curve). Measured here on
// the change d = C_F − C_A (the final curve minus the attracting curve, point by point), in a
// frame that turns with the attracting curve (tangent and a rotation-minimizing normal pair),
// so that a ripple across a bending curve is seen at its own frequency; any dimension:
//   amplitude   the RMS of |d − mean d| over the points;
//   wavelength  L / k*, k* the frequency (cycles over the curve's length L) where the power
//               spectrum of d, resampled uniformly in the attracting curve's arc length, peaks
//               (k ≥ 1; an open curve's d is detrended and Hann-windowed first so that its ends
//               do not leak into every frequency).
#pragma once

#include "fairshape/core/types.h"

namespace fairshape {

struct WrinkleScale {
  double amplitude = 0;
  double wavelength = 0;           // world units
  double wavelength_segments = 0;  // the same in mean segment lengths of the attracting curve
};

//! \pre final and attracting have the same points (≥ 4), closed: no repeated last point.
WrinkleScale wrinkle_scale(const MatrixX3& final, const MatrixX3& attracting, bool closed);

}  // namespace fairshape
