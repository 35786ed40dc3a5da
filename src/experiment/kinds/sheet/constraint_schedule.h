// When a constraint of a sheet config acts (§5's session): from `step`, up to `until`, its
// target dragged by `moves`. Shared by the sheets' constraints and the variational curves'.
#pragma once

#include <vector>

#include "fairshape/core/config.h"
#include "fairshape/experiment/kinds/sheet/sheet_run.h"

namespace fairshape {

//! `step` (active from) and `until` (removed from; −1: never). \throw InvalidConfig naming
//! `until` when it does not come after `step`.
void read_schedule(Config& c, int& step, int& until);

//! `moves: [{step, by: [x, y, z]}]` (they add up). \throw InvalidConfig naming a move's step
//! that does not come after the constraint's `step`.
std::vector<PointMove> read_moves(Config& c, int step);

}  // namespace fairshape
