// The config factories of the registered constraint types (see register_constraints).
#pragma once

#include <memory>
#include <string>

#include "fairshape/constraint/constraint.h"
#include "fairshape/constraint/vertex_selection.h"
#include "fairshape/core/config.h"

namespace fairshape {

//! The config path that names a constraint in error messages ("constraints[2]").
std::string constraint_label(const Config& cfg);
//! The `level` key of a selection-based constraint (-1: the finest).
int level_from_config(Config& cfg);

//! `fixed` (offset zero) and `position` without a config: the selected vertices of `level`
//! (-1: the finest) move by `offset`; `label` names the constraint in error messages.
std::unique_ptr<Constraint> prescribed_offset(VertexSelection selection, const Vec3& offset, int level = -1,
                                              bool on_limit = false, std::string label = "constraint");

std::unique_ptr<Constraint> make_fixed(Config& cfg);
std::unique_ptr<Constraint> make_position(Config& cfg);
std::unique_ptr<Constraint> make_normal(Config& cfg);
//! The `rows` names of a normal constraint (constraint.h NormalRows).
const NameTable<NormalRows>& normal_rows_names();
std::unique_ptr<Constraint> make_rigid(Config& cfg);
std::unique_ptr<Constraint> make_curve(Config& cfg);

}  // namespace fairshape
