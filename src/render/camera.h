// Cameras in the model's own frame: named views (front, side, top, iso) for a model whose up
// axis is x, y or z, turned by azimuth and elevation, fitted to the scene or focused on a
// point; one camera serves every panel of a figure.
#pragma once

#include <vtkCamera.h>
#include <vtkRenderer.h>

#include "fairshape/core/name_table.h"
#include "fairshape/core/types.h"

namespace fairshape::render {

enum class UpAxis { X, Y, Z };
enum class NamedView { Front, Side, Top, Iso };
const NameTable<UpAxis>& up_axis_names();      // x | y | z
const NameTable<NamedView>& named_view_names();  // front | side | top | iso

struct ViewSpec {
  NamedView view = NamedView::Iso;  // iso: front turned 30° about the up axis and raised 20°
  UpAxis up = UpAxis::Y;
  double azimuth = 0, elevation = 0;  // degrees, after the named view
  double zoom = 1;
  bool focused = false;  // look at `focus`, framing a sphere of `radius` (else fit the scene)
  Vec3 focus = Vec3::Zero();
  double radius = 0;
};

//! Sets `renderer`'s active camera for `bounds` (xmin, xmax, ymin, ymax, zmin, zmax).
void place_camera(vtkRenderer* renderer, const ViewSpec& view, const double bounds[6]);

}  // namespace fairshape::render
