// The options a run actually used: every value its config reads returned, the defaults of the
// keys it left out included. run.json records them (experiment/run_metadata.h) so two runs of
// the same file under different defaults (a default changed between versions) can be told apart.
//
// Recording is switched on per thread for the span of one parse (a RAII scope) instead of being
// passed through every reader: the kinds, the registries' factories and the blocks they build
// from sub-nodes all read through Config, and none of them needs to know that a caller listens.
#pragma once

#include <map>
#include <string>

#include <yaml-cpp/yaml.h>

namespace fairshape {

//! Dotted key path ("solver.multigrid.stiff_stars", "energy[0].type") → the value used.
using EffectiveOptions = std::map<std::string, YAML::Node>;

//! While alive, every Config read on this thread (outside `fairshape list`'s documenting reads)
//! records its key path and the value it returned into `sink`. Scopes nest: the innermost records.
class RecordEffectiveOptions {
 public:
  explicit RecordEffectiveOptions(EffectiveOptions& sink);
  ~RecordEffectiveOptions();
  RecordEffectiveOptions(const RecordEffectiveOptions&) = delete;
  RecordEffectiveOptions& operator=(const RecordEffectiveOptions&) = delete;

  //! The sink of the innermost live scope on this thread, or nullptr.
  static EffectiveOptions* current();

 private:
  EffectiveOptions* previous_;
};

}  // namespace fairshape
