#include "fairshape/experiment/kinds/surface_edit/run_one.h"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>
#include <random>

#include "fairshape/core/error.h"
#include "fairshape/core/memory.h"
#include "fairshape/core/timer.h"
#include "fairshape/design/edit_assembly.h"
#include "fairshape/design/orientation_check.h"
#include "fairshape/design/regional_edit.h"
#include "fairshape/experiment/kinds/surface_edit/constraint_overlay.h"
#include "fairshape/experiment/kinds/surface_edit/drag_run.h"
#include "fairshape/experiment/kinds/surface_edit/open_session.h"
#include "fairshape/experiment/kinds/surface_edit/system_export.h"
#include "fairshape/experiment/metric_format.h"
#include "fairshape/experiment/sha256.h"
#include "fairshape/io/mesh_io.h"
#include "fairshape/io/vtk_io.h"
#include "fairshape/design/edit_solve.h"
#include "fairshape/problem/constrained_system.h"
#include "fairshape/problem/least_squares.h"
#include "fairshape/remesh/remesh.h"
#include "fairshape/subdivision/feature_creases.h"
#include "fairshape/subdivision/subdivider.h"

namespace fairshape {
namespace fs = std::filesystem;

namespace {


// A level with the displacement it received and its constrained vertices, for final.obj and VTK.
SurfaceMesh result_mesh(const SurfaceMesh& before, const MatrixX3& after, int level,
                        const DesignConstraints& placed) {
  SurfaceMesh m = before;
  m.positions() = after;
  const Eigen::MatrixXd displacement = after - before.positions();
  m.vertex_data["displacement"] = displacement;
  m.vertex_data["displacement_norm"] = displacement.rowwise().norm();
  // A vertex keeps its id on every finer level (subdivider.h), so a constraint placed on a
  // coarser level marks the same id here.
  Eigen::MatrixXd constrained = Eigen::MatrixXd::Zero(m.n_vertices(), 1);
  for (const auto& p : placed.points)
    if (p.level <= level)
      for (int v : marked_vertices(p)) constrained(v, 0) = 1.0;  // a surface point: its face's corners
  m.vertex_data["constrained"] = constrained;
  if (!placed.normals.empty()) {
    Eigen::MatrixXd normals = Eigen::MatrixXd::Zero(m.n_vertices(), 3);
    for (const auto& n : placed.normals)
      if (n.level <= level) normals.row(n.vertex) = n.normal.normalized().transpose();
    m.vertex_data["target_normal"] = normals;
  }
  return m;
}

// Writes iterations.csv rows and VTK snapshots of the edit level while a solve runs. A row's
// energy is the iterate's, as runs.csv measures the result's (not the objective of the
// reduced system the solver iterates on, whose constant differs from mode to mode).
class IterationSink {
 public:
  IterationSink(const SurfaceEditSpec& spec, const RunOutputs& out, const SurfaceMesh& rest, int level,
                const DesignConstraints& placed, const EditProblem& problem, const Eigen::MatrixXd* reference)
      : spec_(spec), out_(out), rest_(rest), level_(level), placed_(placed), problem_(problem), reference_(reference) {
  }
  bool operator()(const IterationRecord& r) {
    if (spec_.output.iterations)
      out_.add_row("iterations", {std::to_string(r.iteration), num(r.residual),
                                  r.x->rows() == problem_.H.rows() ? num(edit_energy(problem_, *r.x)) : "",
                                  num(r.seconds), reference_ ? num(relative_error(*r.x, *reference_)) : ""});
    if (spec_.output.vtk == VtkPolicy::All && r.iteration % spec_.output.vtk_every == 0) {
      const std::string file = out_.run_id + "_it" + std::to_string(r.iteration) + ".vtp";
      write_vtp(result_mesh(rest_, rest_.positions() + MatrixX3(*r.x), level_, placed_),
                (fs::path(out_.dir) / "vtk" / file).string());
      steps_.emplace_back(r.iteration, file);
    }
    return true;
  }
  void finish() const {
    if (!steps_.empty()) write_pvd(steps_, (fs::path(out_.dir) / "vtk" / (out_.run_id + ".pvd")).string());
  }

