#include "fairshape/remesh/closest_point.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <atomic>
#include <limits>

#include "fairshape/core/error.h"
#include "fairshape/core/parallel_for.h"  // serial without TBB

namespace fairshape {

using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

struct ClosestPointQuery::Impl {
  std::vector<Triangle> triangles;
  std::vector<int> face_of;  // the polygon each fan triangle comes from
  std::vector<Kernel::Vector_3> normal;  // of each fan triangle, unnormalised, as the polygon is oriented
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
  for (const auto& t : impl_->triangles) impl_->normal.push_back(CGAL::cross_product(t[1] - t[0], t[2] - t[0]));
  impl_->tree.insert(impl_->triangles.begin(), impl_->triangles.end());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
}

ClosestPointQuery::~ClosestPointQuery() = default;

MatrixX3 ClosestPointQuery::closest_points(const MatrixX3& points, std::vector<int>* faces) const {
  MatrixX3 out(points.rows(), 3);
  if (faces) faces->assign(static_cast<std::size_t>(points.rows()), -1);
  for_each_range(Eigen::Index{0}, points.rows(), 512, [&](const auto& r) {
    for (Eigen::Index i = r.begin(); i != r.end(); ++i) {
      const auto hit = impl_->tree.closest_point_and_primitive(Kernel::Point_3(points(i, 0), points(i, 1), points(i, 2)));
      const auto& q = hit.first;
      out.row(i) << q.x(), q.y(), q.z();
      if (faces) (*faces)[static_cast<std::size_t>(i)] = impl_->face_of[static_cast<std::size_t>(hit.second - impl_->triangles.begin())];
    }
  });
  return out;
}

MatrixX3 ClosestPointQuery::facing_points(const MatrixX3& points, const MatrixX3& normals, double reach,
                                         int* unmoved) const {
  using Segment = Kernel::Segment_3;
  using Hit = Tree::Intersection_and_primitive_id<Segment>::Type;
  if (reach <= 0) return closest_points(points);
  MatrixX3 out(points.rows(), 3);
  std::atomic<int> stuck{0};
  for_each_range(Eigen::Index{0}, points.rows(), 256, [&](const auto& r) {
    std::vector<Hit> hits;
    for (Eigen::Index i = r.begin(); i != r.end(); ++i) {
      const Kernel::Point_3 p(points(i, 0), points(i, 1), points(i, 2));
      const Kernel::Vector_3 n(normals(i, 0), normals(i, 1), normals(i, 2));
      auto facing = [&](Tree::Primitive_id id) { return n * impl_->normal[static_cast<std::size_t>(id - impl_->triangles.begin())] > 0; };
      const double len = std::sqrt(n.squared_length());
      double best = std::numeric_limits<double>::infinity();
      Kernel::Point_3 q = p;
      if (len > 0) {
        const Kernel::Vector_3 step = n * (reach / len);
        hits.clear();
        impl_->tree.all_intersections(Segment(p - step, p + step), std::back_inserter(hits));
        for (const Hit& h : hits) {
          const auto* x = boost::get<Kernel::Point_3>(&h.first);
          if (!x || !facing(h.second)) continue;
          const double d = CGAL::squared_distance(p, *x);
          if (d < best) best = d, q = *x;
        }
      }
      if (best == std::numeric_limits<double>::infinity()) {
        ++stuck;
        q = impl_->tree.closest_point(p);
      }
      out.row(i) << q.x(), q.y(), q.z();
    }
  });
  if (unmoved) *unmoved = stuck.load();
  return out;
}

Eigen::VectorXd ClosestPointQuery::ray_distances(const MatrixX3& points, const MatrixX3& directions, double skip) const {
  using Ray = Kernel::Ray_3;
  using Hit = Tree::Intersection_and_primitive_id<Ray>::Type;
  Eigen::VectorXd out = Eigen::VectorXd::Constant(points.rows(), std::numeric_limits<double>::infinity());
  for_each_range(Eigen::Index{0}, points.rows(), 64, [&](const auto& r) {
    std::vector<Hit> hits;
    for (Eigen::Index i = r.begin(); i != r.end(); ++i) {
      const Kernel::Point_3 p(points(i, 0), points(i, 1), points(i, 2));
      const Kernel::Vector_3 d(directions(i, 0), directions(i, 1), directions(i, 2));
      if (d.squared_length() == 0) continue;
      hits.clear();
      impl_->tree.all_intersections(Ray(p, d), std::back_inserter(hits));
      for (const Hit& h : hits) {
        const auto* x = boost::get<Kernel::Point_3>(&h.first);
        if (!x) continue;  // a ray along a face: no crossing
        const double t = std::sqrt(CGAL::squared_distance(p, *x));
        if (t > skip) out[i] = std::min(out[i], t);
      }
    }
  });
  return out;
}

}  // namespace fairshape
