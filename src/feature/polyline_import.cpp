#include "fairshape/feature/polyline_import.h"

#include <vector>

#include "fairshape/io/mesh_io.h"
#include "fairshape/io/text_scanner.h"

namespace fairshape::feature {
namespace {

Polyline read_point_list(const std::string& path) {
  const std::string text = io::internal::read_whole_file(path);
  io::internal::TextScanner scan(text, path);
  std::vector<Vec3> points;
  while (scan.next_line()) {
    const auto& tok = scan.tokens();
    if (tok.size() != 3) scan.fail(std::string("expected a point 'x y z', got ") + std::to_string(tok.size()) + " values");
    points.emplace_back(scan.to_double(tok[0], "x"), scan.to_double(tok[1], "y"), scan.to_double(tok[2], "z"));
  }
  Polyline c;
  c.closed = points.size() > 3 && points.front() == points.back();
  if (c.closed) points.pop_back();
  c.points.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) c.points.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return c;
}

}  // namespace

Polyline read_curve_points(const std::string& path) {
  const bool obj = path.size() >= 4 && (path.substr(path.size() - 4) == ".obj" || path.substr(path.size() - 4) == ".OBJ");
  const Polyline c = obj ? read_polyline(path) : read_point_list(path);
  if (c.n_points() < 2)
    throw InvalidInput(path + ": a curve needs at least 2 points, the file has " + std::to_string(c.n_points()));
  return c;
}

}  // namespace fairshape::feature
