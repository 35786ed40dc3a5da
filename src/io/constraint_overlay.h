// The overlay file a run writes beside a result .vtp (<stem>_constraints.vtp) so a figure can
// show where its constraints are, and fairshape render draws: points with a `kind` each
// (fixed vertex, handle with its offset, normal target), and curves as polylines. One format
// for every run kind, written here and read by src/render/overlay.
#pragma once

#include <string>
#include <vector>

#include "fairshape/core/types.h"

namespace fairshape {

//! Values of the overlay's `kind` point array.
//! OutlinePoint: a point of an outline (a region's boundary, e.g. a feature's neighbourhood), drawn
//! thinner and darker than a curve.
enum class OverlayKind : int { OutlinePoint = -2, CurvePoint = -1, Fixed = 0, Handle = 1, Normal = 2 };
inline constexpr const char* kOverlayKind = "kind";            // OverlayKind per point
inline constexpr const char* kOverlayOffset = "offset";        // a handle's displacement (it started at point − offset)
inline constexpr const char* kOverlayNormal = "target_normal";  // a normal target's unit normal

class ConstraintOverlay {
 public:
  void add_fixed(const Vec3& at) { add(at, OverlayKind::Fixed, Vec3::Zero(), Vec3::Zero()); }
  void add_handle(const Vec3& at, const Vec3& offset) { add(at, OverlayKind::Handle, offset, Vec3::Zero()); }
  void add_normal(const Vec3& at, const Vec3& normal) { add(at, OverlayKind::Normal, Vec3::Zero(), normal.normalized()); }
  //! A polyline through `points` (closed: back to the first).
  void add_curve(const std::vector<Vec3>& points, bool closed = false);
  //! A region's outline through `points`.
  void add_outline(const std::vector<Vec3>& points);
  //! \throw OutputError as write_vtp.
  void write(const std::string& path) const;

 private:
  void add(const Vec3& at, OverlayKind kind, const Vec3& offset, const Vec3& normal);
  void add_line(const std::vector<Vec3>& points, bool closed, OverlayKind kind);
  std::vector<Vec3> points_, offsets_, normals_;
  std::vector<OverlayKind> kinds_;
  std::vector<std::vector<int>> lines_;
};

}  // namespace fairshape
