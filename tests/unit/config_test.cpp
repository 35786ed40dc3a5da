#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include "fairshape/core/config.h"
#include "fairshape/core/summary.h"
#include "fairshape/experiment/components.h"
#include "fairshape/experiment/config_loader.h"
#include "fairshape/experiment/config_schema.h"
#include "fairshape/experiment/kinds/surface_edit/surface_edit_spec.h"
#include "fairshape/experiment/sweep.h"
#include "test_support.h"

using namespace fairshape;
using Catch::Matchers::Contains;

namespace {
YAML::Node smoke_config() { return load_experiment_config(test::source_path("configs/smoke/cow_nose_pull.yaml"), {}); }
std::vector<std::string> dirs() { return input_search_dirs(test::source_path("configs/smoke/cow_nose_pull.yaml")); }
}  // namespace

TEST_CASE("Config: unknown keys, wrong types and ranges are errors naming the key", "[config]") {
  Config c(YAML::Load("{tolerance: 1e-8, tolerence: 3, omega: abc, n: 7}"), "solver");
  CHECK(c.get<double>("tolerance", 1.0, "doc") == 1e-8);
  CHECK_THROWS_WITH(c.get<double>("omega", 1.0, "doc"), Contains("solver.omega: expected") && Contains("abc"));
  CHECK_THROWS_WITH(c.get_int("n", 1, 0, 5, "doc"), Contains("solver.n: 7 is out of range [0, 5]"));
  CHECK_THROWS_WITH(c.check_no_unknown_keys(), Contains("solver.tolerence: unknown key") && Contains("tolerance"));
  Config choice(YAML::Load("{mode: fast}"), "x");
  CHECK_THROWS_WITH(choice.get_choice("mode", "a", {"a", "b"}, "doc"), Contains("unknown value 'fast' (valid: a, b)"));
}

TEST_CASE("registry lookups list what exists", "[config]") {
  const Components& c = components();
  Config empty;
  CHECK_THROWS_WITH(c.solvers.create("sor2", Backend::Optimized, empty),
                    Contains("unknown solver 'sor2'") && Contains("gauss_seidel"));
  CHECK(c.solvers.has("cholesky", Backend::Reference));
  CHECK(c.solvers.has("cholesky", Backend::Optimized));
}

TEST_CASE("defaults are merged under the file, --set overrides, sweep keys stay dotted", "[config]") {
  const YAML::Node root = smoke_config();
  CHECK(root["output"]["vtk"].as<std::string>() == "final");  // from base/output.yaml
  CHECK(root["name"].as<std::string>() == "smoke_cow_nose_pull");
  const YAML::Node over = load_experiment_config(
      test::source_path("configs/smoke/cow_nose_pull.yaml"),
      {"solver.tolerance=1e-10", "sweep.input.mesh=[data/cow.off, data/knot.off]", "solver.sor.omega=1.2"});
  CHECK(over["solver"]["tolerance"].as<double>() == 1e-10);
  CHECK(over["solver"]["sor"]["omega"].as<double>() == 1.2);
  CHECK(over["sweep"]["input.mesh"].size() == 2);
  CHECK_THROWS_WITH(load_experiment_config(test::source_path("configs/smoke/cow_nose_pull.yaml"), {"novalue"}),
                    Contains("expected key.path=value"));
}

