#include "fairshape/solver/petsc_distributed.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "fairshape/core/error.h"
#include "fairshape/core/timer.h"
#include "fairshape/solver/petsc_binary.h"
#include "fairshape/solver/petsc_ksp.h"
#include "fairshape/solver/petsc_runtime.h"

#ifndef FAIRSHAPE_MPI_SOLVE_PATHS
#define FAIRSHAPE_MPI_SOLVE_PATHS ""
#endif

namespace fs = std::filesystem;

namespace fairshape::petsc {
namespace {

std::string column_file(const fs::path& dir, const std::string& stem, Eigen::Index c) {
  return (dir / (stem + std::to_string(c) + ".petsc")).string();
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string tail(const std::string& text, std::size_t lines) {
  std::size_t pos = text.size();
  for (std::size_t k = 0; k <= lines && pos != std::string::npos && pos > 0; ++k) pos = text.rfind('\n', pos - 1);
  return pos == std::string::npos ? text : text.substr(pos + 1);
}

// The MPI program: petsc.worker, or fairshape-mpi-solve beside this executable, in the build tree
// or the installed tree.
std::string find_worker(const Settings& s) {
  if (!s.worker.empty()) {
    if (!fs::exists(s.worker)) throw InvalidConfig("petsc.worker: " + s.worker + " does not exist");
    return s.worker;
  }
  std::vector<fs::path> candidates;
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) candidates.push_back(self.parent_path() / "fairshape-mpi-solve");
  std::istringstream paths(FAIRSHAPE_MPI_SOLVE_PATHS);
  for (std::string p; std::getline(paths, p, ':');)
    if (!p.empty()) candidates.push_back(fs::path(p) / "fairshape-mpi-solve");
  for (const fs::path& c : candidates)
    if (fs::exists(c)) return c.string();
  std::string where;
  for (const fs::path& c : candidates) where += (where.empty() ? "" : ", ") + c.string();
  throw InvalidConfig("petsc.ranks > 1 needs the MPI program fairshape-mpi-solve (not found at " + where +
                      "); build it (make build) or set petsc.worker");
}

std::vector<std::string> launch_command(const Settings& s, const std::string& worker, const std::string& dir) {
  std::string line = s.launcher;
  const std::string ranks = std::to_string(s.ranks);
  for (std::size_t at; (at = line.find("{ranks}")) != std::string::npos;) line.replace(at, 7, ranks);
  std::istringstream words(line);
  std::vector<std::string> argv;
  for (std::string w; words >> w;) argv.push_back(w);
  argv.push_back(worker);
  argv.push_back(dir);
  return argv;
}

// Runs argv with its output in `log`; the exit status (128 + N for a signal).
int run_command(const std::vector<std::string>& argv, const fs::path& log) {
  const pid_t pid = fork();
  if (pid < 0) throw SolverError("petsc: fork failed: cannot start the MPI job");
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
    }
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execvp(args[0], args.data());
    std::fprintf(stderr, "cannot run %s\n", args[0]);
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

DistributedOutcome solve_distributed(const Settings& s, const SparseMatrix& A, const std::vector<SparseMatrix>& prolongations,
                                     const Eigen::MatrixXd& near_null, const Eigen::MatrixXd& b, Eigen::MatrixXd& x) {
  const Timer wall;
  const std::string worker = find_worker(s);
  const fs::path base = s.job_dir.empty() ? fs::temp_directory_path() : fs::path(s.job_dir);
  std::error_code ec;
  fs::create_directories(base, ec);
  std::string pattern = (base / "fairshape-petsc-XXXXXX").string();
  if (!mkdtemp(pattern.data())) throw OutputError("petsc.job_dir: cannot create a job folder in " + base.string());
  const fs::path dir(pattern);
  struct Cleanup {
    fs::path dir;
    bool keep;
    ~Cleanup() {
      std::error_code e;
      if (!keep) fs::remove_all(dir, e);
    }
  } cleanup{dir, s.keep_job};

  write_matrix_file((dir / "A.petsc").string(), A);
  for (std::size_t l = 1; l < prolongations.size(); ++l)
    write_matrix_file(column_file(dir, "P", static_cast<Eigen::Index>(l)), prolongations[l]);
  for (Eigen::Index k = 0; k < near_null.cols(); ++k)
    write_vector_file(column_file(dir, "near_null", k), near_null.col(k));
  nlohmann::json job;
  job["settings"] = nlohmann::json::parse(s.to_json());
  job["rows"] = A.rows();
  job["columns"] = b.cols();
  job["levels"] = std::max<std::size_t>(prolongations.size(), 1);
  job["near_null"] = near_null.cols();
  std::vector<bool> warm;
  for (Eigen::Index c = 0; c < b.cols(); ++c) {
    write_vector_file(column_file(dir, "b", c), b.col(c));
    warm.push_back(!x.col(c).isZero(0.0));
    if (warm.back()) write_vector_file(column_file(dir, "x0_", c), x.col(c));
  }
  job["warm_start"] = warm;
  {
    std::ofstream out(dir / "job.json");
    out << job.dump(1) << "\n";
    if (!out) throw OutputError((dir / "job.json").string() + ": writing failed");
  }

  const int status = run_command(launch_command(s, worker, dir.string()), dir / "log.txt");
  std::string failure = read_text(dir / "error.txt");
  if (status != 0 || !failure.empty() || !fs::exists(dir / "result.json"))
    throw SolverError(s.solver_name() + ": the MPI job (" + s.launcher + ") failed with status " + std::to_string(status) +
                      (failure.empty() ? "" : ": " + failure) + "\n" + tail(read_text(dir / "log.txt"), 12) +
                      (s.keep_job ? "(job folder kept: " + dir.string() + ")" : "(set petsc.keep_job to keep the job folder)"));
  const nlohmann::json result = nlohmann::json::parse(read_text(dir / "result.json"));
  DistributedOutcome out;
  for (Eigen::Index c = 0; c < b.cols(); ++c) {
    x.col(c) = read_vector_file(column_file(dir, "x", c), A.rows());
    out.iterations.push_back(result.at("columns").at(c).at("iterations"));
    out.reasons.push_back(result.at("columns").at(c).at("reason"));
    out.error_estimates.push_back(result.at("columns").at(c).value("error_estimate", -1.0));
  }
  out.setup_s = result.at("setup_s");
  out.solve_s = result.at("solve_s");
  for (const auto& r : result.at("ranks"))
    out.ranks.push_back({r.at("rank"), r.at("rows"), r.at("nonzeros"), r.at("max_rss_mb")});
  out.wall_s = wall.seconds();
  return out;
}

int run_distributed_job(int argc, char** argv) {
  try {
    initialize(&argc, &argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fairshape-mpi-solve: %s\n", e.what());
    return 1;
  }
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (argc != 2) {
    if (rank == 0) std::fprintf(stderr, "usage: fairshape-mpi-solve JOB_DIR (a folder written by a petsc_* solver)\n");
    return 2;
  }
  const fs::path dir(argv[1]);
  try {
    const nlohmann::json job = nlohmann::json::parse(read_text(dir / "job.json"));
    const Settings s = Settings::from_json(job.at("settings").dump());
    const MPI_Comm comm = PETSC_COMM_WORLD;
    MatHandle A = read_matrix(comm, (dir / "A.petsc").string());
    std::vector<MatHandle> P(job.at("levels").get<std::size_t>());
    std::vector<Mat> interpolations(P.size(), nullptr);
    for (std::size_t l = 1; l < P.size(); ++l) {
      P[l] = read_matrix(comm, column_file(dir, "P", static_cast<Eigen::Index>(l)));
      interpolations[l] = P[l].get();
    }
    std::vector<VecHandle> null_vectors;
    std::vector<Vec> near_null;
    for (int k = 0; k < job.at("near_null").get<int>(); ++k) {
      null_vectors.push_back(read_vector(comm, column_file(dir, "near_null", k)));
      near_null.push_back(null_vectors.back().get());
    }
    const ConfiguredKsp ksp(comm, s, A.get(), interpolations, near_null);
    nlohmann::json columns = nlohmann::json::array();
    double solve_s = 0;
    for (int c = 0; c < job.at("columns").get<int>(); ++c) {
      VecHandle b = read_vector(comm, column_file(dir, "b", c));
      VecHandle x;
      const bool warm = job.at("warm_start").at(c);
      if (warm) {
        x = read_vector(comm, column_file(dir, "x0_", c));
      } else {
        FS_PETSC(VecDuplicate(b.get(), x.out()));
        FS_PETSC(VecSet(x.get(), 0.0));
      }
      FS_PETSC(KSPSetInitialGuessNonzero(ksp.get(), warm ? PETSC_TRUE : PETSC_FALSE));
      // error_tolerance: the job stops by fairshape's monitor on the error estimate (PETSc's
      // residual test replaced); otherwise PETSc's own test with the options' rtol.
      IterationMonitor monitor(s.iterative, {}, {}, /*krylov=*/true);
      std::unique_ptr<IterateErrorEstimate> estimate;
      MonitoredTest test;
      test.monitor = &monitor;
      if (s.iterative.error_tolerance > 0) {
        FS_PETSC(VecNorm(b.get(), NORM_2, &test.b_norm));
        if (!(test.b_norm > 0)) test.b_norm = 1;
        estimate = std::make_unique<IterateErrorEstimate>(A.get(), s.iterative.error_delay);
        test.estimate = estimate.get();
        FS_PETSC(KSPSetConvergenceTest(ksp.get(), MonitoredTest::test, &test, nullptr));
      }
      const Timer t;
      FS_PETSC(KSPSolve(ksp.get(), b.get(), x.get()));
      solve_s += t.seconds();
      PetscInt its = 0;
      KSPConvergedReason reason;
      FS_PETSC(KSPGetIterationNumber(ksp.get(), &its));
      FS_PETSC(KSPGetConvergedReason(ksp.get(), &reason));
      write_vector(column_file(dir, "x", c), x.get());
      if (test.error) std::rethrow_exception(test.error);
      columns.push_back({{"iterations", its},
                         {"reason", ConfiguredKsp::reason_name(reason)},
                         {"error_estimate", monitor.summary().error_estimate}});
    }
    PetscInt local_rows = 0, local_cols = 0;
    FS_PETSC(MatGetLocalSize(A.get(), &local_rows, &local_cols));
    MatInfo info;
    FS_PETSC(MatGetInfo(A.get(), MAT_LOCAL, &info));
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    double mine[3] = {static_cast<double>(local_rows), info.nz_used, usage.ru_maxrss / 1024.0};
    std::vector<double> all(static_cast<std::size_t>(3 * size));
    MPI_Gather(mine, 3, MPI_DOUBLE, all.data(), 3, MPI_DOUBLE, 0, comm);
    if (rank == 0) {
      nlohmann::json result;
      result["columns"] = columns;
      result["setup_s"] = ksp.setup_seconds();
      result["solve_s"] = solve_s;
      result["ranks"] = nlohmann::json::array();
      for (int r = 0; r < size; ++r)
        result["ranks"].push_back({{"rank", r},
                                   {"rows", static_cast<long long>(all[3 * r])},
                                   {"nonzeros", static_cast<long long>(all[3 * r + 1])},
                                   {"max_rss_mb", all[3 * r + 2]}});
      std::ofstream out(dir / "result.json.tmp");
      out << result.dump(1) << "\n";
      out.close();
      fs::rename(dir / "result.json.tmp", dir / "result.json");
    }
  } catch (const std::exception& e) {
    // One rank's error stops every rank (the others may wait in a collective call).
    std::ofstream(dir / "error.txt", std::ios::app) << "rank " << rank << ": " << e.what() << "\n";
    MPI_Abort(PETSC_COMM_WORLD, 1);
  }
  return 0;
}

}  // namespace fairshape::petsc
