#include "fairshape/core/summary.h"

#include "fairshape/core/error.h"

namespace fairshape {

const std::vector<std::string>& termination_names() {
  static const std::vector<std::string> names{"converged",         "energy_stalled", "schedule_completed",
                                              "max_iterations",    "constraints_unmet", "ill_conditioned",   "numerical_failure",
                                              "not_a_minimum",     "folded",            "stalled",           "infeasible",
                                              "invalid_input",     "output_failed",     "crashed",
                                              "out_of_memory",     "edit_undone"};
  return names;
}

std::string_view to_string(Termination t) { return termination_names().at(static_cast<std::size_t>(t)); }

Termination termination_from_string(std::string_view name) {
  const auto& names = termination_names();
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == name) return static_cast<Termination>(i);
  std::string valid;
  for (const auto& n : names) valid += (valid.empty() ? "" : ", ") + n;
  throw InvalidInput("unknown termination '" + std::string(name) + "' (valid: " + valid + ")");
}

bool is_success(Termination t) {
  return t == Termination::Converged || t == Termination::EnergyStalled || t == Termination::ScheduleCompleted;
}

}  // namespace fairshape
