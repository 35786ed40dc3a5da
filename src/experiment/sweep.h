// The points of an experiment: `sweep:` is a Cartesian product over its keys, where the
// lists under `zip:` count as one axis. Points are made on demand from their flat index, so
// a shard of a large sweep builds only its own.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace fairshape {

struct RunPoint {
  std::size_t index = 0;                                    // position in the full sweep
  std::vector<std::pair<std::string, std::string>> params;  // swept key -> value, for the tables
  YAML::Node config;                                        // resolved, without `sweep`
  //! 16 hex digits of the SHA-256 of the point's whole resolved config (outputs, name and
  //! description included: anything that can change a result file), then `-k` for the k-th
  //! (k >= 2) occurrence of a point the sweep lists more than once (a repeat).
  std::string run_id;
};

//! The largest sweep fairshape expands (points, after the product).
constexpr std::size_t kMaxSweepPoints = 10'000'000;

class SweepSpace {
 public:
  //! \throw InvalidConfig for a non-list value, an empty list, zip lists of unequal length,
  //! or more than kMaxSweepPoints points (counted without overflow).
  explicit SweepSpace(const YAML::Node& root);
  std::size_t size() const { return size_; }
  //! Swept keys in table column order (zip keys in their order, then the others).
  std::vector<std::string> keys() const;
  RunPoint point(std::size_t index) const;
  //! point(index).run_id and .params without building the point's config.
  std::string run_id(std::size_t index) const;
  std::vector<std::pair<std::string, std::string>> params(std::size_t index) const;

 private:
  struct Axis {
    std::vector<std::string> keys;
    std::vector<std::vector<YAML::Node>> values;  // values[k][i]: key k at position i
    std::vector<std::vector<std::string>> text;   // text[k][i]: the value as a table cell
    std::vector<std::vector<std::string>> flow;   // flow[k][i]: the value as run_id_of's text holds it
    std::vector<std::size_t> occurrence;          // earlier positions with the same values
    std::vector<std::size_t> multiplicity;        // positions with the same values
    std::size_t size() const { return values.front().size(); }
  };
  std::vector<std::size_t> positions(std::size_t index) const;
  YAML::Node config_at(const std::vector<std::size_t>& pos) const;
  std::string hash_text(const std::vector<std::size_t>& pos) const;
  std::string run_id_at(const std::vector<std::size_t>& pos, std::string hash) const;  // `-k` added for repeats
  void prepare_hash_text();

  YAML::Node base_;
  std::vector<Axis> axes_;
  std::size_t size_ = 1;
  // run_id_of's text of every point is the base's text with each swept value's text put in:
  // emitted once, not once per point (a sweep of 10^6 points spent most of its validation
  // emitting YAML). Empty when that does not reproduce run_id_of exactly (checked on every
  // axis value): then each point's config is emitted.
  std::vector<std::string> hash_pieces_;  // text between the swept values, in emission order
  std::vector<std::pair<std::size_t, std::size_t>> hash_slots_;  // (axis, key) of each value put in
};

//! Every point (small sweeps and tests; the harness iterates a SweepSpace).
std::vector<RunPoint> expand_sweep(const YAML::Node& root);
std::vector<std::string> swept_keys(const YAML::Node& root);
//! The hash part of a run_id.
std::string run_id_of(const YAML::Node& run_config);

}  // namespace fairshape
