#include "remesh/closest_point.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/error.h"

namespace fairshape {

using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

struct ClosestPointQuery::Impl {
  std::vector<Triangle> triangles;
  std::vector<int> face_of;  // the polygon each fan triangle comes from
  Tree tree;
};

ClosestPointQuery::ClosestPointQuery(const SurfaceMesh& s) : impl_(std::make_unique<Impl>()) {
  auto point = [&s](int v) { return Kernel::Point_3(s.positions()(v, 0), s.positions()(v, 1), s.positions()(v, 2)); };
  for (int f = 0; f < s.n_faces(); ++f) {
    const auto vs = s.face_vertices(f);
    for (std::size_t i = 1; i + 1 < vs.size(); ++i) {
      impl_->triangles.emplace_back(point(vs[0]), point(vs[i]), point(vs[i + 1]));
      impl_->face_of.push_back(f);
    }
  }
  if (impl_->triangles.empty()) throw InvalidInput("closest point query: the surface has no faces");
  impl_->tree.insert(impl_->triangles.begin(), impl_->triangles.end());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

ClosestPointQuery::~ClosestPointQuery() = default;

MatrixX3 ClosestPointQuery::closest_points(const MatrixX3& points, std::vector<int>* faces) const {
  MatrixX3 out(points.rows(), 3);
  if (faces) faces->assign(static_cast<std::size_t>(points.rows()), -1);
  tbb::parallel_for(tbb::blocked_range<Eigen::Index>(0, points.rows(), 512), [&](const auto& r) {
    for (Eigen::Index i = r.begin(); i != r.end(); ++i) {
      const auto hit = impl_->tree.closest_point_and_primitive(Kernel::Point_3(points(i, 0), points(i, 1), points(i, 2)));
      const auto& q = hit.first;
      out.row(i) << q.x(), q.y(), q.z();
      if (faces) (*faces)[static_cast<std::size_t>(i)] = impl_->face_of[static_cast<std::size_t>(hit.second - impl_->triangles.begin())];
    }
  });
  return out;
}

}  // namespace fairshape
