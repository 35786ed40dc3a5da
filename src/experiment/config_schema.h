// The keys of fairshape's experiment configs as data, read from the same Config reads that
// parse a run (core/config.h: "the reads are the schema"): `fairshape list --keys` prints them,
// `fairshape schema` writes them as a JSON Schema for editors to complete and check configs.
#pragma once

#include <string>
#include <vector>

#include "fairshape/core/config.h"

namespace fairshape {

struct KindKeys {
  std::string kind;    // "surface_edit"
  std::string marker;  // what makes a config this kind's
  std::vector<OptionDoc> keys;  // list items as `key[].item`, each key once
};

//! Every run kind's keys, the config loader's (defaults, smoke, sweep) among them.
std::vector<KindKeys> experiment_keys();

//! One JSON Schema (draft-07) for every kind: any of the kinds' schemas, each key with its
//! default and doc; the component `type`s (energies, constraints, solvers) as enums; unknown
//! keys refused in the blocks whose keys are all known.
//! Returned as JSON text (indented).
std::string experiment_schema(const std::vector<KindKeys>& kinds);

}  // namespace fairshape