TEST_CASE("sweep expansion: Cartesian product, zip axes, stable run ids", "[config]") {
  YAML::Node root = smoke_config();
  root["sweep"] = YAML::Load(
      "{solver.type: [cholesky, sor], implementation: [reference, optimized, reference],"
      " zip: {seed: [1, 2], solver.tolerance: [1.0e-6, 1.0e-9]}}");
  const auto runs = expand_sweep(root);
  REQUIRE(runs.size() == 2 * 3 * 2);
  CHECK(swept_keys(root) == std::vector<std::string>{"seed", "solver.tolerance", "solver.type", "implementation"});
  // zipped keys move together
  for (const auto& r : runs) CHECK((r.config["seed"].as<int>() == 1) == (r.config["solver"]["tolerance"].as<double>() == 1e-6));
  // identical points (implementation listed twice) are repeats: the same hash, a repeat suffix
  CHECK(runs[2].run_id == runs[0].run_id + "-2");
  CHECK(runs[0].run_id != runs[1].run_id);
  CHECK(expand_sweep(root)[5].run_id == runs[5].run_id);
  std::set<std::string> ids;
  for (const auto& r : runs) ids.insert(r.run_id);
  CHECK(ids.size() == runs.size());  // no two points share an id, repeats included
  // the lazy space makes the same points as the full expansion
  const SweepSpace space(root);
  REQUIRE(space.size() == runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i) CHECK(space.point(i).run_id == runs[i].run_id);

  // keys that change only outputs or labels still change the id (they change result files)
  YAML::Node labelled = smoke_config();
  labelled["sweep"] = YAML::Load("{description: [a, b], output.vtk: [none, final]}");
  std::set<std::string> labelled_ids;
  for (const auto& r : expand_sweep(labelled)) labelled_ids.insert(r.run_id);
  CHECK(labelled_ids.size() == 4);

  // a product beyond the limit is refused without overflowing, however many axes
  YAML::Node huge = smoke_config();
  for (int a = 0; a < 64; ++a) {
    std::string key = "k";  // (not "k" + to_string: GCC 12's -Wrestrict false positive)
    key += std::to_string(a);
    huge["sweep"][key] = YAML::Load("[0, 1]");
  }
  CHECK_THROWS_WITH(SweepSpace(huge), Contains("the limit"));

  root["sweep"] = YAML::Load("{zip: {seed: [1, 2], solver.tolerance: [1.0e-6]}}");
  CHECK_THROWS_WITH(expand_sweep(root), Contains("equally long"));
  root["sweep"] = YAML::Load("{seed: []}");
  CHECK_THROWS_WITH(expand_sweep(root), Contains("non-empty list"));
}

TEST_CASE("run validation catches bad components, keys and values before running", "[config]") {
  auto spec_with = [](const std::string& key, const std::string& value) {
    YAML::Node root = smoke_config();
    set_by_path(root, key, YAML::Load(value));
    return SurfaceEditSpec::from_config(root, components(), dirs());
  };
  CHECK_NOTHROW(spec_with("solver.type", "sor"));
  CHECK_THROWS_WITH(spec_with("solver.type", "multigrd"), Contains("solver.type: unknown value 'multigrd'"));
  CHECK_THROWS_WITH(spec_with("solver.sor", "{omega: 2.0}"), Contains("solver.sor.omega") && Contains("(0, 2)"));
  CHECK_THROWS_WITH(spec_with("solver.tolerance", "-1"), Contains("solver.tolerance"));
  CHECK_THROWS_WITH(spec_with("input.mesh", "nowhere.off"), Contains("input.mesh") && Contains("not found"));
  CHECK_THROWS_WITH(spec_with("implementation", "fast"), Contains("valid: reference, optimized"));
  CHECK_THROWS_WITH(spec_with("energy", "[{type: bending}]"), Contains("unknown energy 'bending'"));
  CHECK_THROWS_WITH(spec_with("energy", "[{type: membrane, wieght: 2}]"), Contains("energy[0].wieght: unknown key"));
  CHECK_THROWS_WITH(spec_with("constraints", "[{type: fixed, region: {axis: w}}]"), Contains("valid: x, y, z"));
  CHECK_THROWS_WITH(spec_with("colour", "red"), Contains("colour: unknown key"));
  // input.crease_angle: degrees in [0, 179], only where there is a subdivision surface.
  CHECK_THROWS_WITH(spec_with("input.crease_angle", "200"), Contains("input.crease_angle: 200 is out of range [0, 179]"));
  CHECK_THROWS_WITH(spec_with("input.crease_angle", "-5"), Contains("input.crease_angle") && Contains("[0, 179]"));
  CHECK_THROWS_WITH(spec_with("input.crease_angle", "steep"), Contains("input.crease_angle"));
  const SurfaceEditSpec on_mesh = spec_with("input.crease_angle", "40");  // representation: mesh
  CHECK(on_mesh.crease_angle == 40);
  CHECK(std::find(on_mesh.unused_keys.begin(), on_mesh.unused_keys.end(), "input.crease_angle") != on_mesh.unused_keys.end());
}

