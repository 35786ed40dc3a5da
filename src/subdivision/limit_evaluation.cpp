#include "fairshape/subdivision/limit_evaluation.h"

#include <opensubdiv/bfr/refinerSurfaceFactory.h>
#include <opensubdiv/bfr/surface.h>
#include <opensubdiv/far/topologyDescriptor.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "fairshape/core/error.h"

namespace fairshape {

namespace Osd = OpenSubdiv;

namespace {

// Refinement depth Bfr uses around extraordinary vertices before closing the patch tree with
// Gregory patches: the part of a face not covered by exact patches is 2^-kApproxLevel wide.
// 10 is OpenSubdiv's own ceiling for adaptive isolation; construction stays fast because the
// refinement is local to the vertex.
constexpr int kApproxLevel = 10;

std::unique_ptr<Osd::Far::TopologyRefiner> make_refiner(const SurfaceMesh& m, const SubdivisionOptions& opt) {
  using Factory = Osd::Far::TopologyRefinerFactory<Osd::Far::TopologyDescriptor>;
  std::vector<int> sizes, indices;
  for (int f = 0; f < m.n_faces(); ++f) {
    const auto vs = m.face_vertices(f);
    sizes.push_back(static_cast<int>(vs.size()));
    indices.insert(indices.end(), vs.begin(), vs.end());
  }
  // Crease and corner tags, as OpenSubdiv's descriptor takes them: without them a creased
  // mesh would be evaluated as smooth. Boundary edges need no tag (OpenSubdiv sharpens them).
  std::vector<int> crease_pairs, corners;
  std::vector<float> crease_weights, corner_weights;
  for (int e = 0; e < m.n_edges(); ++e)
    if (m.edge_sharpness(e) > 0.0f) {
      crease_pairs.insert(crease_pairs.end(), {m.from_vertex(2 * e), m.to_vertex(2 * e)});
      crease_weights.push_back(m.edge_sharpness(e));
    }
  for (int v = 0; v < m.n_vertices(); ++v)
    if (m.vertex_sharpness(v) > 0.0f) {
      corners.push_back(v);
      corner_weights.push_back(m.vertex_sharpness(v));
    }
  Osd::Far::TopologyDescriptor d;
  d.numVertices = m.n_vertices();
  d.numFaces = m.n_faces();
  d.numVertsPerFace = sizes.data();
  d.vertIndicesPerFace = indices.data();
  d.numCreases = static_cast<int>(crease_weights.size());
  d.creaseVertexIndexPairs = crease_pairs.data();
  d.creaseWeights = crease_weights.data();
  d.numCorners = static_cast<int>(corners.size());
  d.cornerVertexIndices = corners.data();
  d.cornerWeights = corner_weights.data();
  // The same rules as our subdivider (tests/conformance/opensubdiv_oracle_test.cpp checks the
  // refinement against OpenSubdiv with exactly these options).
  Osd::Sdc::Options o;
  o.SetVtxBoundaryInterpolation(opt.boundary == BoundaryMode::EdgeOnly ? Osd::Sdc::Options::VTX_BOUNDARY_EDGE_ONLY
                                                                       : Osd::Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER);
  o.SetCreasingMethod(opt.crease == CreaseMethod::Chaikin ? Osd::Sdc::Options::CREASE_CHAIKIN
                                                          : Osd::Sdc::Options::CREASE_UNIFORM);
  const auto type = opt.scheme == SchemeType::Loop ? Osd::Sdc::SCHEME_LOOP : Osd::Sdc::SCHEME_CATMARK;
  std::unique_ptr<Osd::Far::TopologyRefiner> r(Factory::Create(d, Factory::Options(type, o)));
  if (!r) throw InvalidInput("limit evaluation: OpenSubdiv rejected the mesh topology");
  return r;
}

std::string number(double x) {
  std::ostringstream os;
  os << x;
  return os.str();
}

}  // namespace

struct LimitEvaluator::Impl {
  std::unique_ptr<Osd::Far::TopologyRefiner> refiner;
  std::unique_ptr<Osd::Bfr::RefinerSurfaceFactory<>> factory;
  // Per face, the bounding box of the control points its limit patch depends on (the corners
  // of the faces sharing a vertex with it), padded: closest_point's lower bounds.
  std::vector<Eigen::AlignedBox3d> boxes;

