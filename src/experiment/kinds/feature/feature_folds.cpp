#include "fairshape/experiment/kinds/feature/feature_folds.h"

#include <string>

#include "fairshape/core/summary.h"

namespace fairshape {

void report_folds(const FoldReport& folds, MetricRow& row) {
  row["flipped_faces"] = std::to_string(folds.flipped.size());
  if (folds.flipped.empty()) return;
  const std::string miss = row["termination"] == to_string(Termination::ConstraintsUnmet) ? "; " + row["message"] : "";
  row["termination"] = std::string(to_string(Termination::Folded));
  row["message"] = "folded: " + folds.describe() + miss;
}

void mark_flipped(SurfaceMesh& fine, const FoldReport& folds) {
  Eigen::MatrixXd flipped = Eigen::MatrixXd::Zero(fine.n_vertices(), 1);
  for (int f : folds.flipped)
    for (int v : fine.face_vertices(f)) flipped(v, 0) = 1.0;
  fine.vertex_data["flipped"] = flipped;
}

}  // namespace fairshape
