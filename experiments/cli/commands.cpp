#include "commands.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <iostream>

#include "fairshape/core/atomic_file.h"
#include "fairshape/core/error.h"
#include "fairshape/experiment/config_schema.h"
#include "fairshape/curve_design/curve_components.h"
#include "fairshape/qp/qp_solver.h"
#include "fairshape/experiment/components.h"
#include "fairshape/experiment/kinds/sheet/constraint_kinds.h"
#include "fairshape/energy/local_quadratic.h"
#include "fairshape/io/json_io.h"
#include "fairshape/io/matrix_market.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/io/vtk_io.h"
#include "fairshape/mesh/mesh_stats.h"
#include "fairshape/remesh/quality.h"
#include "fairshape/remesh/remesh.h"
#include "fairshape/subdivision/limit.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape::cli {
namespace fs = std::filesystem;
namespace {

bool is_vtp(const std::string& p) { return fs::path(p).extension() == ".vtp"; }

// The commands read and write VTK polydata besides the mesh formats: name all of them.
void require_command_format(const std::string& path) {
  if (is_vtp(path)) return;
  try {
    (void)format_from_path(path);
  } catch (const IOError&) {
    throw IOError(path + ": unknown mesh format '" + std::filesystem::path(path).extension().string() +
                  "' (valid: .obj, .off, .ply, .vtp)");
  }
}

SurfaceMesh load_any(const std::string& path, std::vector<std::string>* warnings) {
  require_command_format(path);
  if (is_vtp(path)) return read_vtp(path);
  const MeshFile f = read_mesh_file(path);
  if (warnings) *warnings = f.warnings;
  return mesh_from_file(f, path);  // crease/corner tags applied: a bad one names its line
}

// Coordinates near the largest double overflow in subdivision's sums: say so, naming the level
// and vertex, rather than pass inf on (the writers refuse it too, without the reason).
void require_finite_levels(const std::vector<SurfaceMesh>& levels, bool limit) {
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const MatrixX3& P = levels[l].positions();
    if (P.allFinite()) continue;
    Eigen::Index v = 0;
    while (P.row(v).allFinite()) ++v;
    throw InvalidInput("subdivide: " + std::string(limit && l + 1 == levels.size() ? "the limit positions of " : "") + "level " +
                       std::to_string(l) + " has non-finite positions (vertex " + std::to_string(v) +
                       "): the input's coordinates are too large for the subdivision to stay finite");
  }
}

}  // namespace

int cmd_info(const InfoArgs& a) {
  std::vector<std::string> warnings;
  const SurfaceMesh m = load_any(a.mesh, &warnings);
  for (const auto& w : warnings) std::cerr << "warning: " << w << "\n";
  std::cout << a.mesh << "\n" << format_stats(compute_stats(m));
  return 0;
}

int cmd_convert(const ConvertArgs& a) {
  require_command_format(a.input);
  require_command_format(a.output);
  if (a.binary && (is_vtp(a.output) || format_from_path(a.output) != MeshFormat::Ply))
    throw InvalidConfig("--binary: only PLY output has a binary form (output: " + a.output + ")");
  if (is_vtp(a.output)) {
    write_vtp(load_any(a.input, nullptr), a.output);
    return 0;
  }
  if (is_vtp(a.input)) {
    write_mesh(read_vtp(a.input), a.output, {a.binary});
    return 0;
  }
  MeshFile f = read_mesh_file(a.input);
  for (const auto& w : f.warnings) std::cerr << "warning: " << w << "\n";
  if (f.vertices.rows() == 0) throw InvalidInput(a.input + ": no vertices (an empty or unrecognized file): nothing to convert");
  if (!f.faces.empty()) (void)mesh_from_file(f, a.input);  // refuse to pass on bad topology or tags
  if (!f.sharpness.empty() && format_from_path(a.output) != MeshFormat::Obj)
    std::cerr << "warning: " << f.sharpness.size() << " crease/corner tag(s) of " << a.input
              << " are not kept: only .obj (and .vtp) files carry them\n";
  write_mesh_file(f, a.output, {a.binary});
  return 0;
}