TEST_CASE("each QP constraint mode's options are its solver's, valid whichever mode is chosen, unused ones recorded",
          "[config]") {
  auto spec_with = [](std::vector<std::pair<std::string, std::string>> sets) {
    YAML::Node root = smoke_config();
    for (const auto& [key, value] : sets) set_by_path(root, key, YAML::Load(value));
    return SurfaceEditSpec::from_config(root, components(), dirs());
  };
  const SurfaceEditSpec penalty = spec_with({{"problem.constraint_mode", "qr_penalty"}, {"problem.qr_penalty", "{mu: 1000, solve: orthogonal}"}});
  CHECK(penalty.qp_config().node()["mu"].as<double>() == 1000);
  CHECK(penalty.qp_config().path() == "problem.qr_penalty");
  CHECK(std::find(penalty.unused_keys.begin(), penalty.unused_keys.end(), "problem.qr_penalty.mu") == penalty.unused_keys.end());
  // Under another mode the block is still validated, and recorded as not used.
  const SurfaceEditSpec paper = spec_with({{"problem.qr_penalty", "{mu: 1000}"}});
  CHECK(std::find(paper.unused_keys.begin(), paper.unused_keys.end(), "problem.qr_penalty.mu") != paper.unused_keys.end());
  CHECK_THROWS_WITH(spec_with({{"problem.qr_penalty", "{mu: -1}"}}), Contains("problem.qr_penalty.mu"));
  CHECK_THROWS_WITH(spec_with({{"problem.qr_penalty", "{solve: exact}"}}), Contains("valid: semi_normal, orthogonal"));
  CHECK_THROWS_WITH(spec_with({{"problem.kkt", "{mu: 3}"}}), Contains("problem.kkt.mu: unknown key"));
}

TEST_CASE("outcome vocabulary: names round-trip, success is what was asked", "[config][summary]") {
  for (const auto& name : termination_names()) CHECK(to_string(termination_from_string(name)) == name);
  CHECK_THROWS_WITH(termination_from_string("done"), Contains("valid: converged"));
  CHECK(is_success(Termination::Converged));
  CHECK(is_success(Termination::EnergyStalled));
  CHECK(is_success(Termination::ScheduleCompleted));
  CHECK_FALSE(is_success(Termination::MaxIterations));
  CHECK_FALSE(is_success(Termination::Crashed));
  CHECK_FALSE(is_success(Termination::NumericalFailure));
}

TEST_CASE("a --set on a swept key replaces its axis, one overlapping it is refused", "[config]") {
  const std::string dir = std::filesystem::temp_directory_path() / "fairshape_set_sweep_test";
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/c.yaml";
  std::ofstream(path) << "name: t\nsweep:\n  seed: [1, 2]\n  zip: {energy: [[a], [b]], threads: [1, 2]}\n";
  std::vector<std::string> notes;
  YAML::Node root = load_experiment_config(path, {"seed=5", "threads=3"}, &notes);
  CHECK(root["seed"].as<int>() == 5);
  CHECK_FALSE(root["sweep"]["seed"]);
  CHECK(root["sweep"]["zip"]["energy"]);
  CHECK_FALSE(root["sweep"]["zip"]["threads"]);
  CHECK(notes.size() == 2);
  CHECK_THROWS_WITH(load_experiment_config(path, {"energy.0.type=x"}), Contains("overlaps the swept key"));
}

