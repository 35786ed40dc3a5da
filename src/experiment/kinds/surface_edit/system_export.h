// output.system: a surface edit's assembled problem as Matrix Market files in
// system/<run_id>/, so any external solver can be tried on exactly the
// problem fairshape solved. SciPy reads every file (scipy.io.mmread); README.txt in the folder
// says what each one is.
#pragma once

#include <string>

#include "fairshape/design/edit_solve.h"
#include "fairshape/subdivision/multires_surface.h"

namespace fairshape {

//! The program min ½ tr(Δᵀ H Δ) − tr(gᵀ Δ) subject to A Δ = C (and A_coupled vec(Δ) = C_coupled),
//! and the prolongations of `h` from level 0 up to the edit level `level`. With `paper_solution` (constraint_mode paper, no coupled rows):
//! also the reduced system the free solve saw — A_free Δ_free = b_free, the constrained
//! vertices held at their minimum-norm values taken from the solution.
//! \throw OutputError when a file cannot be written.
void write_edit_system(const EditProblem& p, const MultiresSurface& h, int level, const std::string& folder,
                       const Eigen::MatrixXd* paper_solution);

}  // namespace fairshape