int cmd_render(const RenderArgs& a, int argc, char** argv) {
  const char* display = std::getenv("DISPLAY");
  if ((!display || !*display) && !std::getenv("FAIRSHAPE_IN_XVFB")) {
    // Debian's VTK renders only through X: start a virtual one for this command.
    setenv("FAIRSHAPE_IN_XVFB", "1", 1);
    // -noreset: Xvfb otherwise resets when its last client leaves, which races with the
    // display probe in render_png that connects and disconnects just before VTK connects.
    std::vector<std::string> args{"xvfb-run", "-a", "-s", "-screen 0 1600x1200x24 -noreset",
                                  fs::read_symlink("/proc/self/exe").string()};
    for (int i = 1; i < argc; ++i) args.emplace_back(argv[i]);
    std::vector<char*> cargs;
    for (auto& s : args) cargs.push_back(s.data());
    cargs.push_back(nullptr);
    execvp("xvfb-run", cargs.data());
    throw IOError("render: no DISPLAY and xvfb-run is not installed (Debian package 'xvfb')");
  }
  render::FigureSpec spec = a.spec;
  spec.overlays = !a.no_overlays;
  spec.panels.assign(a.files.begin(), a.files.end() - 1);
  const std::string& png = a.files.back();
  if (fs::path(png).extension() != ".png")
    throw InvalidConfig("render: the last file, " + png + ", is the output and must end in .png");
  spec.view.view = render::named_view_names().value(a.view, "--view");
  spec.view.up = render::up_axis_names().value(a.up, "--up");
  spec.background = render::background_names().value(a.background, "--background");
  if (!a.component.empty()) {
    spec.colouring.component = render::component_names().value(a.component, "--component");
    spec.colouring.component_given = true;
  }
  if (!a.map.empty()) {
    spec.colouring.map = render::colour_map_names().value(a.map, "--map");
    spec.colouring.map_given = true;
  }
  if ((spec.colouring.component_given || spec.colouring.map_given || !a.range.empty()) && spec.colouring.array.empty())
    throw InvalidConfig("render: --component, --map and --range colour by an array: give --array");
  if (!a.range.empty()) {
    if (!(a.range[1] > a.range[0])) throw InvalidConfig("render: --range LO HI needs LO < HI");
    spec.range = std::make_pair(a.range[0], a.range[1]);
  }
  if (!a.focus.empty()) {
    spec.view.focused = true;
    spec.view.focus = Vec3(a.focus[0], a.focus[1], a.focus[2]);
  }
  if (spec.view.focused && spec.focus_on_constraints)
    throw InvalidConfig("render: --focus and --focus-constraints both choose the focus: give one");
  if (spec.view.radius > 0 && !spec.view.focused && !spec.focus_on_constraints)
    throw InvalidConfig("render: --radius frames the --focus point: give --focus or --focus-constraints");
  render::render_figure(spec, png);
  std::cerr << "rendered " << spec.panels.size() << " panel(s) -> " << png << "\n";
  return 0;
}

int cmd_subdivide(const SubdivideArgs& a) {
  const SubdivisionOptions opt{scheme_from_string(a.scheme), boundary_from_string(a.boundary),
                               loop_weights_from_string(a.weights)};
  UniformRefineLimits limits;
  limits.max_bytes = a.max_memory_gb * double(1ull << 30);
  std::vector<SurfaceMesh> levels =
      refine_uniform(load_any(a.input, nullptr), opt, a.levels, backend_from_string(a.implementation), limits);
  if (a.limit) levels.back().positions() = limit_positions(levels.back(), opt);
  require_finite_levels(levels, a.limit);
  if (fs::path(a.output).extension() == ".vtm") {
    std::vector<NamedMesh> blocks;
    for (std::size_t l = 0; l < levels.size(); ++l) blocks.push_back({"level_" + std::to_string(l), &levels[l]});
    write_vtm(blocks, a.output);
  } else if (is_vtp(a.output)) {
    write_vtp(levels.back(), a.output);
  } else {
    write_mesh(levels.back(), a.output);
  }
  std::cerr << "subdivided " << a.input << " (" << levels.front().n_faces() << " faces) " << a.levels << "x with "
            << a.scheme << " -> " << a.output << " (" << levels.back().n_vertices() << " vertices, "
            << levels.back().n_faces() << " faces)\n";
  return 0;
}

