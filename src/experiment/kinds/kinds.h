// The run kinds fairshape ships; each lives in its own folder beside this file.
#pragma once

#include <memory>

#include "fairshape/experiment/run_kind.h"

namespace fairshape {

std::unique_ptr<RunKind> make_surface_edit_kind();  // Boier-Martin et al.: input.mesh, energy, constraints
std::unique_ptr<RunKind> make_sheet_kind();         // Welch & Witkin: sheets
std::unique_ptr<RunKind> make_curve_kind();         // Sauvage et al.: input.curve
std::unique_ptr<RunKind> make_feature_kind();       // Khodakovsky & Schröder: features

}  // namespace fairshape
