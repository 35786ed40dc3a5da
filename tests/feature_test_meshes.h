// Small analytic meshes the feature tests draw on (feature_test, feature_profile_test,
// curve_placement_test): one definition, so the tests measure the same surfaces.
#pragma once

#include <cmath>
#include <numbers>

#include "fairshape/mesh/surface_mesh.h"
#include "fairshape/subdivision/scheme.h"

namespace fairshape::test {

// A triangulated n × n grid on [0, size]² in the plane z = 0 (diagonals alternating).
inline SurfaceMesh plane_grid(int n, double size) {
  MatrixX3 V((n + 1) * (n + 1), 3);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) V.row(j * (n + 1) + i) << size * i / n, size * j / n, 0.0;
  PolygonList faces;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      if ((i + j) % 2 == 0) {
        faces.push_back({a, b, d});
        faces.push_back({a, d, c});
      } else {
        faces.push_back({a, b, c});
        faces.push_back({b, d, c});
      }
    }
  return SurfaceMesh::from_polygons(V, faces);
}

// An open cylinder of radius R around z: `around` vertices per ring, `rings` + 1 rings over height H.
inline SurfaceMesh cylinder(int around, int rings, double R, double H) {
  MatrixX3 V(around * (rings + 1), 3);
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i < around; ++i) {
      const double phi = 2 * std::numbers::pi * i / around;
      V.row(j * around + i) << R * std::cos(phi), R * std::sin(phi), H * j / rings;
    }
  PolygonList faces;
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < around; ++i) {
      const int a = j * around + i, b = j * around + (i + 1) % around, c = a + around, d = b + around;
      faces.push_back({a, b, d});
      faces.push_back({a, d, c});
    }
  return SurfaceMesh::from_polygons(V, faces);
}

// Loop subdivision with the default rules: the scheme of every feature hierarchy.
inline SubdivisionOptions loop_options() {
  SubdivisionOptions opt;
  opt.scheme = SchemeType::Loop;
  return opt;
}

// The length of a mesh's bounding-box diagonal: the scale feature tolerances are relative to.
inline double diagonal(const SurfaceMesh& m) {
  return (m.positions().colwise().maxCoeff() - m.positions().colwise().minCoeff()).norm();
}

}  // namespace fairshape::test
