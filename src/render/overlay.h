// Where the constraints are, drawn over a panel from an overlay file (the <stem>_constraints.vtp
// a run writes beside each result .vtp, or any curve or point file): fixed vertices as small grey
// spheres (a tint of the pinned region), handles as red spheres with an arrow from where they
// started, normal targets as magenta arrows, curves (constraint and feature curves) as
// orange tubes. Sizes follow the scene's diagonal.
#pragma once

#include <vtkPolyData.h>
#include <vtkProp.h>
#include <vtkSmartPointer.h>

#include <vector>

namespace fairshape::render {

//! `curve_radius`: the curves' tubes, × the scene's diagonal (SurfaceStyle::overlay_curve_radius).
std::vector<vtkSmartPointer<vtkProp>> overlay_props(vtkPolyData* overlay, double scene_diagonal, double curve_radius);

}  // namespace fairshape::render
