// What every experiment config shares, whatever it runs (surface edits, curves, sheets,
// features): the top-level keys, the keys a run sets but does not use, and how input files
// and small values are read.
#pragma once

#include <string>
#include <vector>

#include "fairshape/core/backend.h"
#include "fairshape/core/config.h"
#include "fairshape/core/types.h"

namespace fairshape {

//! The keys every experiment config starts with, whatever it runs (surfaces, curves, sheets).
struct RunBasics {
  std::string name;
  int seed = 0, threads = 0;  // `repeat` is validated here and run by the harness (experiment/repeats.h)
  Backend implementation = Backend::Optimized;
  //! Keys the config sets that this run does not use (solver.* under constraint_mode kkt, the
  //! options of a solver not chosen, relaxation_omega without sor, ...), for runs.csv's
  //! unused_keys column: recorded as not applicable, never as used.
  std::vector<std::string> unused_keys;
  //! Records `key` of `block` as unused when the config sets it and `used` is false.
  void note_unused(const Config& block, const std::string& key, bool used);
  //! Records every key the config sets in `block`.
  void note_unused(const Config& block);
  //! The unused_keys cell: the keys, space-separated.
  std::string unused_keys_cell() const;
};
//! Reads name, description, seed, threads, repeat and implementation from the config's root.
RunBasics read_run_basics(Config& root);

//! A `[x, y, z]` key. \throw InvalidConfig naming the key unless three finite numbers.
Vec3 read_vec3(Config& c, const std::string& key, const Vec3& fallback, const std::string& doc);

//! The current directory, then `config_path`'s folder and its parents (so configs can name
//! `data/cow.off` from anywhere inside the repository).
std::vector<std::string> input_search_dirs(const std::string& config_path);
//! `path` as found in `dirs`. \throw InvalidConfig naming `key` when it is nowhere.
std::string resolve_input(const std::string& path, const std::vector<std::string>& dirs, const std::string& key);
//! The required input file `key` of `block`, resolved as above ("" while the block is documenting).
std::string read_input_path(Config& block, const std::string& key, const std::string& doc, const std::vector<std::string>& dirs);
//! Reads the mesh at `path` once per process (validation of every sweep point asks again), so
//! a malformed or unreadable input is an invalid config — exit 2, nothing run — rather than a
//! failed run. \throw InvalidConfig naming `key` and the reader's message.
void require_readable_mesh(const std::string& path, const std::string& key);

}  // namespace fairshape