 private:
  const SurfaceEditSpec& spec_;
  const RunOutputs& out_;
  const SurfaceMesh& rest_;
  int level_;
  const DesignConstraints& placed_;
  const EditProblem& problem_;
  const Eigen::MatrixXd* reference_;
  std::vector<std::pair<double, std::string>> steps_;
};

// The exact optimum of the same constrained problem — min E subject to every constraint row,
// solved through its KKT system (the optimized LU) whatever constraint_mode the run uses —
// cached per system and drag step: the yardstick of error_vs_reference, energy_vs_optimum and
// the per-iteration error in iterations.csv. The paper's split answers the same problem less
// exactly (constrained vertices at the minimum-norm values of their rows), so it is measured
// against this optimum, not against itself solved more precisely (papers/boier-martin/README.md,
// "One reference per problem"). One factorization serves every step that is missing.
std::vector<const ReferenceSolution*> reference_solutions(const SurfaceEditSpec& spec, RunCache& cache, const EditProblem& p,
                                                         const std::vector<Eigen::MatrixXd>& targets) {
  std::vector<const ReferenceSolution*> refs(targets.size(), nullptr);
  if (!spec.output.reference_solution) return refs;
  // A drag's step k is scale k/N of the configured targets, a scheduled step its own (the
  // schedule is part of the problem key).
  const auto step_name = [&](std::size_t s) {
    return spec.scheduled ? "step " + std::to_string(s + 1) : "scale " + num(*spec.steps[s].scale);
  };
  const auto key = [&](std::size_t s) {
    std::string k = spec.problem_key() + "|optimum";
    return s + 1 == targets.size() ? k : k.append("|").append(step_name(s));
  };
  std::unique_ptr<Solver> direct;
  std::unique_ptr<PreparedEdit> exact;  // factored on the first step the cache lacks
  for (std::size_t s = 0; s < targets.size(); ++s) {
    if (!cache.reference_solution(key(s))) {
      const Timer yardstick;  // the factorization is charged to the first step that needs it
      if (!exact) {
        Config none;
        direct = components().solvers.create("cholesky", Backend::Optimized, none);
        exact = std::make_unique<PreparedEdit>(p, ConstraintMode::Kkt, *direct, Backend::Optimized, spec.qp_config());
      }
      const EditSolution sol = exact->solve(targets[s]);
      if (sol.summary.termination != Termination::Converged) continue;
      cache.store_reference_solution(key(s), {sol.delta, sol.solve_s}, yardstick.seconds(),
                                     std::string("reference solution (the exact optimum, KKT") +
                                         (s + 1 == targets.size() ? ")" : ", drag step " + std::to_string(s + 1) + ")"));
    }
    refs[s] = cache.reference_solution(key(s));
  }
  return refs;
}

// The targets of each of the run's steps, found by applying them to the session without solving;
// the session is left with its configured targets.
std::vector<Eigen::MatrixXd> step_targets(const SurfaceEditSpec& spec, SurfaceEditSession& session) {
  std::vector<Eigen::MatrixXd> targets;
  for (const EditStepSpec& step : spec.steps) {
    apply_step(step, session);
    targets.push_back(session.targets());
  }
  session.scale(1.0);
  return targets;
}

// The paper's split, or §5's ladder, may answer with more energy than the optimum of the same
// problem; above this factor the run says so (measured: papers/boier-martin/README.md, "Paper
// mode against the optimum" — 1.008× for the converged ladder, 2.6× interactive, 2,636× a
// normal constraint's fin).
constexpr double kPaperEnergyFactor = 1.5;

void measure_accuracy(const SurfaceEditSpec& spec, const EditProblem& p, const SurfaceEditStep& step,
                      const ReferenceSolution* ref, MetricRow& row) {
  const EditSolution& sol = step.solution;
  const double energy = step.energy;
  row["energy"] = num(energy);
  row["constraint_violation"] = num(sol.constraint_residual);
  if (!ref) return;
  row["error_vs_reference"] = num(relative_error(sol.delta, ref->u));
  const double optimum = edit_energy(p, ref->u);
  if (!(optimum > 0)) return;
  const double ratio = energy / optimum;
  row["energy_vs_optimum"] = num(ratio);
  const bool paper = spec.constraint_mode == ConstraintMode::Paper || spec.accuracy.multilevel();
  if (paper && ratio > kPaperEnergyFactor)
    row["message"] += std::string(row["message"].empty() ? "" : "; ") + "paper split: energy " + num(ratio) +
                      " times the optimum of the same problem (constraint_mode kkt reaches it)";
}

void write_geometry(const SurfaceEditSpec& spec, const RunOutputs& out, const SurfaceMesh& result, const MultiresSurface& h) {
  if (spec.output.final_mesh) write_mesh(result, out.final_path());
  if (spec.output.vtk == VtkPolicy::None) return;
  write_vtp(result, (fs::path(out.dir) / "vtk" / (out.run_id + ".vtp")).string());
  if (h.levels() > 0) h.save((fs::path(out.dir) / "vtk" / (out.run_id + "_levels.vtm")).string());
}

// Figure 8 (d–f): each level of the ladder with its deformation and the vertices the
// propagated constraints reach there.
void write_ladder(const SurfaceEditSpec& spec, const RunOutputs& out, const MultiresSurface& rest, const EditLadder& ladder,
                  int coarse, const std::vector<Eigen::MatrixXd>& solutions) {
  if (spec.output.vtk == VtkPolicy::None) return;
  for (std::size_t k = 0; k < solutions.size(); ++k) {
    if (solutions[k].size() == 0) continue;  // a level the mode did not solve on
    const int l = coarse + static_cast<int>(k);
    SurfaceMesh m = rest.mesh(l);
    m.positions() += MatrixX3(solutions[k]);
    m.vertex_data["displacement_norm"] = solutions[k].rowwise().norm();
    const SparseMatrix& A = ladder.problems[k].constraints.A;
    Eigen::MatrixXd constrained = Eigen::MatrixXd::Zero(m.n_vertices(), 1);
    for (int v : reached_columns(A)) constrained(v, 0) = 1.0;
    m.vertex_data["constrained"] = constrained;
    write_vtp(m, (fs::path(out.dir) / "vtk" / (out.run_id + "_ladder_level" + std::to_string(l) + ".vtp")).string());
  }
}

// A vertex moving this many times the largest handle is a spike.
constexpr double kSpikeRatio = 1.5;
// In an exact solve of an energy of the deformation the constrained points pull the rest along,
// so no vertex moves much beyond the handles (measured: at most 5.0 over the cow's figures and
// six other models, mushroom the highest); ten times is the answer of conflicting rows (372,578 on a
// curve along an open patch's boundary whose long boundary edges reach into a fixed region).
constexpr double kIllConditionedRatio = 10.0;

// spike_ratio: the largest displacement of an edit-level vertex over the largest handle
// offset (empty without a moving handle). Near 1 for an exact solve of an energy of the
// displacement; paper mode freezes the constrained vertices at the minimum-norm values of
// their rows, which spike (2–3× on the cow), and its runs then say so. An energy of positions
// (the thin plate of P_rest + ΔP) also moves vertices by flattening the details — that
// energy's answer, not a spike — so its ratio is reported without a warning.
void report_spike(const SurfaceEditSpec& spec, const DesignConstraints& placed, const Eigen::MatrixXd& delta,
                  MetricRow& row) {
  double handle = 0;
  for (const PointConstraint& c : placed.points) handle = std::max(handle, c.offset.norm());
  if (!(handle > 0) || delta.rows() == 0) return;
  const double ratio = delta.rowwise().norm().maxCoeff() / handle;
  row["spike_ratio"] = num(ratio);
  const EditTerms terms = spec.edit_terms();
  bool of_displacement = !terms.positions;
  for (const WeightedEnergy& e : terms.energies) of_displacement &= !e.energy->measures_positions();
  const bool paper = spec.constraint_mode == ConstraintMode::Paper || spec.accuracy.multilevel();
  const auto say = [&row](const std::string& what) { row["message"] += (row["message"].empty() ? "" : "; ") + what; };
  if (paper && of_displacement && ratio > kSpikeRatio)
    say("spike: a vertex moved " + num(ratio) +
        " times the largest handle (paper mode sets constrained vertices to the minimum-norm values of their "
        "propagated rows; constraint_mode kkt is exact)");
  if (!paper && of_displacement && ratio > kIllConditionedRatio && row["termination"] == to_string(Termination::Converged)) {
    row["termination"] = std::string(to_string(Termination::IllConditioned));
    say("ill-conditioned constraints: the exact answer moves a vertex " + num(ratio) +
        " times the largest handle, so nearly dependent rows have conflicting targets (constrained points "
        "close together asked to move apart, or a handle whose surface point depends mostly on fixed vertices)");
  }
}

// flipped_faces and normal_error_deg, measured on the result whatever the solver certified:
// a fold or a normal met by its reverse is never a success (design/orientation_check.h).
void report_orientation(const OrientationCheck& c, MetricRow& row) {
  row["flipped_faces"] = std::to_string(c.folds.flipped.size());
  if (c.normal_error_deg >= 0) row["normal_error_deg"] = num(c.normal_error_deg);
  if (!c.folded()) return;
  row["message"] += (row["message"].empty() ? "" : "; ") + c.describe();
  if (is_success(termination_from_string(row["termination"]))) row["termination"] = std::string(to_string(Termination::Folded));
}

// curve_points: the vertices the curves snapped, or their points on the limit surface (the
// VTP's `constrained` marks the vertices they use).
void count_curve_points(const DesignConstraints& placed, MetricRow& row) {
  if (placed.curves.empty()) return;
  std::size_t snapped = 0;
  for (const PlacedCurve& c : placed.curves) snapped += c.vertices.size() + c.samples.size();  // snapped or on the limit
  row["curve_points"] = std::to_string(snapped);
}

// What every edit reports of its result and writes: the detail change (the edited finest
// level re-analysed), the spike ratio, the session's orientation check, the geometry and the
// constraints' overlay. `region` (regional edits): the finest level's influence_region array.
OrientationCheck report_result(const SurfaceEditSpec& spec, const RunOutputs& out, const MultiresSurface& rest,
                               const MultiresSurface& edited, const DesignConstraints& placed, const Eigen::MatrixXd& delta,
                               const Eigen::VectorXi* region, const OrientationCheck& orientation, MetricRow& row) {
  const SurfaceMesh& finest = edited.mesh(edited.levels());
  // The edited surface analysed anew: its details are what the edit left of the rest
  // shape's (synthesize_from keeps the rest details, whatever the energy did to them).
  const MultiresSurface reanalysed =
      rest.levels() > 0 ? MultiresSurface::analyze(rest.mesh(0), finest.positions(), rest.options(), rest.levels(),
                                                   spec.implementation)
                        : edited;
  const double change = relative_detail_change(rest, reanalysed);
  row["detail_change"] = std::isnan(change) ? "" : num(change);
  report_spike(spec, placed, delta, row);
  for (const PlacedCurve& c : placed.curves)  // a curve placed otherwise than asked says how
    if (!c.note.empty()) row["message"] += (row["message"].empty() ? "" : "; ") + c.note;
  report_orientation(orientation, row);
  SurfaceMesh result = result_mesh(rest.mesh(rest.levels()), finest.positions(), rest.levels(), placed);
  if (region) result.vertex_data["influence_region"] = region->cast<double>();
  mark_flipped(result, orientation.folds);
  write_geometry(spec, out, result, reanalysed);
  if (spec.output.vtk != VtkPolicy::None)
    write_constraint_overlay(placed, edited, (fs::path(out.dir) / "vtk" / (out.run_id + "_constraints.vtp")).string());
  return orientation;
}

// Constraints with regions of influence of their own (design/regional_edit.h): solved in
// passes, coarse to fine; the yardstick is the same passes with CHOLMOD on the free vertices.
OrientationCheck execute_regional(SurfaceEditSpec& spec, RunCache& cache, const RunOutputs& out,
                                  const MultiresSurface& rest, int level, MetricRow& row) {
  const EditTerms terms = spec.edit_terms();
  // Under §5's ladder the whole-level passes are solved on it (design/regional_edit.h).
  const std::unique_ptr<SurfaceEditSession> session = open_session(spec, borrowed(rest), false);
  const double before_solve_mb = trimmed_rss_mb();
  reset_peak_rss();
  if (spec.output.system)
    throw InvalidInput("output.system: an edit with regions of influence solves one system per pass (design/regional_edit.h); "
                       "writing them is not supported: set output.system: false");
  const SurfaceEditStep r = session->solve();
  const double solve_peak_mb = peak_rss_mb();
  row["peak_rss_mb"] = num(solve_peak_mb);
  row["solve_extra_mb"] = num(solve_peak_mb - before_solve_mb);
  int unknowns = 0;
  for (const RegionalPass& p : r.passes) unknowns += p.unknowns;
  row["n_dofs"] = std::to_string(unknowns);
  row["n_fine"] = std::to_string(rest.mesh(rest.levels()).n_vertices());
  const SolveSummary& summary = r.solution.summary;  // the solver's; the run's own checks are added below
  row["analyze_s"] = num(r.solution.analyze_s);
  row["solve_s"] = num(r.solution.solve_s);
  row["solve_min_s"] = num(r.solution.solve_s);
  row["iterations"] = std::to_string(summary.iterations);
  row["residual"] = num(summary.residual);
  row["constraint_violation"] = num(r.constraint_residual);
  row["termination"] = std::string(to_string(summary.termination));
  row["message"] = summary.message;
  if (r.passes.size() != 0 && !is_success(summary.termination)) return {};
  const int finest = rest.levels();
  const MultiresSurface& edited = session->current();
  const Eigen::MatrixXd moved = edited.mesh(finest).positions() - rest.mesh(finest).positions();
  row["region_fraction"] = num((r.region.array() > 0).count() / static_cast<double>(r.region.size()));
  const double largest = moved.rowwise().norm().maxCoeff();
  row["moved_fraction"] =
      num((moved.rowwise().norm().array() > 1e-12 * largest).count() / static_cast<double>(moved.rows()));
  row["outside_region_move"] = num(r.outside_region_move);
  count_curve_points(session->placed(), row);
  row["energy"] = num(r.energy);  // of the whole deformation on the edit level
  if (spec.output.reference_solution) {
    const std::string key = spec.problem_key() + "|regional optimum";
    if (!cache.reference_solution(key)) {
      // The yardstick: the same passes solved exactly (KKT, CHOLMOD) — whatever mode or ladder
      // the run uses, each pass is the same constrained problem (one reference per problem).
      Config none_cfg;
      const auto direct = components().solvers.create("cholesky", Backend::Optimized, none_cfg);
      const Timer yardstick;
      const RegionalEditResult ref = solve_regional_edit(terms, rest, level, ConstraintMode::Kkt, *direct, Backend::Optimized,
                                                         spec.qp_config(), spec.constraint_tolerance, nullptr);
      if (is_success(ref.summary.termination))
        cache.store_reference_solution(key, {ref.edited.mesh(finest).positions() - rest.mesh(finest).positions(), ref.solve_s},
                                       yardstick.seconds(), "reference solution of the regional passes (the exact optimum, KKT)");
    }
    if (const ReferenceSolution* ref = cache.reference_solution(key)) row["error_vs_reference"] = num(relative_error(moved, ref->u));
  }
  return report_result(spec, out, rest, edited, session->placed(), moved, &r.region, r.orientation, row);
}

// time_s: the run's own time. The shared work done during it (a hierarchy, a reference solve)
// is left out and written to setup.csv; setup_ids names all the shared work the run used.
void charge_shared_setups(RunCache& cache, const RunOutputs& out, const Timer& total, MetricRow& row) {
  const double wall = total.seconds();  // one clock read: time_s never exceeds the run's wall time
  const RunCache::Setups setups = cache.take_setups();
  double shared = 0;
  for (const SharedSetup& s : setups.built) {
    shared += s.seconds;
    out.add_row("setup", {s.id, s.what, num(s.seconds)});
  }
  std::string ids;
  for (const std::string& id : setups.used) ids.append(ids.empty() ? "" : " ").append(id);
  row["setup_ids"] = ids;
  row["time_s"] = num(std::max(0.0, wall - shared));
}

}  // namespace

const std::vector<std::string>& step_columns() {
  static const std::vector<std::string> cols{"step",       "scale",           "accuracy",
                                             "solve_s",    "iterations",      "error_vs_reference",
                                             "constraint_violation", "reference_solve_s", "flipped_faces", "check_s"};
  return cols;
}

const std::vector<std::string>& setup_columns() {
  static const std::vector<std::string> cols{"setup_id", "setup", "setup_s"};
  return cols;
}

const std::vector<std::string>& iteration_columns() {
  static const std::vector<std::string> cols{"iteration", "residual", "energy", "seconds", "error_vs_reference"};
  return cols;
}

const std::vector<std::string>& metric_columns() {
  static const std::vector<std::string> cols{
      "n_dofs", "n_fine", "n_constrained", "repeat", "setup_ids", "assemble_s", "analyze_s", "solve_s", "solve_min_s",
      "time_s", "iterations", "residual", "error_estimate", "energy", "constraint_violation", "error_vs_reference", "energy_vs_optimum", "detail_change", "spike_ratio",
      "flipped_faces", "normal_error_deg", "curve_points",
      "region_fraction", "moved_fraction", "outside_region_move", "rotation_rounds",
      "remesh_hausdorff", "remesh_edge_ratio", "peak_rss_mb", "solve_extra_mb", "unused_keys", "termination", "message"};
  return cols;
}

namespace {

// How the hierarchy is built from its input file (the key and the id add the file).
std::string hierarchy_options(const SurfaceEditSpec& spec) {
  const bool subdivided = spec.representation != Representation::Mesh;
  return (subdivided ? std::string(to_string(spec.subdivision().scheme)) : std::string("mesh")) +
         "|" + std::to_string(spec.levels) + "|" + std::string(to_string(spec.boundary)) + "|" +
         std::string(to_string(spec.loop_weights)) + "|" + std::string(to_string(spec.crease_method)) + "|" +
         std::to_string(spec.remesh_base_faces) + (spec.remesh_triangle_base ? "t" : "") + "|" +
         std::string(to_string(spec.implementation)) + "|" + std::to_string(spec.crease_angle);
}

std::string reference_id(const std::string& key) { return "reference-" + sha256_hex(key).substr(0, 12); }

std::string what_hierarchy(const SurfaceEditSpec& spec) {
  if (fs::path(spec.mesh_path).extension() == ".vtm") return "hierarchy loaded from " + spec.mesh_path;
  std::string what = spec.remesh_base_faces > 0 ? "remesh of " : "hierarchy of ";
  what += spec.mesh_path;
  if (spec.representation != Representation::Mesh)
    what += ", " + std::string(to_string(spec.subdivision().scheme)) + ", " + std::to_string(spec.levels) + " levels";
  return what;
}

}  // namespace

RunCache::Setups RunCache::take_setups() { return std::exchange(setups_, {}); }

void RunCache::use(const std::string& id) {
  if (std::find(setups_.used.begin(), setups_.used.end(), id) == setups_.used.end()) setups_.used.push_back(id);
}

const MultiresSurface& RunCache::hierarchy(const SurfaceEditSpec& spec, const RemeshReport** made) {
  const bool subdivided = spec.representation != Representation::Mesh;
  const std::string key = spec.mesh_path + "|" + hierarchy_options(spec);
  // The id names the work by the input's content, not its path: the same hierarchy has the
  // same id in every folder and clone.
  std::string& id = hierarchy_ids_[key];
  if (id.empty()) id = "hierarchy-" + sha256_hex(sha256_file_hex(spec.mesh_path) + "|" + hierarchy_options(spec)).substr(0, 12);
  use(id);
  auto it = hierarchies_.find(key);
  if (it == hierarchies_.end() && fs::path(spec.mesh_path).extension() == ".vtm") {  // saved: its details kept
    Timer t;
    MultiresSurface h = MultiresSurface::load(spec.mesh_path, spec.implementation);
    it = hierarchies_.emplace(key, std::move(h)).first;
    setups_.built.push_back({id, what_hierarchy(spec), t.seconds()});
  }
  if (it == hierarchies_.end()) {
    Timer t;  // reading the mesh included
    SurfaceMesh input = read_mesh(spec.mesh_path);
    if (subdivided && spec.crease_angle > 0) mark_feature_creases(input, spec.crease_angle);
    if (spec.remesh_base_faces > 0 && input.has_sharpness())  // the remeshed base has other edges
      throw InvalidInput("its crease/corner tags would be lost: remeshing (input.remesh_base_faces) builds a new "
                         "base mesh; use remesh_base_faces: 0 to keep them");
    SubdivisionOptions opt;
    if (subdivided) opt = spec.subdivision();
    RemeshOptions ropt;
    ropt.subdivision = opt;
    ropt.base_faces = spec.remesh_base_faces;
    ropt.levels = spec.levels;
    ropt.backend = spec.implementation;
    if (spec.remesh_triangle_base) ropt.base = RemeshBase::Triangles;
    RemeshReport report;
    UniformRefineLimits limits;
    limits.max_bytes = spec.max_memory_gb * double(1ull << 30);
    MultiresSurface h = spec.remesh_base_faces > 0 ? remesh(input, ropt, &report)
                                                   : MultiresSurface(input, opt, spec.levels, spec.implementation, limits);
    if (spec.remesh_base_faces > 0) {
      remesh_reports_[key] = report;
      // The numbers go into runs.csv; a missed quality target is also said, once per remesh.
      for (const auto& m : report.misses()) std::cerr << "warning: remesh " << spec.mesh_path << ": " << m << "\n";
    }
    it = hierarchies_.emplace(key, std::move(h)).first;
    setups_.built.push_back({id, what_hierarchy(spec), t.seconds()});
  }
  if (made) {
    const auto r = remesh_reports_.find(key);
    *made = r == remesh_reports_.end() ? nullptr : &r->second;
  }
  return it->second;
}

const ReferenceSolution* RunCache::reference_solution(const std::string& key) {
  auto it = references_.find(key);
  if (it == references_.end()) return nullptr;
  use(reference_id(key));
  return &it->second;
}

void RunCache::store_reference_solution(const std::string& key, ReferenceSolution r, double seconds, std::string what) {
  references_[key] = std::move(r);
  setups_.built.push_back({reference_id(key), std::move(what), seconds});
}

namespace {

// One solve of the run's edit; `checked`: what its result's orientation check found.
MetricRow attempt_run(SurfaceEditSpec& spec, RunCache& cache, const RunOutputs& out, OrientationCheck& checked) {
  MetricRow row;
  for (const auto& c : metric_columns()) row[c] = "";
  row["unused_keys"] = spec.unused_keys_cell();
  reset_peak_rss();
  Timer total;
  try {
    const RemeshReport* remeshed = nullptr;
    const MultiresSurface& rest = cache.hierarchy(spec, &remeshed);
    if (remeshed) {  // the remesh made for this run (a saved hierarchy's is in its _remesh.json)
      row["remesh_hausdorff"] = num(remeshed->hausdorff_relative());
      row["remesh_edge_ratio"] = num(remeshed->edge_ratio());
    }
    const int level = spec.edit_level < 0 ? rest.levels() : spec.edit_level;
    if (is_regional(spec.edit_terms())) {
      checked = execute_regional(spec, cache, out, rest, level, row);
      charge_shared_setups(cache, out, total, row);
      return row;
    }
    Timer t;
    // The run's session (design/surface_edit_session.h): it solves each step and checks each
    // result; this run writes what it found. A reversed normal is solved again by execute_run,
    // so that each attempt writes its own files.
    const std::unique_ptr<SurfaceEditSession> session = open_session(spec, borrowed(rest), false);
    const EditProblem& problem = session->problem();
    const DesignConstraints& placed = session->placed();
    row["assemble_s"] = num(t.seconds());
    row["n_dofs"] = std::to_string(problem.H.rows());
    row["n_fine"] = std::to_string(rest.mesh(rest.levels()).n_vertices());
    row["n_constrained"] = std::to_string(problem.constraints.A.rows() + problem.constraints.A_coupled.rows());
    count_curve_points(placed, row);
    // A rotation-aware edit is its own yardstick (its rounds stop at a tolerance): the linear
    // solve would measure how far the rotations went, not an error.
    const auto references = spec.rotations.iterations > 0
                                ? std::vector<const ReferenceSolution*>(spec.steps.size(), nullptr)
                                : reference_solutions(spec, cache, problem, step_targets(spec, *session));
    const ReferenceSolution* reference = references.back();
    // peak_rss_mb: the solve's peak (analysis included), not the yardstick's; solve_extra_mb:
    // that peak above what the process held before it (the hierarchy, H, the constraints), i.e.
    // what the solver itself allocates — CHOLMOD's factor, the multigrid levels.
    const double before_solve_mb = trimmed_rss_mb();
    reset_peak_rss();
    IterationSink sink(spec, out, rest.mesh(level), level, placed, problem, reference ? &reference->u : nullptr);
    const IterationCallback cb = std::ref(sink);
    // output.vtk: all records the steps of a drag or schedule: each step's surface, for a strip
    // (Figure 9, bottom).
    const bool stepwise = spec.accuracy.multilevel() || spec.scheduled;
    std::vector<std::pair<double, std::string>> vtk_steps;
    const StepCallback write_step = [&](int step, const SurfaceEditSession& s) {
      const std::string file = out.run_id + "_step" + std::to_string(step) + ".vtp";
      write_vtp(result_mesh(rest.mesh(rest.levels()), s.current().mesh(rest.levels()).positions(), rest.levels(), placed),
                (fs::path(out.dir) / "vtk" / file).string());
      vtk_steps.emplace_back(step, file);
    };
    const StepsOutcome steps = run_steps(spec, out, *session, references, cb, stepwise,
                                         stepwise && spec.output.vtk == VtkPolicy::All ? write_step : StepCallback());
    if (!vtk_steps.empty()) write_pvd(vtk_steps, (fs::path(out.dir) / "vtk" / (out.run_id + "_steps.pvd")).string());
    const std::string& folded_on_the_way = steps.folded_steps;  // a drag's earlier steps that folded
    const EditSolution& sol = steps.last.solution;
    if (spec.rotations.iterations > 0) row["rotation_rounds"] = std::to_string(steps.last.rotation_rounds);
    sink.finish();
    const double solve_peak_mb = peak_rss_mb();
    if (spec.output.system) {
      // The reduced system is the single-level paper split's: the ladder and rotation rounds solve others.
      const bool split = spec.constraint_mode == ConstraintMode::Paper && !spec.accuracy.multilevel() &&
                         spec.rotations.iterations == 0 && sol.delta.allFinite() && is_success(sol.summary.termination);
      write_edit_system(problem, rest, level, (fs::path(out.dir) / "system" / out.run_id).string(), split ? &sol.delta : nullptr);
    }
    row["peak_rss_mb"] = num(solve_peak_mb);
    row["solve_extra_mb"] = num(solve_peak_mb - before_solve_mb);
    row["analyze_s"] = num(sol.analyze_s);
    row["solve_s"] = num(sol.solve_s);
    row["solve_min_s"] = num(sol.solve_s);  // over the repeats: the harness's (experiment/repeats.h)
    row["iterations"] = std::to_string(sol.summary.iterations);
    row["residual"] = num(sol.summary.residual);
    if (sol.summary.error_estimate >= 0) row["error_estimate"] = num(sol.summary.error_estimate);
    row["termination"] = std::string(to_string(sol.summary.termination));
    row["message"] = sol.summary.message;
    if (!folded_on_the_way.empty())
      row["message"] += (row["message"].empty() ? "" : "; ") + ("drag steps folded on the way: " + folded_on_the_way);
    if (sol.delta.allFinite() && sol.summary.termination != Termination::NumericalFailure) {
      measure_accuracy(spec, problem, steps.last, reference, row);
      checked = report_result(spec, out, rest, session->current(), placed, sol.delta, nullptr, steps.last.orientation, row);
      write_ladder(spec, out, rest, session->ladder(), session->coarse_level(), session->level_solutions());
    }
  } catch (const SolverError& e) {
    row["termination"] = std::string(to_string(Termination::NumericalFailure));
    row["message"] = e.what();
  } catch (const OutputError& e) {  // results incomplete: not a finished run
    row["termination"] = std::string(to_string(Termination::OutputFailed));
    row["message"] = e.what();
  } catch (const Error& e) {  // a problem of the input validation could not see without H
    row["termination"] = std::string(to_string(Termination::InvalidInput));
    row["message"] = std::string("in the assembled problem: ") + e.what();
  }
  charge_shared_setups(cache, out, total, row);
  if (row["peak_rss_mb"].empty()) row["peak_rss_mb"] = num(peak_rss_mb());  // a run that failed before or in its solve
  return row;
}

}  // namespace

MetricRow execute_run(SurfaceEditSpec& spec, RunCache& cache, const RunOutputs& out) {
  // A normal left to rows `auto` and met by its reverse: the edit is solved again with frame
  // rows (papers/boier-martin/README.md, "Folds and reversed normals"); the second solve's
  // files replace the first's, and its row counts both solves' time.
  MetricRow row;
  double earlier_s = 0;
  const std::string note = solve_orienting_normals([&](bool frame_rows) {
    if (frame_rows) earlier_s = std::stod(row["time_s"]);
    spec.frame_rows_for_auto_normals = frame_rows;
    OrientationCheck checked;
    row = attempt_run(spec, cache, out, checked);
    return checked;
  });
  spec.frame_rows_for_auto_normals = false;
  if (note.empty()) return row;
  row["time_s"] = num(earlier_s + (row["time_s"].empty() ? 0.0 : std::stod(row["time_s"])));
  row["message"] = noted(note + (spec.output.iterations ? " (iterations.csv holds both solves)" : ""), row["message"]);
  return row;
}

}  // namespace fairshape
