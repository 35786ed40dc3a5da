// The `fixed` and `position` constraints, and the bookkeeping that catches conflicts.
#include <sstream>

#include "constraint/constraint.h"
#include "constraint/vertex_selection.h"

namespace fairshape {

void PrescribedValues::set(int vertex, const Vec3& value, const std::string& who) {
  auto [it, inserted] = values_.try_emplace(vertex, value);
  if (inserted) {
    owner_[vertex] = who;
    return;
  }
  if ((it->second - value).norm() <= 1e-12 * (1.0 + value.norm())) return;  // same target twice
  std::ostringstream os;
  os << "vertex " << vertex << " has incompatible targets: " << owner_[vertex] << " asks for displacement ["
     << it->second.transpose() << "], " << who << " for [" << value.transpose() << "]";
  throw InvalidInput(os.str());
}

namespace {

class PositionConstraint : public Constraint {
 public:
  PositionConstraint(VertexSelection sel, Vec3 offset, std::string who)
      : selection_(std::move(sel)), offset_(offset), who_(std::move(who)) {}
  void prescribe(const SurfaceMesh& rest, PrescribedValues& out) const override {
    for (int v : selection_.resolve(rest, who_)) out.set(v, offset_, who_);
  }

 private:
  VertexSelection selection_;
  Vec3 offset_;
  std::string who_;
};

std::string label(const Config& cfg) { return cfg.path().empty() ? "constraint" : cfg.path(); }

}  // namespace

std::unique_ptr<Constraint> make_fixed(Config& cfg) {
  return std::make_unique<PositionConstraint>(VertexSelection::from_config(cfg), Vec3::Zero(), label(cfg));
}

std::unique_ptr<Constraint> make_position(Config& cfg) {
  const auto off = cfg.get<std::vector<double>>("offset", {0, 0, 0}, "displacement [dx, dy, dz] of the handle");
  if (off.size() != 3) throw InvalidConfig(cfg.key_path("offset") + ": expected 3 numbers");
  for (double d : off)
    if (!std::isfinite(d)) throw InvalidConfig(cfg.key_path("offset") + ": not finite");
  return std::make_unique<PositionConstraint>(VertexSelection::from_config(cfg), Vec3(off[0], off[1], off[2]),
                                              label(cfg));
}

void register_constraints(ConstraintRegistry& r) {
  for (Backend b : {Backend::Reference, Backend::Optimized}) {
    r.add("fixed", b, "selected vertices keep their rest position (u = 0)", make_fixed);
    r.add("position", b, "selected vertices move by a given offset (u = offset)", make_position);
  }
}

}  // namespace fairshape