int cmd_remesh(const RemeshArgs& a) {
  if (fs::path(a.output).extension() != ".vtm") throw IOError(a.output + ": remesh writes a .vtm hierarchy");
  RemeshOptions opt;
  opt.subdivision = {scheme_from_string(a.scheme), boundary_from_string(a.boundary), loop_weights_from_string(a.weights)};
  opt.base_faces = a.base_faces;
  opt.levels = a.levels;
  opt.relax_rounds = a.relax_rounds;
  opt.base = a.base == "triangles" ? RemeshBase::Triangles : RemeshBase::QuadDominant;
  opt.base_method = a.base_method == "edge-collapse" ? BaseMethod::EdgeCollapse
                    : a.base_method == "isotropic"   ? BaseMethod::Isotropic
                                                     : BaseMethod::Auto;
  opt.fit = a.fit == "finest" ? FitMethod::Finest : FitMethod::LevelByLevel;
  RemeshReport r;
  const MultiresSurface h = remesh(load_any(a.input, nullptr), opt, &r);
  h.save(a.output);
  const auto pct = [&r](double d) { return 100.0 * d / r.bbox_diagonal; };
  const char* made_by = r.base_method == BaseMethod::Isotropic ? "isotropic" : "edge-collapse";
  std::cout << "base faces          " << r.base_faces << " (asked " << r.base_faces_requested << "; base by " << made_by
            << ")"
            << "\nfinest level        " << r.fine_vertices << " vertices, " << r.fine_faces << " faces"
            << "\nHausdorff distance  " << r.hausdorff << " (" << pct(r.hausdorff)
            << "% of the bounding-box diagonal; dense->remesh " << pct(r.dense_to_fine) << "%, remesh->dense "
            << pct(r.fine_to_dense) << "%; samples " << pct(r.sample_spacing) << "% apart)"
            << "\nedge ratio          " << r.edge_ratio() << " (finest level: longest " << r.longest_edge
            << ", shortest " << r.shortest_edge << "; at " << r.longest_at.transpose() << " and "
            << r.shortest_at.transpose() << ")"
            << "\nvalence, base       " << to_string(r.base_valence) << "\nvalence, finest     "
            << to_string(r.fine_valence) << "\nclosest-point fallback " << r.unprojected
            << " finest vertices (no facing surface along the normal within reach)\noff the surface     "
            << r.off_surface << " finest vertices, at most " << pct(r.off_surface_max)
            << "% of the diagonal (held back where landing would crowd or stretch their edges)"
            << "\nremesh time         " << r.seconds
            << " s\n";
  // A missed target is not an error (the hierarchy is usable, and the numbers are above), but
  // it must not pass silently.
  const std::vector<std::string> misses = r.misses();
  for (const auto& m : misses) std::cout << "warning: " << m << "\n";
  for (const auto& m : misses) std::cerr << "warning: remesh " << a.input << ": " << m << "\n";
  nlohmann::json j;
  j["targets"] = {{"hausdorff_relative", kHausdorffTarget}, {"edge_ratio", kEdgeRatioTarget}};
  j["targets_met"] = misses.empty();
  j["warnings"] = misses;
  j["input"] = a.input;
  j["asked"] = {{"scheme", a.scheme}, {"base_faces", a.base_faces}, {"levels", a.levels}, {"base", a.base},
                {"base_method", a.base_method}, {"fit", a.fit}, {"relax_rounds", a.relax_rounds}};
  j["base_faces"] = r.base_faces;
  j["base_method"] = made_by;
  j["fine_vertices"] = r.fine_vertices;
  j["fine_faces"] = r.fine_faces;
  j["bbox_diagonal"] = r.bbox_diagonal;
  j["hausdorff"] = r.hausdorff;
  j["hausdorff_relative"] = r.hausdorff_relative();
  j["dense_to_remesh"] = r.dense_to_fine;
  j["remesh_to_dense"] = r.fine_to_dense;
  j["sample_spacing"] = r.sample_spacing;
  j["shortest_edge"] = r.shortest_edge;
  j["longest_edge"] = r.longest_edge;
  j["edge_ratio"] = r.edge_ratio();
  j["shortest_edge_at"] = {r.shortest_at.x(), r.shortest_at.y(), r.shortest_at.z()};
  j["longest_edge_at"] = {r.longest_at.x(), r.longest_at.y(), r.longest_at.z()};
  j["unprojected_vertices"] = r.unprojected;
  j["off_surface_vertices"] = r.off_surface;
  j["off_surface_max"] = r.off_surface_max;
  auto histogram = [](const std::map<int, int>& m) {
    nlohmann::json o = nlohmann::json::object();
    for (const auto& [valence, count] : m) o[std::to_string(valence)] = count;
    return o;
  };
  j["valence_base"] = histogram(r.base_valence);
  j["valence_finest"] = histogram(r.fine_valence);
  j["seconds"] = r.seconds;
  const fs::path out(a.output);
  write_json(j, (out.parent_path() / (out.stem().string() + "_remesh.json")).string());
  return 0;
}

