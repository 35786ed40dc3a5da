// A curve traced on the current surface (`from_surface.surface: current`) is Welch & Witkin's
// "add a curve": the sheet as the steps before left it is the curve's target, exactly, so adding
// the curve moves nothing; traced on the initial surface it pulls the lifted sheet back.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include <yaml-cpp/yaml.h>

#include "fairshape/core/error.h"
#include "fairshape/experiment/config_loader.h"
#include "fairshape/experiment/kinds/sheet/sheet_run.h"
#include "fairshape/experiment/run_outputs.h"
#include "fairshape/io/mesh_io.h"
#include "test_support.h"

using namespace fairshape;
namespace fs = std::filesystem;

namespace {

struct Result {
  MetricRow row;
  SurfaceMesh mesh;
};

Result run_sheet(YAML::Node cfg, const std::string& id) {
  cfg["output"]["vtk"] = "none";
  const fs::path dir = test::scratch_dir(std::string("traced_curve_") + id);
  create_run_folders(dir.string());
  SheetRunSpec spec = SheetRunSpec::from_config(cfg);
  const RunOutputs out{dir.string(), id, true, nullptr};
  Result r{execute_sheet_run(spec, out), {}};
  r.mesh = read_mesh(out.final_path());
  return r;
}

// Figure 1 up to step 2: the arc promoted (step 0) and pulled up (step 1), then at step 2 the
// ridge added with no edit (`surface` how it is traced) or, without the ridge, nothing added.
YAML::Node fig1_to_step2(const std::string& solver, const std::string& surface, bool with_ridge) {
  YAML::Node cfg = load_experiment_config(test::source_path("configs/welch-witkin/fig1.yaml"), {});
  set_by_path(cfg, "solver.type", YAML::Load(solver));
  set_by_path(cfg, "curves.1.from_surface.surface", YAML::Load(surface));
  cfg["curves"][1].remove("edits");
  if (!with_ridge) {
    cfg["constraints"].remove(5);  // the ridge's curve constraint
    // The arc edited by nothing at step 2, so the run still has steps 0..2.
    cfg["curves"][0]["edits"].push_back(YAML::Load("{step: 2, t: 0.5, radius: 0.6, by: [0, 0, 0]}"));
  }
  return cfg;
}

}  // namespace

TEST_CASE("a curve traced on the current surface and added with no edit moves the sheet by nothing", "[sheet][traced_curve]") {
  for (const std::string solver : {"kkt", "range_space", "qr_penalty"}) {
    INFO(solver);
    const Result before = run_sheet(fig1_to_step2(solver, "current", false), "without_" + solver);
    const Result added = run_sheet(fig1_to_step2(solver, "current", true), "current_" + solver);
    INFO(added.row.at("message"));
    REQUIRE(before.row.at("termination") == "converged");
    REQUIRE(added.row.at("termination") == "converged");
    REQUIRE(added.mesh.n_vertices() == before.mesh.n_vertices());
    // Round-off: the sheet is 2 wide and lifted 0.6.
    CHECK((added.mesh.positions() - before.mesh.positions()).cwiseAbs().maxCoeff() <= 1e-8);
    CHECK(std::stod(added.row.at("energy")) == Approx(std::stod(before.row.at("energy"))).epsilon(1e-8));
    // The curve's target is the surface it was traced on: met to round-off, not to its chords.
    CHECK(std::stod(added.row.at("max_constraint_error")) <= std::stod(before.row.at("max_constraint_error")) + 1e-8);
  }
  // Traced on the initial (flat) sheet the same curve pulls the lifted sheet back down.
  const Result before = run_sheet(fig1_to_step2("kkt", "current", false), "without");
  const Result initial = run_sheet(fig1_to_step2("kkt", "initial", true), "initial");
  CHECK((initial.mesh.positions() - before.mesh.positions()).cwiseAbs().maxCoeff() > 0.5);
}

TEST_CASE("from_surface.surface: current is refused for variational curves and unknown values are named", "[sheet][traced_curve]") {
  YAML::Node cfg = fig1_to_step2("kkt", "currnt", true);
  CHECK_THROWS_WITH(SheetRunSpec::from_config(cfg), Catch::Contains("curves[1].from_surface.surface") && Catch::Contains("current"));
  cfg = fig1_to_step2("kkt", "current", true);
  cfg["curves"][1]["variational"] = YAML::Load("{spans: 4}");
  CHECK_THROWS_WITH(SheetRunSpec::from_config(cfg), Catch::Contains("curves[1].from_surface.surface") && Catch::Contains("initial"));
}
