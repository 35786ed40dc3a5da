#include "experiment/run_one.h"

#include <algorithm>
#include <filesystem>
#include <random>
#include <sstream>

#include "core/error.h"
#include "core/memory.h"
#include "core/timer.h"
#include "io/csv.h"
#include "io/mesh_io.h"
#include "io/vtk_io.h"
#include "problem/constrained_system.h"
#include "subdivision/subdivider.h"

namespace fairshape {
namespace fs = std::filesystem;
namespace {

std::string num(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

ConstrainedSystem assemble(const RunSpec& spec, const SurfaceMesh& rest) {
  const int n = rest.n_vertices();
  ConstrainedSystem sys;
  sys.H.resize(n, n);
  sys.g = Eigen::MatrixXd::Zero(n, 3);
  for (const auto& e : spec.energies) {
    Triplets t;
    e.energy->add_hessian(rest, e.weight, t);
    SparseMatrix He(n, n);
    He.setFromTriplets(t.begin(), t.end());
    if (e.energy->measures_positions()) sys.g -= He * rest.positions();  // E(P_rest + u)
    sys.H += He;
  }
  PrescribedValues prescribed;
  for (const auto& c : spec.constraints) c.constraint->prescribe(rest, prescribed);
  // Nothing pinned and H·1 = 0: the minimizer is defined only up to a translation.
  if (prescribed.values().empty() && (sys.H * Eigen::VectorXd::Ones(n)).norm() <= 1e-12 * sys.H.norm())
    throw InvalidInput("the problem is singular: no vertex is fixed or moved, and the energy is invariant under "
                       "translation (add a 'fixed' or 'position' constraint)");
  sys.fixed_values.resize(static_cast<Eigen::Index>(prescribed.values().size()), 3);
  Eigen::Index k = 0;
  for (const auto& [v, value] : prescribed.values()) {
    sys.fixed.push_back(v);
    const Vec3 target = spec.formulation == Formulation::Position ? Vec3(rest.position(v) + value) : value;
    sys.fixed_values.row(k++) = target.transpose();
  }
  return sys;
}

Eigen::MatrixXd initial_guess(const RunSpec& spec, const ReducedSystem& red, const SurfaceMesh& rest) {
  const Eigen::Index n = static_cast<Eigen::Index>(red.free.size());
  if (spec.initial_guess == "random") {
    std::mt19937_64 gen(static_cast<std::uint64_t>(spec.seed));
    std::uniform_real_distribution<double> d(-1.0, 1.0);
    Eigen::MatrixXd x(n, 3);
    for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = d(gen);
    return x;
  }
  if (spec.formulation == Formulation::Position) return red.restrict_to_free(rest.positions());
  return Eigen::MatrixXd::Zero(n, 3);
}

SurfaceMesh result_mesh(const SurfaceMesh& rest, const Eigen::MatrixXd& u, const ConstrainedSystem& sys,
                        Formulation f) {
  SurfaceMesh m = rest;
  const Eigen::MatrixXd displacement = f == Formulation::Position ? Eigen::MatrixXd(u - rest.positions()) : u;
  m.positions() = rest.positions() + displacement;
  m.vertex_data["displacement"] = displacement;
  m.vertex_data["displacement_norm"] = displacement.rowwise().norm();
  Eigen::MatrixXd constrained = Eigen::MatrixXd::Zero(rest.n_vertices(), 1);
  for (int v : sys.fixed) constrained(v, 0) = 1.0;
  m.vertex_data["constrained"] = constrained;
  return m;
}

// Writes iterations.csv rows and VTK snapshots while a solve runs.
class IterationSink {
 public:
  IterationSink(const RunSpec& spec, const RunOutputs& out, const SurfaceMesh& rest, const ConstrainedSystem& sys,
                const ReducedSystem& red)
      : spec_(spec), out_(out), rest_(rest), sys_(sys), red_(red) {
    if (spec.output.iterations) csv_ = std::make_unique<CsvAppender>((fs::path(out.dir) / "iterations.csv").string());
  }
  bool operator()(const IterationRecord& r) {
    if (csv_) csv_->append({out_.run_id, std::to_string(r.iteration), num(r.residual), num(r.seconds)});
    if (spec_.output.vtk == "every_iteration" && r.iteration % spec_.output.vtk_every == 0) {
      const std::string file = out_.run_id + "_it" + std::to_string(r.iteration) + ".vtp";
      write_vtp(result_mesh(rest_, red_.expand(*r.x), sys_, spec_.formulation),
                (fs::path(out_.dir) / "vtk" / file).string());
      steps_.emplace_back(r.iteration, file);
    }
    return true;
  }
  void finish() const {
    if (!steps_.empty()) write_pvd(steps_, (fs::path(out_.dir) / "vtk" / (out_.run_id + ".pvd")).string());
  }

 private:
  const RunSpec& spec_;
  const RunOutputs& out_;
  const SurfaceMesh& rest_;
  const ConstrainedSystem& sys_;
  const ReducedSystem& red_;
  std::unique_ptr<CsvAppender> csv_;
  std::vector<std::pair<double, std::string>> steps_;
};

void measure_accuracy(const RunSpec& spec, RunCache& cache, const ConstrainedSystem& sys, const ReducedSystem& red,
                      const Eigen::MatrixXd& u, MetricRow& row) {
  row["energy"] = num(energy(sys, u));
  double violation = 0;
  for (std::size_t k = 0; k < sys.fixed.size(); ++k)
    violation = std::max(violation, (u.row(sys.fixed[k]) - sys.fixed_values.row(static_cast<Eigen::Index>(k))).norm());
  row["constraint_violation"] = num(violation);
  if (!spec.output.reference_solution) return;
  const Eigen::MatrixXd* ref = cache.reference_solution(spec.system_key);
  if (!ref) {
    Config none;
    auto direct = components().solvers.create("cholesky", Backend::Reference, none);
    Eigen::MatrixXd x;
    direct->analyze(red.A);
    if (direct->solve(red.A, red.b, x).termination != Termination::Converged) return;
    cache.store_reference_solution(spec.system_key, red.expand(x));
    ref = cache.reference_solution(spec.system_key);
  }
  const double scale = ref->norm() > 0 ? ref->norm() : 1.0;
  row["error_vs_reference"] = num((u - *ref).norm() / scale);
}

void write_geometry(const RunSpec& spec, const RunOutputs& out, const SurfaceMesh& result) {
  if (spec.output.final_mesh) {
    fs::path p = fs::path(out.dir) / "final.obj";
    if (!out.single_run) {
      fs::create_directories(fs::path(out.dir) / "final");
      p = fs::path(out.dir) / "final" / (out.run_id + ".obj");
    }
    write_mesh(result, p.string());
  }
  if (spec.output.vtk != "none") write_vtp(result, (fs::path(out.dir) / "vtk" / (out.run_id + ".vtp")).string());
}

}  // namespace

const std::vector<std::string>& metric_columns() {
  static const std::vector<std::string> cols{
      "n_dofs", "n_fine", "n_constrained", "repeat", "subdivide_s", "assemble_s", "analyze_s", "solve_s", "solve_min_s",
      "time_s", "iterations", "residual", "energy", "constraint_violation", "error_vs_reference",
      "peak_rss_mb", "termination", "message"};
  return cols;
}

const SurfaceMesh& RunCache::surface(const RunSpec& spec, double* build_s) {
  const std::string key = spec.mesh_path + "|" + spec.representation + "|" + std::to_string(spec.levels) + "|" +
                          spec.boundary + "|" + spec.loop_weights + "|" + std::string(to_string(spec.implementation));
  auto it = surfaces_.find(key);
  if (it == surfaces_.end()) {
    SurfaceMesh m = read_mesh(spec.mesh_path);
    Timer t;
    if (spec.levels > 0) {
      const SubdivisionOptions opt{scheme_from_string(spec.representation), boundary_from_string(spec.boundary),
                                   loop_weights_from_string(spec.loop_weights)};
      m = refine_uniform(m, opt, spec.levels, spec.implementation).back();
    }
    it = surfaces_.emplace(key, std::make_pair(std::move(m), t.seconds())).first;
  }
  *build_s = it->second.second;
  return it->second.first;
}

const Eigen::MatrixXd* RunCache::reference_solution(const std::string& key) const {
  auto it = references_.find(key);
  return it == references_.end() ? nullptr : &it->second;
}

void RunCache::store_reference_solution(const std::string& key, Eigen::MatrixXd u) { references_[key] = std::move(u); }

MetricRow execute_run(RunSpec& spec, RunCache& cache, const RunOutputs& out) {
  MetricRow row;
  for (const auto& c : metric_columns()) row[c] = "";
  row["repeat"] = std::to_string(spec.repeat);
  reset_peak_rss();
  Timer total;
  try {
    double subdivide_s = 0;
    const SurfaceMesh& rest = cache.surface(spec, &subdivide_s);
    row["subdivide_s"] = num(subdivide_s);
    Timer t;
    const ConstrainedSystem sys = assemble(spec, rest);
    const ReducedSystem red = reduce(sys);
    row["assemble_s"] = num(t.seconds());
    row["n_dofs"] = std::to_string(red.free.size());
    row["n_fine"] = std::to_string(rest.n_vertices());
    row["n_constrained"] = std::to_string(sys.fixed.size());
    t.reset();
    spec.solver->analyze(red.A);
    row["analyze_s"] = num(t.seconds());
    const Eigen::MatrixXd x0 = initial_guess(spec, red, rest);
    IterationSink sink(spec, out, rest, sys, red);
    std::vector<double> times;
    SolveSummary summary;
    Eigen::MatrixXd x;
    for (int r = 0; r < spec.repeat; ++r) {
      x = x0;
      t.reset();
      summary = spec.solver->solve(red.A, red.b, x, r == 0 ? IterationCallback(std::ref(sink)) : IterationCallback());
      times.push_back(t.seconds());
    }
    sink.finish();
    row["solve_s"] = num(median(times));
    row["solve_min_s"] = num(*std::min_element(times.begin(), times.end()));
    row["iterations"] = std::to_string(summary.iterations);
    row["residual"] = num(summary.residual);
    row["termination"] = std::string(to_string(summary.termination));
    row["message"] = summary.message;
    if (x.allFinite() && summary.termination != Termination::NumericalFailure) {
      const Eigen::MatrixXd u = red.expand(x);
      measure_accuracy(spec, cache, sys, red, u, row);
      write_geometry(spec, out, result_mesh(rest, u, sys, spec.formulation));
    }
  } catch (const SolverError& e) {
    row["termination"] = std::string(to_string(Termination::NumericalFailure));
    row["message"] = e.what();
  } catch (const Error& e) {  // the input: files, topology, constraints
    row["termination"] = std::string(to_string(Termination::InvalidInput));
    row["message"] = e.what();
  }
  row["time_s"] = num(total.seconds());
  row["peak_rss_mb"] = num(peak_rss_mb());
  return row;
}

}  // namespace fairshape
