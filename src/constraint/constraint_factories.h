// The config factories of the registered constraint types (see register_constraints).
#pragma once

#include <memory>
#include <string>

#include "constraint/constraint.h"
#include "core/config.h"

namespace fairshape {

//! The config path that names a constraint in error messages ("constraints[2]").
std::string constraint_label(const Config& cfg);
//! The `level` key of a selection-based constraint (-1: the finest).
int level_from_config(Config& cfg);

std::unique_ptr<Constraint> make_fixed(Config& cfg);
std::unique_ptr<Constraint> make_position(Config& cfg);
std::unique_ptr<Constraint> make_normal(Config& cfg);
std::unique_ptr<Constraint> make_rigid(Config& cfg);
std::unique_ptr<Constraint> make_curve(Config& cfg);

}  // namespace fairshape
