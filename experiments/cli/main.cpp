// The `fairshape` command line. CLI11 stays in this one file (it costs ~7 s per TU).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <limits>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "submit_command.h"
#include "fairshape/core/error.h"
#include "fairshape/experiment/run_metadata.h"

namespace {
// CLI11's NonNegativeNumber and PositiveNumber let "nan" and "inf" through: every number a
// command takes is finite.
CLI::Validator finite_at_least(double lo, bool strict) {
  return CLI::Validator(
      [lo, strict](std::string& text) -> std::string {
        double v = 0;
        try {
          std::size_t used = 0;
          v = std::stod(text, &used);
          if (used != text.size()) return "'" + text + "' is not a number";
        } catch (const std::exception&) {
          return "'" + text + "' is not a number";
        }
        if (!std::isfinite(v)) return "'" + text + "' is not finite";
        if (strict ? !(v > lo) : !(v >= lo)) return text + " must be " + (strict ? "> " : ">= ") + std::to_string(lo);
        return "";
      },
      strict ? "POSITIVE FINITE" : lo == 0 ? "NONNEGATIVE FINITE" : "FINITE");
}
// Any finite number (angles, coordinates, colour ranges).
CLI::Validator finite_number() { return finite_at_least(-std::numeric_limits<double>::max(), false); }
// CLI11 names an unexpected option but not the ones there are: say them.
std::string valid_options(const CLI::App& command) {
  std::string names;
  for (const CLI::Option* o : command.get_options()) {
    const std::string n = o->get_name(false, false);
    if (n.rfind("--", 0) == 0 && n.rfind("--help", 0) != 0) names += (names.empty() ? "" : " ") + n;
  }
  return command.get_name() + ": valid options: " + names + "\n";
}
}  // namespace