int cmd_energy(const EnergyArgs& a) {
  if (a.alpha == 0 && a.beta == 0) throw InvalidInput("energy: --alpha and --beta are both zero");
  const Backend backend = backend_from_string(a.implementation);
  SurfaceMesh m = load_any(a.mesh, nullptr);
  if (a.level > 0) m = refine_uniform(m, {scheme_from_string(a.scheme)}, a.level, backend).back();
  const SparseMatrix H = stretch_bend_hessian(m, {a.alpha, a.beta}, backend);
  for (int k = 0; k < H.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(H, k); it; ++it)
      if (!std::isfinite(it.value()))
        throw InvalidInput("energy: the Hessian has a non-finite entry at (" + std::to_string(it.row()) + ", " +
                           std::to_string(it.col()) + "): --alpha, --beta or the mesh's coordinates are too large " +
                           "for it to stay finite");
  write_matrix_market(H, a.out, true);
  std::cerr << "H: " << H.rows() << " x " << H.cols() << ", " << H.nonZeros() << " nonzeros -> " << a.out << "\n";
  return 0;
}

template <class R>
static void list_registry(const char* heading, const R& reg) {
  std::cout << heading << ":\n";
  for (const auto& name : reg.names()) {
    const typename R::Entry* first = nullptr;
    std::cout << "  " << name << "\n";
    for (const auto& e : reg.entries())
      if (e.name == name) {
        std::cout << "      " << to_string(e.backend) << ": " << e.doc << "\n";
        if (!first) first = &e;
      }
    for (const auto& o : reg.options(*first))
      std::cout << "      " << o.key << " = " << o.default_value << "  -- " << o.doc << "\n";
  }
}

int cmd_list() {
  const Components& c = components();
  list_registry("energies", c.energies);
  list_registry("constraints", c.constraints);
  list_registry("solvers", c.solvers);
  const CurveComponents& curves = curve_components();  // configs with input.curve
  list_registry("curve energies (optimization.smoothness)", curves.energies);
  list_registry("curve constraints (optimization.constraints)", curves.constraints);
  list_registry("length solvers (optimization.solver)", curves.solvers);
  list_registry("constrained solvers (sheet configs: solver; Welch & Witkin eq. 9/10)", qp::qp_solver_registry());
  list_registry("sheet constraints (sheet configs: constraints[].type; Welch & Witkin §4.2, §5)", sheet_constraint_registry());
  return 0;
}

int cmd_list_keys() {
  for (const KindKeys& k : experiment_keys()) {
    std::cout << k.kind << " runs (" << k.marker << "):\n";
    for (const OptionDoc& d : k.keys) std::cout << "  " << d.key << " = " << d.default_value << "  -- " << d.doc << "\n";
  }
  std::cout << "energy, constraint and solver options: `fairshape list`\n";
  return 0;
}

int cmd_schema(const std::string& output) {
  const std::string schema = experiment_schema(experiment_keys());
  if (output.empty()) {
    std::cout << schema;
    return 0;
  }
  write_atomically(output, [&](std::ostream& os) { os << schema; });
  std::cerr << "schema -> " << output << "\n";
  return 0;
}

}  // namespace fairshape::cli
