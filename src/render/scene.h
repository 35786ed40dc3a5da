// One panel's props: the surface (Phong-shaded, smooth normals unless asked flat, optional
// edges and control mesh) or the curve (a tube), coloured by a scalar of its point data.
#pragma once

#include <vtkDoubleArray.h>
#include <vtkProp.h>
#include <vtkScalarsToColors.h>
#include <vtkSmartPointer.h>

#include <string>
#include <vector>

#include "fairshape/core/name_table.h"
#include "fairshape/render/colour_map.h"
#include "fairshape/render/render_source.h"

namespace fairshape::render {

//! How a vector array becomes one scalar per point; `normal` is its component along the
//! rendered surface's unit normal (signed: a groove and a ridge get opposite signs).
enum class Component { Magnitude, X, Y, Z, Normal };
const NameTable<Component>& component_names();  // magnitude | x | y | z | normal

struct Colouring {
  std::string array;  // a point array; empty: plain colour
  Component component = Component::Magnitude;
  bool component_given = false;  // false: magnitude for vectors, the value for scalars
  ColourMap map = ColourMap::Viridis;
  bool map_given = false;  // false: viridis, or diverging for a signed component
  bool signed_values() const { return component_given && component != Component::Magnitude; }
  ColourMap effective_map() const { return map_given ? map : signed_values() ? ColourMap::Diverging : ColourMap::Viridis; }
};

struct SurfaceStyle {
  bool flat = false;          // facet normals instead of smooth ones
  bool edges = false;         // the rendered mesh's edges
  int control_level = -1;     // ≥ 0: that level of the source's hierarchy as a wireframe
  double tube_radius = 0.004; // curves, × the scene's diagonal
  //! Curves of an overlay (constraint and feature curves), thinner by default so that a fine
  //! feature beside its curve stays visible; outlines are drawn at half of it.
  double overlay_curve_radius = 0.0018;
};

//! The scalar `c` asks for on `data`, named "__scalar". \throw InvalidInput for an unknown
//! array (listing the available ones) or a component a scalar array lacks.
vtkSmartPointer<vtkDoubleArray> panel_scalars(vtkPolyData* data, const Colouring& c, const std::string& path);

//! The props of one panel; `colours` null: plain colour.
std::vector<vtkSmartPointer<vtkProp>> panel_props(const RenderSource& source, vtkDoubleArray* scalars,
                                                  vtkScalarsToColors* colours, double lo, double hi,
                                                  const SurfaceStyle& style, double scene_diagonal);

}  // namespace fairshape::render