int main(int argc, char** argv) {
  using namespace fairshape::cli;
  CLI::App app{"fairshape: variational multiresolution shape design"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "help for every subcommand");
  app.set_version_flag("--version", fairshape::version_string(), "the project version and the commit it was built from");

  InfoArgs info;
  auto* c_info = app.add_subcommand("info", "counts, polygon sizes, boundary loops, Euler characteristic, genus, "
                                            "valences and bounding box of a mesh");
  c_info->add_option("mesh", info.mesh, "mesh file (.obj, .off, .ply, .vtp)")->required();

  ConvertArgs conv;
  auto* c_conv = app.add_subcommand("convert", "convert a mesh between formats, chosen by extension");
  c_conv->add_option("input", conv.input, "input mesh (.obj, .off, .ply, .vtp)")->required();
  c_conv->add_option("output", conv.output, "output mesh (.obj, .off, .ply, .vtp)")->required();
  c_conv->add_flag("--binary", conv.binary, "binary PLY output");

  RenderArgs ren;
  fairshape::render::FigureSpec& fig = ren.spec;
  auto* c_ren = app.add_subcommand(
      "render",
      "render meshes, curves or runs to one PNG (VTK offscreen): several inputs are panels side by side with one\n"
      "camera and one colour range; shaded with a key and a fill light, coloured by a point array with a colour bar");
  c_ren->add_option("files", ren.files,
                    "INPUT... OUT.png. An input is a .vtp/.obj/.off/.ply file, a .vtm (a level: FILE.vtm@L, default the\n"
                    "finest), a .pvd (a step: FILE.pvd@K, default the last) or a result folder (a run: DIR@RUN_ID;\n"
                    "a folder with several runs needs one)")
      ->required()->expected(2, -1);
  c_ren->add_option("--run", fig.choice.run, "the run of a result folder input (same as DIR@RUN_ID)");
  c_ren->add_option("--block", fig.choice.block, "the level of a .vtm input (same as FILE.vtm@L)")->check(CLI::Range(0, 1 << 20));
  c_ren->add_option("--step", fig.choice.step, "the step of a .pvd input (same as FILE.pvd@K)")->check(CLI::Range(0, 1 << 30));
  c_ren->add_option("--label", fig.labels, "a panel's label, once per input in order");
  c_ren->add_option("--title", fig.title, "the figure's title");
  c_ren->add_option("--rest", fig.rest, "an input panel shown first, uncoloured (e.g. the mesh before the edit)");
  c_ren->add_option("--rest-label", fig.rest_label, "its label (with --label)")->capture_default_str();
  c_ren->add_option("--columns", fig.columns, "panels per row (default: one row)")->check(CLI::Range(1, 64));
  c_ren->add_option("--array", fig.colouring.array, "colour by this point array (e.g. displacement); default: plain");
  c_ren->add_option("--component", ren.component,
                    "of a vector array: magnitude (default), x, y, z, or normal (signed, along the surface normal:\n"
                    "a ridge and a groove get opposite colours)")
      ->check(CLI::IsMember(fairshape::render::component_names().names()));
  c_ren->add_option("--map", ren.map, "colour map: viridis (default), diverging (default for signed components), grey")
      ->check(CLI::IsMember(fairshape::render::colour_map_names().names()));
  c_ren->add_option("--range", ren.range, "colour range LO HI (default: over every panel; symmetric for diverging)")
      ->expected(2)->check(finite_number());
  c_ren->add_option("--colour-label", fig.colour_label, "the colour bar's label, with units");
  c_ren->add_option("--view", ren.view, "named view in the model's frame: front, side, top, iso")
      ->capture_default_str()->check(CLI::IsMember(fairshape::render::named_view_names().names()));
  c_ren->add_option("--up", ren.up, "the model's up axis: x, y, z")->capture_default_str()
      ->check(CLI::IsMember(fairshape::render::up_axis_names().names()));
  c_ren->add_option("--azimuth", fig.view.azimuth, "turn about the up axis after the view, degrees")
      ->capture_default_str()->check(finite_number());
  c_ren->add_option("--elevation", fig.view.elevation, "raise after the view, degrees")
      ->capture_default_str()->check(finite_number());
  c_ren->add_option("--zoom", fig.view.zoom, "camera zoom factor")->capture_default_str()->check(finite_at_least(0, true));
  c_ren->add_option("--focus", ren.focus, "look at the point X Y Z (with --radius: the part of the model shown)")
      ->expected(3)->check(finite_number());
  c_ren->add_option("--radius", fig.view.radius, "with --focus: the radius shown around it (default: a quarter of the model)")
      ->check(finite_at_least(0, true));
  c_ren->add_flag("--focus-constraints", fig.focus_on_constraints,
                  "look at the first panel's handles and normal targets (from its overlay), framed with a margin");
  c_ren->add_option("--width", fig.panel_width, "panel width, pixels")->capture_default_str()->check(CLI::Range(16, 8192));
  c_ren->add_option("--height", fig.panel_height, "panel height, pixels")->capture_default_str()->check(CLI::Range(16, 8192));
  c_ren->add_option("--background", ren.background, "white or transparent")->capture_default_str()
      ->check(CLI::IsMember(fairshape::render::background_names().names()));
  c_ren->add_option("--overlay", fig.extra_overlays,
                    "draw this over every panel: a .vtp, or an .obj of curves (tubes) or points (spheres)");
  c_ren->add_flag("--no-overlays", ren.no_overlays,
                  "leave out a run's constraints (drawn by default from vtk/<run>_constraints.vtp: fixed vertices grey,\n"
                  "handles red with an arrow from where they started, normal targets magenta arrows, curves orange)");
  c_ren->add_option("--camera-out", fig.camera_path,
                    "also write the camera and each panel's world-to-pixel projection (JSON)");
  c_ren->add_flag("--edges", fig.style.edges, "draw the rendered mesh's edges");
  c_ren->add_flag("--flat", fig.style.flat, "facet shading instead of smooth normals");
  c_ren->add_option("--control-level", fig.style.control_level,
                    "draw this level of the input's hierarchy (a .vtm, or a run's _levels.vtm) as a wireframe")
      ->check(CLI::Range(0, 64));
  c_ren->add_option("--tube-radius", fig.style.tube_radius, "curves' tube radius, as a fraction of the model's diagonal")
      ->capture_default_str()->check(finite_at_least(0, true));
  c_ren->add_option("--overlay-tube-radius", fig.style.overlay_curve_radius,
                    "the overlays' curves (constraint and feature curves): their tube radius, as a fraction of the "
                    "model's diagonal; outlines are half of it")
      ->capture_default_str()->check(finite_at_least(0, true));

  fairshape::SweepOptions run;
  std::string shard = "0/1", worker;
  auto* c_run = app.add_subcommand("run", "run an experiment (a YAML config; a `sweep:` block runs many)");
  c_run->add_option("config", run.config_path, "experiment YAML file")->required();
  c_run->add_option("--set", run.sets, "override a key: --set solver.tolerance=1e-10 (value is YAML)");
  c_run->add_option("--filter", run.filters, "only runs whose key has this value: --filter solver.type=sor");
  c_run->add_option("--out", run.out_dir, "output folder (default results/<name>/<timestamp>_<commit>)");
  c_run->add_flag("--resume", run.resume, "continue an interrupted sweep in --out, skipping finished runs");
  c_run->add_flag("--force", run.force, "start over in an --out folder that holds results");
  c_run->add_option("--jobs", run.jobs, "run sweep points in N parallel processes")->check(CLI::Range(1, 256));
  c_run->add_option("--shard", shard, "run only slice i of n (0 <= i < n), e.g. for a cluster job array");
  c_run->add_flag("--retry-failed", run.retry_failed, "with --resume: run the runs whose row says they failed again");
  c_run->add_flag("--dry-run", run.dry_run, "validate and print the points with their run ids; run nothing");
  c_run->add_flag("--smoke", run.smoke, "run the config's CI-sized variant: its smoke: block of key.path: value overrides");
  c_run->add_flag("--in-process", run.in_process,
                  "run in this process, not in a watched worker (for a debugger; a crash then ends the command, "
                  "--resume continues); only with --jobs 1");
  c_run->add_option("--worker", worker, "internal: set for processes started by --jobs")->group("");

  SubmitArgs subm;
  auto* c_submit = app.add_subcommand(
      "submit", "write (and with --now submit) a sweep as a cluster job array: one `fairshape run --shard i/N --resume`\n"
                "per task and a merge job that waits for them; scripts and results go into --out only");
  c_submit->add_option("config", subm.config, "experiment YAML file")->required();
  c_submit->add_flag("--slurm", subm.slurm, "the scheduler: Slurm (sbatch job array, #SBATCH --requeue)");
  c_submit->add_option("--array-size", subm.array_size,
                       "N, the tasks of the array and the shards of the sweep (1 .. its points; default: min(points, " +
                           std::to_string(kDefaultArraySize) + "))");
  c_submit->add_option("--partition", subm.resources.partition, "sbatch --partition (default: the cluster's)");
  c_submit->add_option("--time", subm.resources.time, "sbatch --time per task: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S");
  c_submit->add_option("--cpus-per-task", subm.resources.cpus_per_task, "sbatch --cpus-per-task")
      ->check(CLI::Range(1, 4096));
  c_submit->add_option("--mem", subm.resources.mem, "sbatch --mem per task: megabytes, or with K, M, G, T (16G)");
  c_submit->add_option("--sbatch-arg", subm.resources.extra,
                       "any other sbatch option, one #SBATCH line on every job (repeatable): "
                       "--sbatch-arg=--account=proj --sbatch-arg=--qos=normal --sbatch-arg=--gres=gpu:1");
  c_submit->add_option("--setup", subm.setup,
                       "a shell line each job runs before its command (repeatable, in order): --setup 'module load gcc'");
  c_submit->add_option("--out", subm.out, "output folder, new or empty (default results/<name>/<timestamp>_<commit>): "
                                          "slurm/ scripts and logs, shards/<i>/, the merged tables");
  c_submit->add_option("--set", subm.sets, "override a key in every task, as for run (value is YAML)");
  c_submit->add_flag("--smoke", subm.smoke, "the config's CI-sized variant, as for run");
  c_submit->add_flag("--now", subm.now, "submit with sbatch --parsable (the merge with --dependency=afterok) and print "
                                        "the job ids");

  SubdivideArgs sub;
  auto* c_sub = app.add_subcommand("subdivide", "uniform Catmull-Clark or Loop subdivision (all levels into a .vtm)");
  c_sub->add_option("--scheme", sub.scheme, "subdivision scheme")->required()->check(CLI::IsMember({"catmull-clark", "loop"}));
  c_sub->add_option("--levels", sub.levels, "number of uniform refinement steps")->required();
  c_sub->add_option("--boundary", sub.boundary, "boundary rule (edge-and-corner pins vertices of one face)")
      ->capture_default_str()->check(CLI::IsMember({"edge-only", "edge-and-corner"}));
  c_sub->add_option("--weights", sub.weights, "Loop vertex weights: loop (Loop 1987) or warren")
      ->capture_default_str()->check(CLI::IsMember({"loop", "warren"}));
  c_sub->add_flag("--limit", sub.limit, "move the final vertices to their limit positions");
  c_sub->add_option("--implementation", sub.implementation, "back end")->capture_default_str()
      ->check(CLI::IsMember({"reference", "optimized"}));
  c_sub->add_option("--max-memory-gb", sub.max_memory_gb, "refuse refinements estimated to need more")
      ->capture_default_str()->check(finite_at_least(0, true));
  c_sub->add_option("input", sub.input, "base mesh (.obj, .off, .ply, .vtp)")->required();
  c_sub->add_option("output", sub.output, "finest mesh (.obj, .off, .ply, .vtp) or every level (.vtm)")->required();

  RemeshArgs rem;
  auto* c_rem = app.add_subcommand("remesh", "semi-regular remesh of a dense triangle mesh into a multiresolution "
                                             "subdivision surface (.vtm of every level with details)");
  c_rem->add_option("dense", rem.input, "dense triangle mesh")->required();
  c_rem->add_option("--scheme", rem.scheme, "subdivision scheme")->required()->check(CLI::IsMember({"catmull-clark", "loop"}));
  c_rem->add_option("--base-faces", rem.base_faces, "target face count of the base mesh")->capture_default_str();
  c_rem->add_option("--levels", rem.levels, "subdivision levels")->capture_default_str();
  c_rem->add_option("--boundary", rem.boundary, "boundary rule")->capture_default_str()
      ->check(CLI::IsMember({"edge-only", "edge-and-corner"}));
  c_rem->add_option("--weights", rem.weights, "Loop weights")->capture_default_str()->check(CLI::IsMember({"loop", "warren"}));
  c_rem->add_option("--base", rem.base, "base faces (catmull-clark: triangles paired into quads, or not; loop: "
                                        "always triangles)")->capture_default_str()
      ->check(CLI::IsMember({"quad-dominant", "triangles"}));
  c_rem->add_option("--base-method", rem.base_method, "how the base triangles are made: edge collapse (keeps "
                                                      "horn and tail tips), isotropic remeshing (even edges), or "
                                                      "auto: both, keeping the better result")->capture_default_str()
      ->check(CLI::IsMember({"auto", "isotropic", "edge-collapse"}));
  c_rem->add_option("--fit", rem.fit, "project and relax every level coarse to fine, or only the finest (the earlier "
                                      "remesher)")->capture_default_str()
      ->check(CLI::IsMember({"level-by-level", "finest"}));
  c_rem->add_option("--relax-rounds", rem.relax_rounds, "tangential relaxation rounds per fitted level")
      ->capture_default_str()->check(CLI::Range(0, 1000));
  c_rem->add_option("output", rem.output, "hierarchy (.vtm, plus a .json sidecar and a _remesh.json quality report)")
      ->required();

  EnergyArgs en;
  auto* c_en = app.add_subcommand("energy", "export the stretch+bend matrix H (E = ½ Pᵀ H P, Boier-Martin et al. §3.4) "
                                            "of a mesh or one of its subdivision levels as Matrix Market");
  c_en->add_option("mesh", en.mesh, "mesh (.obj, .off, .ply, .vtp)")->required();
  c_en->add_option("--out", en.out, "output .mtx (SciPy: scipy.io.mmread)")->required();
  c_en->add_option("--alpha", en.alpha, "stretch weight")->capture_default_str()->check(finite_at_least(0, false));
  c_en->add_option("--beta", en.beta, "bend weight")->capture_default_str()->check(finite_at_least(0, false));
  c_en->add_option("--level", en.level, "subdivide the mesh this many times first")->capture_default_str()
      ->check(CLI::Range(0, 8));
  c_en->add_option("--scheme", en.scheme, "scheme for --level")->capture_default_str()
      ->check(CLI::IsMember({"catmull-clark", "loop"}));
  c_en->add_option("--implementation", en.implementation, "back end")->capture_default_str()
      ->check(CLI::IsMember({"reference", "optimized"}));

  bool list_keys = false;
  auto* c_list = app.add_subcommand("list", "every registered energy, constraint and solver, with options");
  c_list->add_flag("--keys", list_keys, "every key of every kind of experiment config instead, with its default");
  std::string schema_out;
  auto* c_schema = app.add_subcommand("schema", "the experiment configs' keys as a JSON Schema (draft-07), for editors "
                                                "to complete and check configs");
  c_schema->add_option("output", schema_out, "the .json to write (default: standard output)");

  std::vector<std::string> merge_in;
  std::string merge_out;
  auto* c_merge = app.add_subcommand("merge", "join the output folders of shards (every table, run.json) into one folder, "
                                               "or CSV tables into one");
  c_merge->add_option("output", merge_out, "merged folder (or CSV)")->required();
  c_merge->add_option("inputs", merge_in, "shard output folders (or CSV tables of one name)")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int status = app.exit(e) == 0 ? 0 : 2;  // --help is a success; bad arguments are invalid input (2)
    if (status != 0 && *c_submit) std::cerr << valid_options(*c_submit);
    return status;
  }
  try {
    if (*c_info) return cmd_info(info);
    if (*c_conv) return cmd_convert(conv);
    if (*c_ren) return cmd_render(ren, argc, argv);
    if (*c_run) {
      run.shard = fairshape::Slice::parse(shard, "--shard");
      run.is_worker = !worker.empty();
      if (run.is_worker) run.worker = fairshape::Slice::parse(worker, "--worker");
      run.argv.assign(argv, argv + argc);
      if (run.retry_failed && !run.resume) throw fairshape::InvalidConfig("--retry-failed needs --resume");
      if (run.in_process && run.jobs > 1)
        throw fairshape::InvalidConfig("--in-process runs one point at a time: it needs --jobs 1, not --jobs " +
                                       std::to_string(run.jobs));
      run.executable = std::filesystem::read_symlink("/proc/self/exe").string();
      if (run.resume && run.out_dir.empty()) throw fairshape::InvalidConfig("--resume needs --out DIR");
      return fairshape::run_sweep(run);
    }
    if (*c_submit) return cmd_submit(subm);
    if (*c_list) return list_keys ? cmd_list_keys() : cmd_list();
    if (*c_schema) return cmd_schema(schema_out);
    if (*c_sub) return cmd_subdivide(sub);
    if (*c_rem) return cmd_remesh(rem);
    if (*c_en) return cmd_energy(en);
    if (*c_merge) {
      fairshape::merge_results(merge_in, merge_out);
      return 0;
    }
  } catch (const fairshape::Error& e) {
    std::cerr << "fairshape: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "fairshape: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
