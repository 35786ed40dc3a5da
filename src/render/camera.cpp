#include "fairshape/render/camera.h"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

namespace fairshape::render {

const NameTable<UpAxis>& up_axis_names() {
  static const NameTable<UpAxis> t{{UpAxis::X, "x"}, {UpAxis::Y, "y"}, {UpAxis::Z, "z"}};
  return t;
}

const NameTable<NamedView>& named_view_names() {
  static const NameTable<NamedView> t{
      {NamedView::Front, "front"}, {NamedView::Side, "side"}, {NamedView::Top, "top"}, {NamedView::Iso, "iso"}};
  return t;
}

void place_camera(vtkRenderer* renderer, const ViewSpec& v, const double b[6]) {
  // The model's frame: up, the direction the front view looks from, and right = up × it.
  const Vec3 up = v.up == UpAxis::X ? Vec3::UnitX() : v.up == UpAxis::Y ? Vec3::UnitY() : Vec3::UnitZ();
  const Vec3 front = v.up == UpAxis::Z ? Vec3(-Vec3::UnitY()) : Vec3(Vec3::UnitZ());
  const Vec3 right = up.cross(front);
  Vec3 from = front, view_up = up;
  if (v.view == NamedView::Side) from = right;
  if (v.view == NamedView::Top) {
    from = up;
    view_up = -front;  // the model's front at the bottom of the image
  }
  const Vec3 centre((b[0] + b[1]) / 2, (b[2] + b[3]) / 2, (b[4] + b[5]) / 2);
  vtkCamera* cam = renderer->GetActiveCamera();
  const Vec3 focal = v.focused ? v.focus : centre;
  cam->SetFocalPoint(focal.data());
  const Vec3 eye = focal + from;
  cam->SetPosition(eye.data());
  cam->SetViewUp(view_up.data());
  if (v.view == NamedView::Iso) {
    cam->Azimuth(30);
    cam->Elevation(20);
  }
  cam->Azimuth(v.azimuth);
  cam->Elevation(v.elevation);
  cam->OrthogonalizeViewUp();
  if (v.focused) {
    // The sphere of `radius` about the focus fills the view's height.
    const double half_angle = cam->GetViewAngle() / 2 * std::numbers::pi / 180;
    double position[3];
    cam->GetPosition(position);
    const Vec3 towards_eye = (Vec3(position[0], position[1], position[2]) - focal).normalized();
    const Vec3 placed = focal + towards_eye * (v.radius / std::sin(half_angle));
    cam->SetPosition(placed.data());
  } else {
    renderer->ResetCamera(b);
  }
  cam->Zoom(v.zoom);
  renderer->ResetCameraClippingRange(b);
}

}  // namespace fairshape::render