  // One face's surface, kept while consecutive evaluations stay on it (Gauss-Newton).
  mutable int cached_face = -1;
  mutable Osd::Bfr::Surface<double> surface;
  mutable std::vector<int> cvs;
  mutable std::vector<double> w, wu, wv;

  void evaluate(int face, double u, double v) const {
    if (face != cached_face) {
      if (!factory->InitVertexSurface(face, &surface))
        throw InvalidInput("limit evaluation: face " + std::to_string(face) + " has no limit surface");
      cvs.resize(surface.GetNumControlPoints());
      surface.GetControlPointIndices(cvs.data());
      w.resize(cvs.size());
      wu.resize(cvs.size());
      wv.resize(cvs.size());
      cached_face = face;
    }
    const double uv[2] = {u, v};
    surface.EvaluateStencil(uv, w.data(), wu.data(), wv.data());
  }
  void point(const MatrixX3& X, Vec3& P, Vec3& Du, Vec3& Dv) const {
    P.setZero();
    Du.setZero();
    Dv.setZero();
    for (std::size_t i = 0; i < cvs.size(); ++i) {
      const Vec3 x = X.row(cvs[i]).transpose();
      P += w[i] * x;
      Du += wu[i] * x;
      Dv += wv[i] * x;
    }
  }
};

LimitEvaluator::LimitEvaluator(const SurfaceMesh& mesh, const SubdivisionOptions& opt)
    : mesh_(mesh), opt_(opt), impl_(std::make_unique<Impl>()) {
  impl_->refiner = make_refiner(mesh, opt);
  Osd::Bfr::SurfaceFactory::Options fo;
  fo.SetApproxLevelSmooth(kApproxLevel);
  // Semi-sharp creases and corners are refined until their sharpness has decayed (exact up to
  // sharpness kApproxLevel; OpenSubdiv's default stops at 6).
  fo.SetApproxLevelSharp(kApproxLevel);
  impl_->factory = std::make_unique<Osd::Bfr::RefinerSurfaceFactory<>>(*impl_->refiner, fo);
  // The limit patch of a face is a combination of its one-ring's control points with
  // nonnegative weights (B-spline and box-spline bases; the Gregory patches near extraordinary
  // vertices nearly so), so it lies in their box; the padding covers the "nearly".
  impl_->boxes.resize(static_cast<std::size_t>(mesh.n_faces()));
  for (int f = 0; f < mesh.n_faces(); ++f) {
    Eigen::AlignedBox3d& box = impl_->boxes[static_cast<std::size_t>(f)];
    for (int c : mesh.face_vertices(f))
      for (int g : mesh.vertex_faces(c))
        for (int w : mesh.face_vertices(g)) box.extend(Vec3(mesh.position(w)));
    const Vec3 pad = Vec3::Constant(0.05 * box.diagonal().norm());
    box.extend(Vec3(box.min() - pad));
    box.extend(Vec3(box.max() + pad));
  }
}

LimitEvaluator::~LimitEvaluator() = default;

std::string LimitEvaluator::why_not(const FaceParameter& at) const {
  if (at.face < 0 || at.face >= mesh_.n_faces())
    return "face " + std::to_string(at.face) + " does not exist (faces 0.." + std::to_string(mesh_.n_faces() - 1) + ")";
  const int n = mesh_.face_size(at.face);
  if (!std::isfinite(at.u) || !std::isfinite(at.v)) return "(u, v) is not finite";
  if (opt_.scheme == SchemeType::CatmullClark) {
    if (n != 4) return non_quad_face(at.face);
    for (const auto& [name, x] : {std::pair<const char*, double>{"u", at.u}, {"v", at.v}})
      if (x < 0 || x > 1) return std::string(name) + " = " + number(x) + " is outside the quad's range [0, 1]";
    return {};
  }
  if (n != 3) return "face " + std::to_string(at.face) + " is not a triangle (Loop)";
  if (at.u < 0 || at.v < 0 || at.u + at.v > 1)
    return "(u, v) = (" + number(at.u) + ", " + number(at.v) + ") is outside the triangle's range u, v >= 0, u + v <= 1";
  return {};
}

FaceParameter LimitEvaluator::at_vertex(int v) const {
  static const double quad[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, tri[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  const int corners = opt_.scheme == SchemeType::Loop ? 3 : 4;
  for (int f : mesh_.vertex_faces(v)) {
    const auto vs = mesh_.face_vertices(f);
    if (static_cast<int>(vs.size()) != corners) continue;
    const auto c = static_cast<std::size_t>(std::find(vs.begin(), vs.end(), v) - vs.begin());
    const double* uv = corners == 4 ? quad[c] : tri[c];
    return {f, uv[0], uv[1]};
  }
  return {};
}

LimitStencils LimitEvaluator::stencils(const FaceParameter& at) const {
  if (std::string why = why_not(at); !why.empty()) throw InvalidInput("limit evaluation: " + why);
  impl_->evaluate(at.face, at.u, at.v);
  // A control point may appear once per surface; merge anyway so a stencil never repeats a vertex.
  std::map<int, std::array<double, 3>> merged;
  for (std::size_t i = 0; i < impl_->cvs.size(); ++i) {
    auto& m = merged[impl_->cvs[i]];
    m[0] += impl_->w[i];
    m[1] += impl_->wu[i];
    m[2] += impl_->wv[i];
  }
  LimitStencils s;
  for (const auto& [vertex, m] : merged) {
    if (m[0] != 0) s.position.emplace_back(vertex, m[0]);
    if (m[1] != 0) s.du.emplace_back(vertex, m[1]);
    if (m[2] != 0) s.dv.emplace_back(vertex, m[2]);
  }
  return s;
}

Vec3 LimitEvaluator::apply(const Stencil& s, const MatrixX3& positions) {
  Vec3 p = Vec3::Zero();
  for (const auto& [vertex, w] : s) p += w * positions.row(vertex).transpose();
  return p;
}

Vec3 LimitEvaluator::position(const FaceParameter& at) const { return apply(stencils(at).position, mesh_.positions()); }

namespace {

// The parameter domain's closest point (exact for the square; for the triangle, clamping then
// sliding back along u + v = 1 — enough for a descent that checks its own progress).
void project_to_domain(SchemeType scheme, double& u, double& v) {
  u = std::clamp(u, 0.0, 1.0);
  v = std::clamp(v, 0.0, 1.0);
  if (scheme == SchemeType::Loop && u + v > 1) {
    const double excess = 0.5 * (u + v - 1);
    u = std::clamp(u - excess, 0.0, 1.0);
    v = std::clamp(v - excess, 0.0, 1.0);
    if (u + v > 1) (u > v ? u : v) = 1 - (u > v ? v : u);
  }
}

}  // namespace

std::string LimitEvaluator::non_quad_face(int face) const {
  // Subdivision splits face f into quads numbered from the sum of the sizes of faces 0..f-1
  // (subdivider.h: quad i at corner i), so the point can be named exactly one level finer.
  long first = 0;
  for (int g = 0; g < face; ++g) first += mesh_.face_size(g);
  const int n = mesh_.face_size(face);
  return "face " + std::to_string(face) + " is a " + std::to_string(n) + "-gon (valence " + std::to_string(n) +
         "); Catmull-Clark surface points are given on quads: give the point one level finer, where face " +
         std::to_string(face) + " is the quads " + std::to_string(first) + ".." + std::to_string(first + n - 1) +
         " (quad " + std::to_string(first) + " + i at its corner i, (u, v) = (0, 0) at that corner, (1, 0) at the "
         "middle of the side towards corner i + 1, (0, 1) at the middle of the side towards corner i - 1, (1, 1) at "
         "the face's centroid)";
}

FaceParameter LimitEvaluator::closest_point(const Vec3& p, int hint) const {
  const Impl& I = *impl_;
  // A non-quad Catmull-Clark face has a limit patch too, and the closest point may lie on it:
  // searching the quads only would silently return a farther point.
  if (opt_.scheme == SchemeType::CatmullClark)
    for (int f = 0; f < mesh_.n_faces(); ++f)
      if (mesh_.face_size(f) != 4)
        throw InvalidInput("closest point on the limit surface: " + non_quad_face(f) +
                           " (every level from 1 on is all quads)");
  // Branch and bound over the faces: in order of the distance from p to their boxes (a lower
  // bound of the distance to their patch), until that bound exceeds the best distance found.
  // The hint face (a curve's previous sample) goes first, to find a good bound early.
  const int corners = opt_.scheme == SchemeType::Loop ? 3 : 4;
  std::vector<std::pair<double, int>> order;
  order.reserve(I.boxes.size());
  for (int f = 0; f < mesh_.n_faces(); ++f)
    if (mesh_.face_size(f) == corners)
      order.emplace_back(f == hint ? -1.0 : I.boxes[static_cast<std::size_t>(f)].exteriorDistance(p), f);
  if (order.empty())
    throw InvalidInput(std::string("closest point on the limit surface: the mesh has no ") +
                       (corners == 4 ? "quad" : "triangle") + " face (use a finer level)");
  std::sort(order.begin(), order.end());
  FaceParameter best;
  double best_d2 = std::numeric_limits<double>::infinity();
  Vec3 P, Du, Dv;
  const MatrixX3& X = mesh_.positions();
  for (const auto& [bound, f] : order) {
    if (bound * bound > best_d2) break;
    // Start from the best of a 3 x 3 grid of parameters, then projected Gauss-Newton with
    // step halving (the distance never grows).
    double u = 0, v = 0, d2 = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= 2; ++i)
      for (int j = 0; j <= 2; ++j) {
        double a = i / 2.0, b = j / 2.0;
        if (corners == 3 && a + b > 1) continue;
        I.evaluate(f, a, b);
        I.point(X, P, Du, Dv);
        if (const double e = (P - p).squaredNorm(); e < d2) { d2 = e; u = a; v = b; }
      }
    for (int it = 0; it < 50; ++it) {
      I.evaluate(f, u, v);
      I.point(X, P, Du, Dv);
      const Vec3 r = P - p;
      Eigen::Matrix<double, 3, 2> J;
      J << Du, Dv;
      const Eigen::Matrix2d JtJ = J.transpose() * J;
      const Eigen::Vector2d step = -(JtJ + 1e-14 * JtJ.trace() * Eigen::Matrix2d::Identity()).ldlt().solve(J.transpose() * r);
      if (!step.allFinite()) break;
      double t = 1, nu = u, nv = v, nd2 = d2;
      bool improved = false;
      for (int half = 0; half < 30; ++half, t *= 0.5) {
        nu = u + t * step[0];
        nv = v + t * step[1];
        project_to_domain(opt_.scheme, nu, nv);
        I.evaluate(f, nu, nv);
        I.point(X, P, Du, Dv);
        nd2 = (P - p).squaredNorm();
        if (nd2 <= d2) { improved = true; break; }
      }
      if (!improved) break;
      const double moved = std::hypot(nu - u, nv - v);
      u = nu;
      v = nv;
      d2 = nd2;
      if (moved < 1e-15) break;
    }
    if (d2 < best_d2) {
      best_d2 = d2;
      best = {f, u, v};
    }
  }
  return best;
}

}  // namespace fairshape