TEST_CASE("every unknown key of a run's config in one error, with the likely misspelling", "[config]") {
  YAML::Node c = smoke_config();
  c["solvr"] = YAML::Load("{type: cholesky}");
  c["input"]["levls"] = 2;
  c["energy"][0]["wieght"] = 1.0;
  try {
    (void)SurfaceEditSpec::from_config(c, components(), dirs());
    FAIL("three unknown keys passed");
  } catch (const InvalidConfig& e) {
    const std::string m = e.what();
    CHECK_THAT(m, Contains("3 unknown keys"));
    CHECK_THAT(m, !Contains("also"));  // each named once
    CHECK_THAT(m, Contains("solvr: unknown key (did you mean solver?"));
    CHECK_THAT(m, Contains("input.levls: unknown key (did you mean input.levels?"));
    CHECK_THAT(m, Contains("energy[0].wieght: unknown key (did you mean energy[0].weight?"));
    // the keys the loader and the sweep read are valid at the top level too
    CHECK_THAT(m, Contains("defaults") && Contains("smoke") && Contains("sweep"));
  }
  // A misspelt required block is named as the misspelling, before what follows from it.
  YAML::Node d = smoke_config();
  d["energies"] = d["energy"];
  d.remove("energy");
  CHECK_THROWS_WITH(SurfaceEditSpec::from_config(d, components(), dirs()),
                    Contains("energies: unknown key (did you mean energy?"));
  // Far from every key: no guess.
  YAML::Node f = smoke_config();
  f["zzz"] = 1;
  CHECK_THROWS_WITH(SurfaceEditSpec::from_config(f, components(), dirs()),
                    Contains("zzz: unknown key (valid keys here:"));
}

TEST_CASE("every run kind documents every key it reads, and the schema holds them", "[config]") {
  const std::vector<KindKeys> kinds = experiment_keys();
  REQUIRE(kinds.size() == 4);
  std::set<std::string> all;
  for (const KindKeys& k : kinds) {
    INFO(k.kind);
    CHECK(k.keys.size() > 10);
    for (const OptionDoc& d : k.keys) all.insert(d.key);
  }
  // A sample of each kind's keys, top level and nested, list items included.
  for (const char* key : {"name", "input.mesh", "input.levels", "solver.type", "problem.constraint_mode", "energy[].type",
                          "constraints[].type", "output.vtk", "sheets", "input.curve", "edits", "features", "sweep",
                          "defaults", "smoke", "repeat"})
    CHECK(all.count(key) == 1);
  const std::string schema = experiment_schema(kinds);
  CHECK_THAT(schema, Contains("\"$schema\"") && Contains("\"additionalProperties\": false") &&
                         Contains("\"constraint_mode\"") && Contains("\"cholesky\""));
}

TEST_CASE("a sweep's run ids are run_id_of each point's whole config, whatever its values", "[config]") {
  // Values whose text needs quoting or nesting in a flow map, keys new to the base and keys in
  // a list: the ids come from the base's text with the values put in, so check them against
  // the emission of every point's config.
  YAML::Node root = smoke_config();
  root["sweep"] = YAML::Load(
      "{description: ['a, b', 'c: d', '{x}', '', '#1', \"it's\", 'multi\nline'],"
      " constraints.1.offset: [[0.1, 0, 0], [0, 0.2, 0]],"
      " zip: {new_block.new_key: [1, {m: [1, 2]}], energy: [[{type: membrane}], [{type: umbrella_thin_plate, weight: 2}]]}}");
  const SweepSpace space(root);
  REQUIRE(space.size() == 7 * 2 * 2);
  for (std::size_t i = 0; i < space.size(); ++i) {
    const RunPoint p = space.point(i);
    CHECK(p.run_id == run_id_of(p.config));
    CHECK(space.run_id(i) == p.run_id);
    CHECK(space.params(i) == p.params);
  }
}
