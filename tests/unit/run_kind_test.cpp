// The run-kind interface: every shipped config belongs to exactly one kind and validates, and
// a kind's outputs say what the run did (the surface edit's _levels.vtm is re-analysed).
#include <catch2/catch.hpp>

#include <cctype>
#include <filesystem>
#include <map>
#include <set>

#include "fairshape/experiment/kinds/sheet/constraint_kinds.h"
#include "fairshape/constraint/constraint_factories.h"
#include "fairshape/core/config.h"
#include "fairshape/design/edit_assembly.h"
#include "fairshape/energy/local_quadratic.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/curve_design/curve_components.h"
#include "fairshape/experiment/components.h"
#include "fairshape/experiment/config_loader.h"
#include "fairshape/experiment/repeats.h"
#include "fairshape/experiment/run_kind.h"
#include "fairshape/experiment/kinds/surface_edit/surface_edit_spec.h"
#include "fairshape/experiment/sweep.h"
#include "fairshape/qp/qp_solver.h"
#include "fairshape/subdivision/multires_surface.h"
#include "test_support.h"

using namespace fairshape;
using Catch::Matchers::Contains;
namespace fs = std::filesystem;

TEST_CASE("every config under configs/ is one kind's, and each of its points validates", "[experiment][kinds][slow]") {
  const auto kinds = make_run_kinds();
  std::set<std::string> names;
  for (const auto& k : kinds) CHECK(names.insert(k->name()).second);  // names are unique
  int configs = 0;
  for (const auto& e : fs::recursive_directory_iterator(test::source_path("configs"))) {
    if (e.path().extension() != ".yaml" || e.path().parent_path().filename() == "base") continue;
    INFO(e.path().string());
    const YAML::Node root = load_experiment_config(e.path().string(), {});
    const SweepSpace space(root);
    const auto dirs = input_search_dirs(e.path().string());
    RunKind& first = kind_of(space.point(0).config, kinds);
    for (std::size_t i = 0; i < space.size(); ++i) {
      const RunPoint p = space.point(i);
      CHECK(&kind_of(p.config, kinds) == &first);
      CHECK_NOTHROW(first.validate(p.config, dirs));
    }
    ++configs;
  }
  CHECK(configs > 20);
}

TEST_CASE("a config with no kind's keys, or two kinds' keys, is refused naming the kinds", "[experiment][kinds]") {
  const auto kinds = make_run_kinds();
  CHECK_THROWS_WITH(kind_of(YAML::Load("{name: x}"), kinds), Catch::Contains("sheets"));
  CHECK_THROWS_WITH(kind_of(YAML::Load("{name: x, sheets: [], input: {curve: c.obj}}"), kinds),
                    Catch::Contains("several run kinds"));
}

TEST_CASE("_levels.vtm holds the details of the edited surface, analysed anew", "[experiment][kinds]") {
  const auto kinds = make_run_kinds();
  const std::string cfg = test::source_path("configs/boier-martin/fig2_nose_pull.yaml");
  YAML::Node root = load_experiment_config(cfg, {"input.remesh_base_faces=200", "input.levels=2"});
  const SweepSpace space(root);
  REQUIRE(space.size() == 3);  // thin-plate (back fixed), thin-plate (all but the head fixed), detail-preserving
  const fs::path dir = test::scratch_dir("levels_vtm");
  fs::create_directories(dir / "vtk");
  std::vector<MultiresSurface> edited;
  for (std::size_t i : {0u, 2u}) {
    const RunPoint p = space.point(i);
    RunKind& kind = kind_of(p.config, kinds);
    RunTables tables;
    const MetricRow row = kind.execute(p.config, input_search_dirs(cfg), {dir.string(), p.run_id, false, &tables});
    // The thin plate folds the surface where it fairs the details away, as the config expects.
    REQUIRE(row.at("termination") == (i == 0 ? "folded" : "converged"));
    // The remesh made for the run is measured in its row.
    CHECK(std::stod(row.at("remesh_hausdorff")) > 0);
    CHECK(std::stod(row.at("remesh_hausdorff")) < 0.1);
    CHECK(std::stod(row.at("remesh_edge_ratio")) >= 1);
    edited.push_back(MultiresSurface::load((dir / "vtk" / (p.run_id + "_levels.vtm")).string(), Backend::Optimized));
  }
  const int L = edited[0].levels();
  REQUIRE(L == 2);
  // Thin plate fairs the details away, detail preservation keeps them: the two runs' details differ.
  const double size = edited[1].details(L, DetailSpace::Local).norm();
  const double diff = (edited[0].details(L, DetailSpace::Local) - edited[1].details(L, DetailSpace::Local)).norm();
  CHECK(diff > 1e-3 * size);
  // and the saved hierarchy reproduces the edited finest level it was analysed from
  MultiresSurface copy = edited[0];
  copy.synthesize(DetailSpace::Local);
  CHECK((copy.mesh(L).positions() - edited[0].mesh(L).positions()).norm() < 1e-8 * edited[0].mesh(L).positions().norm());
}

