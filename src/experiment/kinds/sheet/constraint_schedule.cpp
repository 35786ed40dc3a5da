#include "fairshape/experiment/kinds/sheet/constraint_schedule.h"

#include "fairshape/experiment/run_basics.h"

namespace fairshape {

void read_schedule(Config& c, int& step, int& until) {
  step = c.get_int("step", 0, 0, 1000, "design step from which it is active");
  until = c.get_int("until", -1, -1, 1001, "design step from which it is removed again (-1: never)");
  if (until >= 0 && until <= step)
    throw InvalidConfig(c.key_path("until") + ": " + std::to_string(until) + " must come after step " + std::to_string(step));
}

std::vector<PointMove> read_moves(Config& c, int step) {
  std::vector<PointMove> moves;
  for (Config m : c.child_list("moves", "the target dragged over the steps: [{step, by: [x, y, z]}] (moves add up)")) {
    PointMove mv;
    mv.step = m.get_int("step", 1, 0, 1000, "design step from which the move applies");
    if (!m.has("by") && !m.documenting()) throw InvalidConfig(m.path() + ": a move needs `by` (the displacement of the target)");
    mv.by = read_vec3(m, "by", mv.by, "displacement of the target");
    m.check_no_unknown_keys();
    if (mv.step <= step)
      throw InvalidConfig(m.key_path("step") + ": " + std::to_string(mv.step) + " must come after the constraint's step " +
                          std::to_string(step) + " (its target at that step is `target`/`by`)");
    moves.push_back(mv);
  }
  return moves;
}

}  // namespace fairshape
