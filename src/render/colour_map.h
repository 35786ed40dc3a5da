// Colour maps for scalar fields: viridis (perceptually uniform, for magnitudes) and a
// diverging blue–white–red map (for signed quantities, centred on zero), as VTK transfer
// functions over a given range.
#pragma once

#include <vtkColorTransferFunction.h>
#include <vtkSmartPointer.h>

#include "fairshape/core/name_table.h"

namespace fairshape::render {

enum class ColourMap { Viridis, Diverging, Grey };
//! viridis | diverging | grey
const NameTable<ColourMap>& colour_map_names();

//! The map spread over [lo, hi] (lo < hi).
vtkSmartPointer<vtkColorTransferFunction> colour_transfer(ColourMap map, double lo, double hi);

}  // namespace fairshape::render
