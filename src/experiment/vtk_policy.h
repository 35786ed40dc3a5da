// `output.vtk`, one schema for every run kind: none | final | all. `all` writes every
// intermediate state the kind has — the solve's iterations every `output.vtk_every` for
// surface edits, every stage of every edit for curves, every design step for sheets; feature
// runs have one state, so `all` is `final` there.
#pragma once

#include "fairshape/core/config.h"

namespace fairshape {

enum class VtkPolicy { None, Final, All };

//! \throw InvalidConfig for another value; the names of earlier releases (every_iteration,
//! stages, true, false) are refused with the name that replaced them.
inline VtkPolicy read_vtk_policy(Config& output, const std::string& all_means) {
  const std::string doc = "VTK output: none, final (the result), or all (" + all_means + ")";
  if (output.has("vtk") && output.node()["vtk"].IsScalar()) {
    const std::string old = output.node()["vtk"].Scalar();
    const char* replacement = old == "every_iteration" || old == "stages" || old == "true" ? "all"
                              : old == "false"                                           ? "none"
                                                                                         : nullptr;
    if (replacement)
      throw InvalidConfig(output.key_path("vtk") + ": '" + old + "' is the old spelling; use " + replacement +
                          " (valid: none, final, all)");
  }
  static const NameTable<VtkPolicy> names{{VtkPolicy::None, "none"}, {VtkPolicy::Final, "final"}, {VtkPolicy::All, "all"}};
  return output.get_enum("vtk", VtkPolicy::Final, names, doc);
}

}  // namespace fairshape
