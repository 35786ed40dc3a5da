#include "fairshape/experiment/kinds/surface_edit/surface_edit_spec.h"

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "fairshape/core/config.h"
#include "fairshape/experiment/components.h"
#include "fairshape/experiment/vtk_policy.h"
#include "fairshape/qp/qp_solver.h"

namespace fairshape {
namespace fs = std::filesystem;

bool solver_is_used(const SurfaceEditSpec& s) {
  return s.constraint_mode == ConstraintMode::Paper &&
         (s.accuracy.mode == AccuracyMode::SingleLevel || s.accuracy.mode == AccuracyMode::Converged);
}

Accuracy AccuracyOptions::ladder() const {
  FAIRSHAPE_ASSERT(multilevel(), "a single-level run has no ladder");
  return mode == AccuracyMode::Interactive ? Accuracy::Interactive
         : mode == AccuracyMode::Improved  ? Accuracy::Improved
                                           : Accuracy::Converged;
}

EditTerms SurfaceEditSpec::edit_terms() const {
  EditTerms t;
  for (const auto& e : energies) t.energies.push_back({e.energy.get(), e.weight});
  for (const auto& c : constraints) {
    t.constraints.push_back(c.constraint.get());
    t.influences.push_back(c.influence);
  }
  t.positions = formulation == Formulation::Position;
  t.frame_rows_for_auto_normals = frame_rows_for_auto_normals;
  // The levels below: only a multilevel solver reads them (the run's, or the cascade's relaxation).
  t.levels = solver->uses_levels() ||
             (accuracy.mode == AccuracyMode::Improved && accuracy.relaxation.rfind("multigrid", 0) == 0);
  return t;
}

Config SurfaceEditSpec::qp_config() const {
  return Config(qp_options ? YAML::Clone(qp_options) : YAML::Node(YAML::NodeType::Map),
                "problem." + std::string(constraint_mode_names().name(constraint_mode)));
}

SubdivisionOptions SurfaceEditSpec::subdivision() const {
  FAIRSHAPE_ASSERT(representation != Representation::Mesh, "the mesh representation has no subdivision");
  return {representation == Representation::Loop ? SchemeType::Loop : SchemeType::CatmullClark, boundary, loop_weights,
          crease_method};
}

namespace {

const NameTable<Representation>& representation_names() {
  static const NameTable<Representation> t{{Representation::Mesh, "mesh"},
                                           {Representation::CatmullClark, "catmull-clark"},
                                           {Representation::Loop, "loop"}};
  return t;
}
const NameTable<AccuracyMode>& accuracy_names() {
  static const NameTable<AccuracyMode> t{{AccuracyMode::SingleLevel, "single-level"},
                                         {AccuracyMode::Interactive, "interactive"},
                                         {AccuracyMode::Improved, "improved"},
                                         {AccuracyMode::Converged, "converged"}};
  return t;
}
const NameTable<Formulation>& formulation_names() {
  static const NameTable<Formulation> t{{Formulation::Displacement, "displacement"}, {Formulation::Position, "position"}};
  return t;
}
const NameTable<InitialGuess>& initial_guess_names() {
  static const NameTable<InitialGuess> t{{InitialGuess::Zero, "zero"}, {InitialGuess::Random, "random"}};
  return t;
}
const NameTable<ConstraintMode>& coarse_mode_names() {  // the ladder's coarse solve: two of the modes
  static const NameTable<ConstraintMode> t{{ConstraintMode::Kkt, "kkt"}, {ConstraintMode::Paper, "paper"}};
  return t;
}

}  // namespace

namespace {

void read_energies(Config& root, const Components& c, Backend backend, SurfaceEditSpec& s) {
  for (Config e : root.child_list("energy", "energy terms: [{type, weight, options...}]")) {
    EnergyTerm t;
    t.type = e.require<std::string>("type", "energy name (see `fairshape list`)");
    t.weight = e.get_number("weight", 1.0, 0.0, 1e12, "weight of this term");
    if (e.documenting()) {  // every energy's options belong to an item of the list
      for (const auto& name : c.energies.names())
        (void)c.energies.create(name, c.energies.has(name, backend) ? backend : Backend::Reference, e);
      continue;
    }
    t.energy = c.energies.create(t.type, backend, e);
    e.check_no_unknown_keys();
    s.energies.push_back(std::move(t));
  }
}

// influence_level / influence_rings of one constraint (Boier-Martin et al. §4.2, region of
// influence: design/influence.h). A fixed constraint moves nothing, so it has no region: it is
// held in every pass, and the keys are refused on it rather than ignored.
int read_rings(const Config& k, const std::string& text) {
  if (text == "auto") return Influence::kAutoRings;
  std::size_t used = 0;
  int rings = 0;
  try {
    rings = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || used == 0 || rings < -1 || rings > 1000)
    throw InvalidConfig(k.key_path("influence_rings") + ": '" + text + "' is not a ring count (valid: 0..1000, -1 for "
                        "the whole level, or auto)");
  return rings;
}

Influence read_influence(Config& k, const std::string& type) {
  Influence i;
  i.held = type == "fixed";
  const bool given = k.has("influence_level") || k.has("influence_rings");
  if (i.held && given)
    throw InvalidConfig(k.key_path(k.has("influence_level") ? "influence_level" : "influence_rings") +
                        ": a fixed constraint is held in every pass of the edit; it has no region of influence");
  i.level = k.get_int("influence_level", Influence::kEditLevel, -1, 16,
                      "level the constraint is propagated to and solved on: its region of influence is coarse "
                      "(global) or fine (local) with it (-1: the edit level; must not be finer than `level`)");
  // A level of its own bounds the region (auto: as many rings as keep the result unfolded)
  // unless told otherwise; without either key the constraint is solved on the whole edit level.
  const std::string rings = k.get<std::string>(
      "influence_rings", i.level != Influence::kEditLevel ? "auto" : "-1",
      "rings of the influence level's vertices around the constraint's rows that may move: a count 0..1000, "
      "-1 (the whole level) or auto (from 2, doubled while the result folds; the default when influence_level is given)");
  i.rings = read_rings(k, rings);
  if (i.held) i.level = Influence::kEditLevel, i.rings = Influence::kWholeLevel;
  return i;
}

}  // namespace

ConstraintTerm read_constraint_term(Config& k, const Components& c, Backend backend) {
  ConstraintTerm t;
  t.type = k.require<std::string>("type", "constraint name (see `fairshape list`)");
  t.influence = read_influence(k, t.type);
  if (k.documenting()) {  // every constraint's options belong to an item of the list
    for (const auto& name : c.constraints.names())
      (void)c.constraints.create(name, c.constraints.has(name, backend) ? backend : Backend::Reference, k);
    return t;
  }
  t.constraint = c.constraints.create(t.type, backend, k);
  k.check_no_unknown_keys();
  return t;
}

namespace {

void read_constraints(Config& root, const Components& c, Backend backend, SurfaceEditSpec& s) {
  for (Config k : root.child_list("constraints", "constraints: [{type, options...}]")) {
    ConstraintTerm t = read_constraint_term(k, c, backend);
    if (!k.documenting()) s.constraints.push_back(std::move(t));
  }
}

// The solver block. Every registered solver's schema applies to it whichever is chosen, so a
// key's validity never depends on its siblings (solver.tolerance is valid beside a direct
// solver) and a sweep over solver.type carries every solver's options; a key no solver knows
// is an error. What the chosen solver does not read is recorded in unused_keys, never
// reported as if it had been used.
void read_solver(Config& root, const Components& c, Backend backend, SurfaceEditSpec& s) {
  Config sc = root.child("solver", "linear solver: {type, tolerance, max_iterations, <type>: {...}}");
  const auto read_common = [&](Config& block) {
    s.solver_type = block.get_choice("type", "cholesky", c.solvers.names(), "solver name");
    s.initial_guess = block.get_enum("initial_guess", InitialGuess::Zero, initial_guess_names(),
                                     "start of iterative solvers (random uses the seed)");
  };
  read_common(sc);
  for (const auto& name : c.solvers.names())
    if (name != s.solver_type)
      (void)c.solvers.create(name, c.solvers.has(name, backend) ? backend : Backend::Reference, sc);
  s.solver = c.solvers.create(s.solver_type, backend, sc);
  sc.check_no_unknown_keys();
  Config chosen(sc.node(), sc.path());
  read_common(chosen);
  (void)c.solvers.create(s.solver_type, backend, chosen);
  // The other constraint modes solve their KKT or QP system themselves, and the interactive
  // and improved ladders use their own direct and relaxation solves: the block is unused.
  if (solver_is_used(s)) {
    for (const auto& k : chosen.unread_keys()) s.unused_keys.push_back(sc.key_path(k));
  } else {
    s.note_unused(sc);
  }
}

// problem.kkt, problem.qr_penalty, problem.range_space: each QP mode's options, validated
// against its solver's schema whichever mode is chosen (a sweep over constraint_mode carries
// them all); the blocks of modes not chosen are recorded as unused.
void read_qp_options(Config& pc, Backend backend, SurfaceEditSpec& s) {
  const auto& registry = qp::qp_solver_registry();
  for (const auto& name : registry.names()) {
    if (name == "paper") continue;  // the split's free solver is the solver: block
    Config block = pc.child(name, "options of constraint_mode " + name + " (see `fairshape list`)");
    (void)registry.create(name, registry.has(name, backend) ? backend : Backend::Optimized, block);
    block.check_no_unknown_keys();
    const bool chosen = s.constraint_mode != ConstraintMode::Paper && constraint_mode_names().name(s.constraint_mode) == name;
    if (chosen) s.qp_options = block.node();
    else s.note_unused(block);
  }
}

void read_output(Config& root, SurfaceEditSpec& s) {
  OutputOptions& o = s.output;
  Config oc = root.child("output", "what each run writes");
  o.vtk = read_vtk_policy(oc, "also the iterate every output.vtk_every iterations, as a .pvd series");
  o.vtk_every = oc.get_int("vtk_every", o.vtk_every, 1, 1000000, "iterations between VTK snapshots");
  s.note_unused(oc, "vtk_every", o.vtk == VtkPolicy::All);
  o.iterations = oc.get<bool>("iterations", o.iterations, "write iterations.csv (residual history)");
  o.final_mesh = oc.get<bool>("final_mesh", o.final_mesh, "write final.obj (final/<run_id>.obj in sweeps)");
  o.reference_solution = oc.get<bool>("reference_solution", o.reference_solution,
                                      "compute error_vs_reference against CHOLMOD's solution of the same system");
  o.system = oc.get<bool>("system", o.system,
                          "write the assembled problem as Matrix Market in system/<run_id>/ (H, g, constraint rows, "
                          "prolongations; paper mode: the reduced system and the constrained set)");
  oc.check_no_unknown_keys();
}

void read_accuracy(Config& pc, SurfaceEditSpec& s) {
  AccuracyOptions& a = s.accuracy;
  a.mode = pc.get_enum("accuracy", a.mode, accuracy_names(),
                         "single-level: the solver on the edit level alone; interactive | improved | converged: "
                         "Boier-Martin et al. §5's ladder from problem.coarse_level");
  const int edit_level = s.edit_level < 0 ? s.levels : s.edit_level;
  a.coarse_level = pc.get_int("coarse_level", a.coarse_level, 0, 8, "level of the ladder's direct coarse solve");
  a.coarse_constraint_mode = pc.get_enum(
      "coarse_constraint_mode", a.coarse_constraint_mode, coarse_mode_names(),
      "the ladder's coarse solve: kkt (exact minimizer) or paper (minimum-norm constrained vertices, which "
      "turns a fine handle into a spike on a coarse level)");
  a.relaxation = pc.get_choice("relaxation", a.relaxation, {"gauss_seidel", "sor", "multigrid", "multigrid_cg"},
                               "improved: the cascade's relaxation on each level (multigrid, multigrid_cg: cycles "
                               "over the levels below, which also reach the smooth error sweeps leave)");
  const bool cycles = a.relaxation.rfind("multigrid", 0) == 0;
  a.relaxation_sweeps = pc.get_int("relaxation_sweeps", cycles ? 2 : 10, 1, 1000000,
                                   "improved: per level, sweeps (default 10, the paper's) or multigrid cycles / "
                                   "preconditioned iterations (default 2)");
  a.relaxation_omega = pc.get_number("relaxation_omega", a.relaxation_omega, 1e-3, 1.999, "improved with sor: ω");
  a.drag_steps = pc.get_int("drag_steps", a.drag_steps, 1, 100000,
                            "solve the edit as a drag in this many steps, each warm-started from the last");
  // What only the ladder reads, and what only the improved ladder's sor cascade reads.
  for (const char* key : {"coarse_level", "coarse_constraint_mode", "drag_steps"}) s.note_unused(pc, key, a.multilevel());
  for (const char* key : {"relaxation", "relaxation_sweeps"}) s.note_unused(pc, key, a.mode == AccuracyMode::Improved);
  s.note_unused(pc, "relaxation_omega", a.mode == AccuracyMode::Improved && a.relaxation == "sor");
  if (!a.multilevel()) {
    if (a.drag_steps > 1) throw InvalidConfig(pc.key_path("drag_steps") + ": a drag needs problem.accuracy "
                                              "interactive, improved or converged");
    return;
  }
  if (a.coarse_level > edit_level)
    throw InvalidConfig(pc.key_path("coarse_level") + ": " + std::to_string(a.coarse_level) +
                        " is above the edit level " + std::to_string(edit_level));
  if (s.constraint_mode != ConstraintMode::Paper)
    throw InvalidConfig(pc.key_path("accuracy") + ": " + std::string(accuracy_names().name(a.mode)) +
                        " needs problem.constraint_mode paper");
}

// Constraints with regions of influence under §5's ladder (design/regional_edit.h): a pass on a
// whole level is solved on the ladder, a bounded region directly. A drag moves every handle of
// one constraint set along its offset, which the regional passes (each measuring what is still
// missing on the surface) do not do: refused rather than run as a single step.
void refuse_drags_with_regions(Config& pc, const SurfaceEditSpec& s) {
  if (s.accuracy.drag_steps <= 1) return;
  for (std::size_t i = 0; i < s.constraints.size(); ++i)
    if (s.constraints[i].influence.regional())
      throw InvalidConfig(pc.key_path("drag_steps") + ": a drag cannot be combined with constraints[" +
                          std::to_string(i) + "]'s influence_level / influence_rings: constraints with regions of "
                          "influence are solved in passes, once (use drag_steps: 1)");
}

// steps: the run as a sequence of session steps (design/surface_edit_session.h), each naming what
// changes before it is solved — every target scaled (problem.drag_steps' step k is scale: k/N),
// handles moved to offsets of their own — and optionally §5's mode it is solved with. Without
// the list, problem.drag_steps equal steps of the configured offsets.
void read_steps(Config& root, SurfaceEditSpec& s) {
  s.scheduled = root.has("steps");
  const std::vector<Config> items = root.child_list(
      "steps", "design steps, each solved in turn from the last: [{scale, offsets: {handle: [x, y, z]}, accuracy}]");
  for (std::size_t i = 0; i < items.size(); ++i) {
    Config k = items[i];
    EditStepSpec step;
    if (k.has("scale") || k.documenting())
      step.scale = k.get_number("scale", 1.0, -1e6, 1e6, "every target this many times its configured offset (applied first)");
    const auto offsets = k.get<std::map<int, std::vector<double>>>(
        "offsets", {}, "handle (the constraint's index in `constraints`) → its offset from rest [x, y, z] from this step on");
    for (const auto& [handle, v] : offsets) {
      std::ostringstream where;
      where << k.key_path("offsets") << "." << handle;
      if (handle < 0 || handle >= static_cast<int>(s.constraints.size()))
        throw InvalidConfig(where.str() + ": no such handle (the constraints are numbered 0.." +
                            std::to_string(static_cast<int>(s.constraints.size()) - 1) + ")");
      if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
        throw InvalidConfig(where.str() + ": expected a finite offset [x, y, z]");
      step.offsets.emplace_back(handle, Vec3(v[0], v[1], v[2]));
    }
    if (k.has("accuracy") || k.documenting()) {
      step.accuracy = k.get_enum("accuracy", s.accuracy.mode, accuracy_names(),
                                 "§5's mode of this step's solve (default problem.accuracy): interactive | improved | "
                                 "converged, on the run's ladder");
      if (!k.documenting() && *step.accuracy != s.accuracy.mode &&
          (!s.accuracy.multilevel() || *step.accuracy == AccuracyMode::SingleLevel))
        throw InvalidConfig(k.key_path("accuracy") + ": '" + std::string(accuracy_names().name(*step.accuracy)) +
                            "' needs problem.accuracy interactive, improved or converged (a ladder), and a step "
                            "cannot leave it");
    }
    k.check_no_unknown_keys();
    if (!k.documenting()) s.steps.push_back(std::move(step));
  }
  if (root.documenting()) return;
  if (s.scheduled && s.steps.empty()) throw InvalidConfig("steps: at least one step");
  if (s.scheduled && s.accuracy.drag_steps > 1)
    throw InvalidConfig("steps: give the design steps or problem.drag_steps, not both");
  if (!s.scheduled)
    for (int k = 1; k <= s.accuracy.drag_steps; ++k)
      s.steps.push_back({static_cast<double>(k) / s.accuracy.drag_steps, {}, {}});
  for (std::size_t i = 0; s.scheduled && i < s.constraints.size(); ++i)
    if (s.constraints[i].influence.regional())
      throw InvalidConfig("steps: design steps cannot be combined with constraints[" + std::to_string(i) +
                          "]'s influence_level / influence_rings: constraints with regions of influence are solved in "
                          "passes, once");
}

// problem.rotation_iterations: details that turn with the surface (design/rotation_aware_edit.h),
// on the single-level edit: the ladder and the regional passes solve the linear energy.
void read_rotations(Config& pc, SurfaceEditSpec& s) {
  RotationAwareOptions& r = s.rotations;
  r.iterations = pc.get_int("rotation_iterations", r.iterations, 0, 10000,
                            "rounds of rotation-aware detail preservation after the linear solve (0: the linear "
                            "energy of the deformation, as in the paper)");
  r.tolerance = pc.get_number("rotation_tolerance", r.tolerance, 1e-14, 1.0,
                              "stop the rounds when one changes the deformation by less than this (relative)");
  s.note_unused(pc, "rotation_tolerance", r.iterations > 0);
  if (r.iterations == 0) return;
  if (s.accuracy.multilevel())
    throw InvalidConfig(pc.key_path("rotation_iterations") + ": rotation-aware rounds need accuracy single-level");
  for (const ConstraintTerm& c : s.constraints)
    if (c.influence.regional())
      throw InvalidConfig(pc.key_path("rotation_iterations") + ": rotation-aware rounds cannot be combined with "
                          "influence_level / influence_rings (regional passes solve the linear energy)");
}

// A saved hierarchy (`fairshape remesh`, a run's _levels.vtm) fixes the representation, the
// depth and the subdivision rules: keys that say otherwise are refused, naming both values.
void adopt_saved_hierarchy(Config& in, SurfaceEditSpec& s) {
  MultiresSurface::Stored st;
  try {
    st = MultiresSurface::stored(s.mesh_path);
  } catch (const Error& e) {
    throw InvalidConfig(in.key_path("mesh") + ": " + e.what());
  }
  const Representation r = st.options.scheme == SchemeType::Loop ? Representation::Loop : Representation::CatmullClark;
  const auto clash = [&](const char* key, std::string_view given, std::string_view saved) {
    throw InvalidConfig(in.key_path(key) + ": '" + std::string(given) + "', but " + s.mesh_path + " is a saved hierarchy with '" +
                        std::string(saved) + "' (leave the key out)");
  };
  if (in.has("representation") && s.representation != r)
    clash("representation", representation_names().name(s.representation), representation_names().name(r));
  if (in.has("levels") && s.levels != st.levels) clash("levels", std::to_string(s.levels), std::to_string(st.levels));
  if (in.has("boundary") && s.boundary != st.options.boundary)
    clash("boundary", to_string(s.boundary), to_string(st.options.boundary));
  if (in.has("weights") && s.loop_weights != st.options.weights)
    clash("weights", to_string(s.loop_weights), to_string(st.options.weights));
  if (in.has("crease_method") && s.crease_method != st.options.crease)
    clash("crease_method", to_string(s.crease_method), to_string(st.options.crease));
  if (s.remesh_base_faces > 0)
    throw InvalidConfig(in.key_path("remesh_base_faces") + ": " + s.mesh_path + " is a saved hierarchy, remeshed already");
  s.representation = r;
  s.levels = st.levels;
  s.boundary = st.options.boundary;
  s.loop_weights = st.options.weights;
  s.crease_method = st.options.crease;
}

// input: the mesh file and how its hierarchy is built.
void read_input(Config& root, const std::vector<std::string>& search_dirs, SurfaceEditSpec& s) {
  Config in = root.child("input", "input geometry");
  s.mesh_path = read_input_path(in, "mesh", "mesh file (.obj, .off, .ply), or a saved hierarchy (.vtm)", search_dirs);
  s.representation = in.get_enum("representation", Representation::Mesh, representation_names(),
                                 "shape representation: the mesh itself or its subdivision surface");
  s.levels = in.get_int("levels", 0, 0, 8, "uniform subdivision steps; the problem lives on the finest level");
  s.max_memory_gb = in.get_number("max_memory_gb", s.max_memory_gb, 0.001, 1e6,
                                  "GiB: refuse uniform refinements whose estimated memory is larger (level 6 of the "
                                  "cow: ~9 GiB for the meshes alone)");
  s.boundary = in.get_enum("boundary", BoundaryMode::EdgeOnly, boundary_names(), "subdivision boundary rule");
  s.loop_weights = in.get_enum("weights", LoopWeights::Loop, loop_weight_names(), "Loop vertex weights");
  s.crease_method = in.get_enum("crease_method", CreaseMethod::Uniform, crease_method_names(),
                                "how semi-sharp crease sharpness decays per level (OpenSubdiv's creasing "
                                "method): uniform (minus 1) or chaikin (averaged along the crease first)");
  s.remesh_base_faces = in.get_int("remesh_base_faces", 0, 0, 10000000,
                                   "remesh the input into a hierarchy with details from about this many base faces "
                                   "(0: the input mesh is the base, zero details)");
  s.remesh_triangle_base = in.get_choice("remesh_base", "quad-dominant", {"quad-dominant", "triangles"},
                                         "Catmull-Clark remesh base: triangles paired into quads, or not (`fairshape "
                                         "remesh --base`)") == "triangles";
  s.edit_level = in.get_int("edit_level", -1, -1, 8, "level the deformation is solved on (-1: the finest)");
  s.crease_angle = in.get_number("crease_angle", 0.0, 0.0, 179.0,
                                 "degrees: input edges whose dihedral angle exceeds it become infinitely sharp creases, "
                                 "their end and junction vertices corners (0: off; tags in an .obj apply anyway)");
  in.check_no_unknown_keys();
  if (std::filesystem::path(s.mesh_path).extension() == ".vtm") adopt_saved_hierarchy(in, s);
  s.note_unused(in, "boundary", s.representation != Representation::Mesh);
  s.note_unused(in, "max_memory_gb", s.representation != Representation::Mesh && s.remesh_base_faces == 0 &&
                                         std::filesystem::path(s.mesh_path).extension() != ".vtm");
  s.note_unused(in, "weights", s.representation == Representation::Loop);
  s.note_unused(in, "crease_method", s.representation != Representation::Mesh);
  if (s.edit_level > s.levels)
    throw InvalidConfig(in.key_path("edit_level") + ": " + std::to_string(s.edit_level) + " is above the finest level " +
                        std::to_string(s.levels));
  s.note_unused(in, "crease_angle", s.representation != Representation::Mesh);
  if (s.crease_angle > 0 && (s.remesh_base_faces > 0 || std::filesystem::path(s.mesh_path).extension() == ".vtm"))
    throw InvalidConfig(in.key_path("crease_angle") + ": creases are marked on the input mesh, which a remeshed or "
                        "saved hierarchy does not keep as its base (leave the key out, or remesh_base_faces: 0)");
  if (s.remesh_base_faces > 0 && s.representation == Representation::Mesh)
    throw InvalidConfig(in.key_path("remesh_base_faces") + ": remeshing needs representation catmull-clark or loop");
  if (s.representation == Representation::Mesh && s.levels > 0)
    throw InvalidConfig(in.key_path("levels") + ": " + std::to_string(s.levels) +
                        " subdivision levels need representation catmull-clark or loop");
}

// A hierarchy given in memory (the Python module's fairshape.edit): it fixes the representation,
// the levels and the subdivision rules, so `input` holds the edit level alone.
void adopt_given_hierarchy(Config& root, const MultiresSurface& h, SurfaceEditSpec& s) {
  Config in = root.child("input", "input geometry");
  s.edit_level = in.get_int("edit_level", -1, -1, 8, "level the deformation is solved on (-1: the finest)");
  in.check_no_unknown_keys();
  s.representation = h.options().scheme == SchemeType::Loop ? Representation::Loop : Representation::CatmullClark;
  s.levels = h.levels();
  s.boundary = h.options().boundary;
  s.loop_weights = h.options().weights;
  s.crease_method = h.options().crease;
  if (s.edit_level > s.levels)
    throw InvalidConfig(in.key_path("edit_level") + ": " + std::to_string(s.edit_level) + " is above the finest level " +
                        std::to_string(s.levels));
}

}  // namespace

// Every key of the run read from `root` (parse_config: unknown keys reported together).
static SurfaceEditSpec read_surface_edit(const YAML::Node& run_config, const Components& c, const std::vector<std::string>& search_dirs, Config& root,
                                         const MultiresSurface* given = nullptr) {
  SurfaceEditSpec s;
  static_cast<RunBasics&>(s) = read_run_basics(root);
  if (given) adopt_given_hierarchy(root, *given, s);
  else read_input(root, search_dirs, s);
  read_energies(root, c, s.implementation, s);
  read_constraints(root, c, s.implementation, s);
  Config pc = root.child("problem", "how the problem is posed");
  s.formulation = pc.get_enum("formulation", Formulation::Displacement, formulation_names(),
                              "unknowns: displacement from the rest shape, or positions");
  // kkt by default: exact. paper (§4.3 as printed) sets the constrained vertices to the
  // minimum-norm values of their propagated rows, which makes spikes on real models; it stays
  // selectable, and its runs say when a vertex moved far beyond the handles (spike_ratio).
  s.constraint_mode = pc.get_enum("constraint_mode", ConstraintMode::Kkt, constraint_mode_names(),
                                  "kkt (default): the exact Lagrange system; paper: least-squares constrained vertices "
                                  "then the solver (§4.3); qr_penalty / range_space: Welch & Witkin's solvers (src/qp)");
  read_accuracy(pc, s);
  refuse_drags_with_regions(pc, s);
  s.constraint_tolerance = pc.get_number(
      "constraint_tolerance", s.constraint_tolerance, 1e-15, 1.0,
      "regional edits: the largest miss of the constraints, measured on the result, × the bounding-box diagonal");
  bool regional = false;
  for (const ConstraintTerm& c : s.constraints) regional |= c.influence.regional();
  s.note_unused(pc, "constraint_tolerance", regional);
  read_rotations(pc, s);
  read_qp_options(pc, s.implementation, s);
  pc.check_no_unknown_keys();
  read_solver(root, c, s.implementation, s);
  read_output(root, s);
  read_steps(root, s);
  // After the unknown-key check: a missing `energy:` is most often a misspelt one, and that
  // message names the misspelling and the valid keys.
  root.check_no_unknown_keys();
  if (s.energies.empty() && !root.documenting()) throw InvalidConfig("energy: at least one energy term is required");

  for (const char* key : {"input", "energy", "constraints", "problem"})
    s.system_key += yaml_to_string(run_config[key]) + "|";
  if (s.scheduled) s.system_key += yaml_to_string(run_config["steps"]) + "|";
  return s;
}

std::vector<OptionDoc> SurfaceEditSpec::keys() {
  return document_keys([](Config& root) { (void)read_surface_edit(YAML::Node(YAML::NodeType::Map), components(), {}, root); });
}

SurfaceEditSpec SurfaceEditSpec::from_config(const YAML::Node& run_config, const Components& c,
                             const std::vector<std::string>& search_dirs) {
  return parse_config(run_config, [&](Config& root) { return read_surface_edit(run_config, c, search_dirs, root); });
}

SurfaceEditSpec SurfaceEditSpec::from_config(const YAML::Node& run_config, const Components& c, const MultiresSurface& given) {
  return parse_config(run_config, [&](Config& root) { return read_surface_edit(run_config, c, {}, root, &given); });
}

}  // namespace fairshape
