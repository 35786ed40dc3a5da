#include "design/multires_constraints.h"

#include <map>
#include <sstream>

#include "subdivision/limit.h"

namespace fairshape {

LinearConstraints propagate_constraints(const MultiresSurface& h, int l, const std::vector<PointConstraint>& cs) {
  if (l < 0 || l > h.levels())
    throw InvalidInput("edit level " + std::to_string(l) + " outside the hierarchy [0, " + std::to_string(h.levels()) + "]");
  // Incompatible targets on one vertex are an error, a repeated identical one is harmless.
  std::map<std::tuple<int, int, bool>, const PointConstraint*> seen;
  std::vector<const PointConstraint*> unique;
  for (const auto& c : cs) {
    if (c.level < l || c.level > h.levels())
      throw InvalidInput(c.label + ": level " + std::to_string(c.level) + " is " +
                         (c.level < l ? "coarser than the edit level " + std::to_string(l)
                                      : "not in the hierarchy (levels 0.." + std::to_string(h.levels()) + ")"));
    if (c.vertex < 0 || c.vertex >= h.mesh(c.level).n_vertices())
      throw InvalidInput(c.label + ": vertex " + std::to_string(c.vertex) + " does not exist on level " +
                         std::to_string(c.level) + " (" + std::to_string(h.mesh(c.level).n_vertices()) + " vertices)");
    if (!c.offset.allFinite()) throw InvalidInput(c.label + ": target is not finite");
    auto [it, inserted] = seen.try_emplace({c.level, c.vertex, c.on_limit}, &c);
    if (inserted) unique.push_back(&c);
    else if ((it->second->offset - c.offset).norm() > 1e-12 * (1.0 + c.offset.norm())) {
      std::ostringstream os;
      os << "vertex " << c.vertex << " of level " << c.level << " has incompatible targets: " << it->second->label
         << " asks for [" << it->second->offset.transpose() << "], " << c.label << " for [" << c.offset.transpose() << "]";
      throw InvalidInput(os.str());
    }
  }
  // One composed operator per level that has constraints.
  std::map<std::pair<int, bool>, RowSparseMatrix> rows_of;
  for (const auto* c : unique) {
    auto key = std::make_pair(c->level, c->on_limit);
    if (rows_of.count(key)) continue;
    SparseMatrix P = h.prolongation(l, c->level);
    if (c->on_limit) P = SparseMatrix(limit_matrix(h.mesh(c->level), h.options()) * P);
    rows_of.emplace(key, RowSparseMatrix(P));
  }
  LinearConstraints out;
  out.C.resize(static_cast<Eigen::Index>(unique.size()), 3);
  Triplets t;
  for (std::size_t r = 0; r < unique.size(); ++r) {
    const RowSparseMatrix& P = rows_of.at({unique[r]->level, unique[r]->on_limit});
    for (RowSparseMatrix::InnerIterator it(P, unique[r]->vertex); it; ++it)
      t.emplace_back(static_cast<int>(r), static_cast<int>(it.col()), it.value());
    out.C.row(static_cast<Eigen::Index>(r)) = unique[r]->offset.transpose();
  }
  out.A.resize(static_cast<Eigen::Index>(unique.size()), h.mesh(l).n_vertices());
  out.A.setFromTriplets(t.begin(), t.end());
  return out;
}

}  // namespace fairshape
