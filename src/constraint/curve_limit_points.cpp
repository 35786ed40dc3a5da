#include "fairshape/constraint/curve_limit_points.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fairshape/constraint/surface_points.h"

namespace fairshape {
namespace {

class Placer {
 public:
  Placer(const LimitEvaluator& e, const MatrixX3& control, bool closed, double max_distance, const std::string& who)
      : e_(e), control_(control), closed_(closed), max_distance_(max_distance), who_(who) {}

  Vec3 polygon(double t) const {
    const Eigen::Index n = control_.rows();
    const Eigen::Index s = std::min<Eigen::Index>(static_cast<Eigen::Index>(t), closed_ ? n - 1 : n - 2);
    const double f = t - static_cast<double>(s);
    return (1 - f) * control_.row(s).transpose() + f * control_.row((s + 1) % n).transpose();
  }

  // Appends the sample at parameter t, after the samples needed between the last one and it.
  void add(double t, int depth = 0) {
    const Vec3 q = polygon(t);
    const FaceParameter p = e_.closest_point(q, out_.points.empty() ? -1 : out_.points.back().at.face);
    const double d = (e_.position(p) - q).norm();
    if (d > max_distance_) {
      std::ostringstream os;
      os << who_ << ": the curve leaves the limit surface near [" << q.transpose() << "] (distance " << d
         << " > max_distance " << max_distance_ << ")";
      throw InvalidInput(os.str());
    }
    if (!out_.points.empty() && !adjacent(out_.points.back().at.face, p.face)) {
      if (depth >= 12) gap(t);
      const double mid = 0.5 * (out_.source.back() + t);
      add(mid, depth + 1);
      add(t, depth + 1);
      return;
    }
    if (!out_.points.empty() && out_.points.back().at.face == p.face && out_.points.back().at.u == p.u &&
        out_.points.back().at.v == p.v)
      return;  // the same surface point again: one row is enough
    out_.points.push_back(make_surface_point(e_, p));
    out_.source.push_back(t);
    out_.on_curve.push_back(q);
  }

  // A closed curve's last point and first must satisfy (AP) too: bisect towards the end.
  void close() {
    if (!closed_ || out_.points.size() < 2) return;
    const double end = static_cast<double>(control_.rows());
    for (int i = 0; i < 12 && !adjacent(out_.points.back().at.face, out_.points.front().at.face); ++i)
      add(0.5 * (out_.source.back() + end));
    if (!adjacent(out_.points.back().at.face, out_.points.front().at.face)) gap(0.0);
  }

  LimitCurve take() { return std::move(out_); }

 private:
  bool adjacent(int f, int g) const {
    if (f == g) return true;
    const auto a = e_.mesh().face_vertices(f), b = e_.mesh().face_vertices(g);
    for (int v : a)
      if (std::find(b.begin(), b.end(), v) != b.end()) return true;
    return false;
  }
  [[noreturn]] void gap(double t) const {
    std::ostringstream os;
    os << who_ << ": consecutive curve points near [" << polygon(t).transpose()
       << "] lie in faces that share no vertex, however finely the curve is sampled (the approximation "
          "property fails: does the curve jump across a gap of the surface?)";
    throw InvalidInput(os.str());
  }

  const LimitEvaluator& e_;
  const MatrixX3& control_;
  bool closed_;
  double max_distance_;
  const std::string& who_;
  LimitCurve out_;
};

}  // namespace

LimitCurve place_on_limit(const LimitEvaluator& evaluator, const MatrixX3& control, bool closed, double step,
                          double max_distance, const std::string& who) {
  if (control.rows() < 2) throw InvalidInput(who + ": a curve needs at least 2 points");
  if (!(step > 0)) throw InvalidInput(who + ": the sampling step must be positive");
  Placer placer(evaluator, control, closed, max_distance, who);
  const Eigen::Index n = control.rows(), segments = closed ? n : n - 1;
  for (Eigen::Index s = 0; s < segments; ++s) {
    const double length = (control.row((s + 1) % n) - control.row(s)).norm();
    const int k = std::max(1, static_cast<int>(std::ceil(length / step)));
    for (int j = 0; j < k; ++j) placer.add(static_cast<double>(s) + static_cast<double>(j) / k);
  }
  if (!closed) placer.add(static_cast<double>(n - 1));
  placer.close();
  return placer.take();
}

}  // namespace fairshape