TEST_CASE("registered names share one style: snake_case, none a punctuation mark from another", "[experiment][names]") {
  std::vector<std::vector<std::string>> registries{components().energies.names(), components().constraints.names(),
                                                   components().solvers.names(), curve_components().energies.names(),
                                                   curve_components().constraints.names(),
                                                   curve_components().solvers.names()};
  qp::QpSolverRegistry qp_solvers("qp solver");
  qp::register_qp_solvers(qp_solvers);
  registries.push_back(qp_solvers.names());
  registries.push_back(sheet_constraint_registry().names());
  std::map<std::string, std::string> by_letters;  // the name without punctuation -> the name
  for (const auto& names : registries)
    for (const auto& name : names) {
      INFO(name);
      CHECK(name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") == std::string::npos);
      std::string letters;
      for (char ch : name)
        if (std::isalnum(static_cast<unsigned char>(ch))) letters += ch;
      const auto [it, fresh] = by_letters.emplace(letters, name);
      CHECK((fresh || it->second == name));
    }
  // The former names are errors that say the new one.
  Config none;
  CHECK_THROWS_WITH(components().energies.create("thin-plate", Backend::Optimized, none),
                    Catch::Contains("surface_thin_plate"));
  CHECK_THROWS_WITH(components().energies.create("thin_plate", Backend::Optimized, none),
                    Catch::Contains("umbrella_thin_plate"));
  CHECK_THROWS_WITH(components().energies.create("detail-preserving", Backend::Optimized, none),
                    Catch::Contains("detail_preserving"));
}

TEST_CASE("an edit assembled from energy and constraint objects equals the one a config describes", "[experiment][design]") {
  const YAML::Node cfg = YAML::Load(R"(
name: same_edit
input: { mesh: data/cow.off, representation: catmull-clark, levels: 1 }
energy: [ { type: detail_preserving, alpha: 0.1, beta: 1.0 } ]
constraints:
  - { type: fixed, region: { axis: x, from: 0.0, to: 0.3 } }
  - { type: position, nearest: [0.5, 0.0, 0.0], offset: [0.15, 0.0, 0.08] }
)");
  const SurfaceEditSpec spec = SurfaceEditSpec::from_config(cfg, components(), {test::source_path("")});
  const MultiresSurface h(read_mesh(test::data_path("cow.off")), SubdivisionOptions{}, 1, Backend::Optimized);
  DesignConstraints from_config_placed, typed_placed;
  const EditProblem from_config = assemble_edit_problem(spec.edit_terms(), h, 1, from_config_placed);

  const auto energy = make_stretch_bend({0.1, 1.0}, StretchBendOf::Deformation, Backend::Optimized);
  const auto back = prescribed_offset(VertexSelection::slab(0, 0.0, 0.3), Vec3::Zero());
  const auto nose = prescribed_offset(VertexSelection::nearest({0.5, 0.0, 0.0}), {0.15, 0.0, 0.08});
  EditTerms terms;
  terms.energies = {{energy.get(), 1.0}};
  terms.constraints = {back.get(), nose.get()};
  const EditProblem typed = assemble_edit_problem(terms, h, 1, typed_placed);

  CHECK((typed.H - from_config.H).norm() == 0);
  CHECK((typed.g - from_config.g).norm() == 0);
  CHECK((typed.constraints.A - from_config.constraints.A).norm() == 0);
  CHECK((typed.constraints.C - from_config.constraints.C).norm() == 0);
  CHECK(typed_placed.points.size() == from_config_placed.points.size());
  CHECK_THROWS_AS(VertexSelection::slab(3, 0, 1), InvalidInput);
  CHECK_THROWS_AS(make_stretch_bend({0, 0}, StretchBendOf::Deformation, Backend::Optimized), InvalidInput);
}

TEST_CASE("the harness's repeats: the median execution's timings, the minimum beside them, results that must agree",
          "[experiment][repeats]") {
  const fs::path dir = test::scratch_dir("repeats");
  RunTables tables;
  const RunOutputs out{dir.string(), "abc", true, &tables};
  const auto ok = [](const MetricRow& m) { return m.at("termination") == "converged"; };
  // Execution k: solve_s and a set-up whose sum is time_s; the set-up is slowest where the
  // solve is fastest, so medians taken column by column would add up to more than time_s.
  std::vector<double> solve{0.4, 0.1, 0.3, 0.2}, setup{0.05, 0.5, 0.25, 0.4};
  std::vector<std::string> dirs_seen;
  int k = 0;
  const auto execute = [&](const RunOutputs& o) {
    dirs_seen.push_back(o.dir);
    o.add_row("iterations", {"row of execution " + std::to_string(k)});
    const auto i = static_cast<std::size_t>(k++);
    return MetricRow{{"solve_s", std::to_string(solve[i])}, {"solve_min_s", std::to_string(solve[i])},
                     {"assemble_s", std::to_string(setup[i])}, {"time_s", std::to_string(solve[i] + setup[i])},
                     {"energy", "1.5"}, {"termination", "converged"}, {"message", ""}};
  };
  const std::vector<std::string> measured =
      measured_by_name({"solve_s", "solve_min_s", "assemble_s", "time_s", "energy", "peak_rss_mb"});
  CHECK(measured == std::vector<std::string>{"solve_s", "solve_min_s", "assemble_s", "time_s", "peak_rss_mb"});
  const MetricRow m = run_repeated(4, measured, out, execute, ok);
  // time_s 0.45, 0.6, 0.55, 0.6: the lower middle is execution 2, and every timing is its own.
  CHECK(std::stod(m.at("time_s")) == Approx(0.55));
  CHECK(std::stod(m.at("solve_s")) == Approx(0.3));
  CHECK(std::stod(m.at("assemble_s")) == Approx(0.25));
  CHECK(std::stod(m.at("solve_min_s")) == Approx(0.1));
  CHECK(m.at("repeat") == "4");
  CHECK(m.at("message").empty());
  // Only the first execution writes into the output folder and its tables; the scratch is gone.
  CHECK(dirs_seen.front() == dir.string());
  for (std::size_t i = 1; i < dirs_seen.size(); ++i) CHECK(dirs_seen[i] != dir.string());
  CHECK(tables.rows().at("iterations").size() == 1);
  CHECK(!fs::exists(dirs_seen.back()));

  // A result that changes between executions is named; a repeat that fails stops the repeats.
  k = 0;
  const auto drifting = [&](const RunOutputs&) {
    ++k;
    return MetricRow{{"solve_s", "0.1"}, {"energy", std::to_string(k)}, {"termination", k == 3 ? "numerical_failure" : "converged"},
                     {"message", ""}};
  };
  const MetricRow d = run_repeated(5, {"solve_s"}, out, drifting, ok);
  CHECK_THAT(d.at("message"), Contains("repeat 3 ended numerical_failure") && Contains("repeats disagree in energy"));
  CHECK(d.at("repeat") == "2");
  CHECK(d.at("energy") == "1");
  // A run that fails the first time is not repeated.
  k = 2;
  CHECK(run_repeated(5, {"solve_s"}, out, drifting, ok).at("repeat") == "1");
}
