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

}  // namespace fairshape
