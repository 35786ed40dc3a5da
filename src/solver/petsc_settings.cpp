#include "fairshape/solver/petsc_settings.h"

#include <cctype>
#include <sstream>

#include <nlohmann/json.hpp>

#include "fairshape/core/name_table.h"

namespace fairshape::petsc {
namespace {

const NameTable<MultigridOptions::CoarseSpace>& coarse_spaces() {
  static const NameTable<MultigridOptions::CoarseSpace> t{{MultigridOptions::CoarseSpace::Nested, "nested"},
                                                          {MultigridOptions::CoarseSpace::Truncated, "truncated"},
                                                          {MultigridOptions::CoarseSpace::Conforming, "conforming"}};
  return t;
}

std::vector<std::string> words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// A PETSc option name is "-name"; a value is anything else (a negative number is a value).
bool is_option_name(const std::string& w) {
  return w.size() > 1 && w[0] == '-' && !(std::isdigit(static_cast<unsigned char>(w[1])) || w[1] == '.');
}

}  // namespace

std::string Settings::solver_name() const {
  switch (preconditioner) {
    case Preconditioner::Mg: return "petsc_mg";
    case Preconditioner::Gamg: return "petsc_gamg";
    case Preconditioner::BoomerAmg: return "petsc_boomeramg";
  }
  return "petsc";
}

Settings Settings::from_config(Config& cfg, Preconditioner preconditioner) {
  Settings s;
  s.preconditioner = preconditioner;
  s.iterative = IterativeOptions::from_config(cfg);
  const std::string name = s.solver_name();
  if (s.iterative.check_every != 1)
    s.refusals.push_back(cfg.key_path("check_every") + ": " + name + " checks its residual every iteration (PETSc's KSP)");
  // Each solver's own block (petsc_mg: {...}), as sor: and multigrid: are: every registered
  // solver reads the solver block, so a key's validity cannot depend on which one is chosen.
  Config own = cfg.child(name, "options of the " + name + " solver");
  if (preconditioner == Preconditioner::Mg) {
    s.coarse_space = own.get_enum("coarse_space", s.coarse_space, coarse_spaces(),
                                "coarse unknowns kept next to constrained vertices (as multigrid.coarse_space)");
    s.max_levels = own.get_int("max_levels", s.max_levels, 0, 64, "coarse levels used (0: every level the hierarchy has)");
    s.smoother_iterations =
        own.get_int("smoother_iterations", s.smoother_iterations, 1, 100, "smoother applications before and after the coarse correction");
    s.smoother = own.get_choice("smoother", s.smoother, {"sor", "chebyshev"},
                              "sor: symmetric SOR (Richardson); chebyshev: Chebyshev around Jacobi");
    s.cycle = own.get_choice("cycle", s.cycle, {"v", "w"}, "multigrid cycle");
  }
  if (preconditioner == Preconditioner::Gamg) {
    s.gamg_threshold = own.get_number("threshold", s.gamg_threshold, -1.0, 1.0,
                                    "graph drop tolerance of the aggregation (PETSc -pc_gamg_threshold)");
    s.gamg_smoothings = own.get_int("smoothings", s.gamg_smoothings, 0, 4, "prolongation smoothing steps (-pc_gamg_agg_nsmooths)");
    s.gamg_eigenvalue_safety = own.get_number(
        "eigenvalue_safety", s.gamg_eigenvalue_safety, 1.0, 10.0,
        "the Chebyshev smoothers' bound over the estimated largest eigenvalue (PETSc's 1.1 underestimates this "
        "fourth-order operator: the preconditioner turns indefinite)");
    s.linear_near_null_space =
        own.get_choice("near_null_space", "linear", {"constant", "linear"},
                     "what the aggregates must reproduce: constants, or constants and the coordinates' linear functions "
                     "(needs the hierarchy's positions)") == "linear";
  }
  if (preconditioner == Preconditioner::BoomerAmg) {
    s.strong_threshold = own.get_number("strong_threshold", s.strong_threshold, 0.0, 1.0, "strength of connection threshold");
    s.coarsen = own.get_choice("coarsen", s.coarsen, {"CLJP", "Ruge-Stueben", "modifiedRuge-Stueben", "Falgout", "PMIS", "HMIS"},
                             "coarsening");
    s.interpolation = own.get_choice("interpolation", s.interpolation,
                                   {"classical", "direct", "multipass", "ext+i", "ext+i-cc", "standard", "FF", "FF1"},
                                   "interpolation");
    s.aggressive_levels = own.get_int("aggressive_levels", s.aggressive_levels, 0, 10, "levels of aggressive coarsening");
  }
  own.check_no_unknown_keys();
  Config p = cfg.child("petsc", "options every petsc_* solver shares");
  s.extra_options = p.get<std::string>("options", "", "more PETSc options, e.g. '-mg_levels_ksp_max_it 3' (prefixed for this "
                                                      "solver; an option PETSc does not use is an error)");
  for (const std::string& w : words(s.extra_options))
    if ((w == "-ksp_type" || w == "-ksp_norm_type" || w == "-pc_type") && !cfg.documenting())
      throw InvalidConfig(p.key_path("options") + ": " + w + " is fixed by the solver's name (" + name +
                          ": conjugate gradients on the true residual)");
  s.ranks = p.get_int("ranks", s.ranks, 1, 1 << 20, "MPI ranks: 1 solves in this process, more start an MPI job");
  s.launcher = p.get<std::string>("launcher", s.launcher, "the MPI launch command, {ranks} replaced (e.g. 'srun -n {ranks}')");
  if (s.launcher.find("{ranks}") == std::string::npos && !cfg.documenting())
    throw InvalidConfig(p.key_path("launcher") + ": '" + s.launcher + "' has no {ranks}");
  s.job_dir = p.get<std::string>("job_dir", s.job_dir,
                                 "folder for a distributed job's files (default: the temporary folder; on a cluster, a "
                                 "folder every node sees)");
  s.worker = p.get<std::string>("worker", s.worker, "the MPI program (default: fairshape-mpi-solve beside fairshape)");
  s.keep_job = p.get<bool>("keep_job", s.keep_job, "keep a distributed job's folder (system, options, logs)");
  if (s.ranks > 1 && s.iterative.energy_tolerance > 0)
    s.refusals.push_back(cfg.key_path("energy_tolerance") + ": a distributed " + name +
                        " solve (petsc.ranks > 1) stops on the residual only");
  p.check_no_unknown_keys();
  return s;
}

std::vector<std::string> Settings::extra_option_names(const std::string& prefix) const {
  std::vector<std::string> out;
  for (const std::string& w : words(extra_options))
    if (is_option_name(w)) out.push_back(prefix + w.substr(1));
  return out;
}

std::string Settings::option_string(const std::string& prefix, int mg_levels) const {
  std::ostringstream o;
  o.precision(17);
  const auto opt = [&](const std::string& name, const auto& value) { o << " -" << prefix << name << " " << value; };
  opt("ksp_type", "cg");
  opt("ksp_norm_type", "unpreconditioned");
  // tolerance 0 (a fixed iteration count) is rtol 0: PETSc then runs to ksp_max_it.
  opt("ksp_rtol", iterative.tolerance);
  opt("ksp_atol", 0.0);
  opt("ksp_divtol", 1e12);
  opt("ksp_max_it", iterative.max_iterations);
  switch (preconditioner) {
    case Preconditioner::Mg:
      opt("pc_type", "mg");
      opt("pc_mg_levels", mg_levels);
      opt("pc_mg_galerkin", "both");
      opt("pc_mg_cycle_type", cycle);
      if (smoother == "sor") {
        opt("mg_levels_ksp_type", "richardson");
        opt("mg_levels_pc_type", "sor");  // PETSc's default SOR is the local symmetric sweep
      } else {
        opt("mg_levels_ksp_type", "chebyshev");
        opt("mg_levels_pc_type", "jacobi");
      }
      opt("mg_levels_ksp_max_it", smoother_iterations);
      opt("mg_coarse_ksp_type", "preonly");
      opt("mg_coarse_pc_type", "redundant");
      opt("mg_coarse_redundant_pc_type", "lu");
      opt("mg_coarse_redundant_pc_factor_mat_ordering_type", "nd");
      break;
    case Preconditioner::Gamg:
      opt("pc_type", "gamg");
      opt("pc_gamg_type", "agg");
      opt("pc_gamg_threshold", gamg_threshold);
      opt("pc_gamg_agg_nsmooths", gamg_smoothings);
      o << " -" << prefix << "mg_levels_ksp_chebyshev_esteig 0,0.1,0," << gamg_eigenvalue_safety;
      break;
    case Preconditioner::BoomerAmg:
      opt("pc_type", "hypre");
      opt("pc_hypre_type", "boomeramg");
      opt("pc_hypre_boomeramg_strong_threshold", strong_threshold);
      opt("pc_hypre_boomeramg_coarsen_type", coarsen);
      opt("pc_hypre_boomeramg_interp_type", interpolation);
      opt("pc_hypre_boomeramg_agg_nl", aggressive_levels);
      break;
  }
  for (const std::string& w : words(extra_options)) o << " " << (is_option_name(w) ? "-" + prefix + w.substr(1) : w);
  return o.str();
}

std::string Settings::to_json() const {
  nlohmann::json j;
  j["preconditioner"] = solver_name();
  j["tolerance"] = iterative.tolerance;
  j["max_iterations"] = iterative.max_iterations;
  j["error_tolerance"] = iterative.error_tolerance;
  j["error_delay"] = iterative.error_delay;
  j["smoother_iterations"] = smoother_iterations;
  j["smoother"] = smoother;
  j["cycle"] = cycle;
  j["gamg_threshold"] = gamg_threshold;
  j["gamg_smoothings"] = gamg_smoothings;
  j["gamg_eigenvalue_safety"] = gamg_eigenvalue_safety;
  j["strong_threshold"] = strong_threshold;
  j["coarsen"] = coarsen;
  j["interpolation"] = interpolation;
  j["aggressive_levels"] = aggressive_levels;
  j["extra_options"] = extra_options;
  return j.dump();
}

Settings Settings::from_json(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text);
  Settings s;
  const std::string name = j.at("preconditioner");
  s.preconditioner = name == "petsc_gamg" ? Preconditioner::Gamg
                     : name == "petsc_boomeramg" ? Preconditioner::BoomerAmg
                                                 : Preconditioner::Mg;
  s.iterative.tolerance = j.at("tolerance");
  s.iterative.max_iterations = j.at("max_iterations");
  s.iterative.error_tolerance = j.at("error_tolerance");
  s.iterative.error_delay = j.at("error_delay");
  s.smoother_iterations = j.at("smoother_iterations");
  s.smoother = j.at("smoother");
  s.cycle = j.at("cycle");
  s.gamg_threshold = j.at("gamg_threshold");
  s.gamg_smoothings = j.at("gamg_smoothings");
  s.gamg_eigenvalue_safety = j.at("gamg_eigenvalue_safety");
  s.strong_threshold = j.at("strong_threshold");
  s.coarsen = j.at("coarsen");
  s.interpolation = j.at("interpolation");
  s.aggressive_levels = j.at("aggressive_levels");
  s.extra_options = j.at("extra_options");
  return s;
}

}  // namespace fairshape::petsc
