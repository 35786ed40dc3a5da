#include "fairshape/experiment/supervisor.h"

#include <signal.h>
#include <spawn.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <map>

#include "fairshape/core/error.h"

extern char** environ;

namespace fairshape {
namespace {

constexpr const char* kSupervisorVariable = "FAIRSHAPE_SUPERVISOR_PID";
constexpr int kMaxWorkers = 256;
volatile sig_atomic_t g_signal = 0;
volatile pid_t g_workers[kMaxWorkers];

void forward_and_stop(int sig) {
  g_signal = sig;
  for (int i = 0; i < kMaxWorkers; ++i)
    if (g_workers[i] > 0) ::kill(g_workers[i], SIGTERM);
}

bool is_stop_signal(int sig) { return sig == SIGTERM || sig == SIGINT || sig == SIGHUP; }

pid_t spawn(const std::vector<std::string>& args) {
  std::vector<std::string> env_storage;
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, kSupervisorVariable, std::strlen(kSupervisorVariable)) != 0) env_storage.emplace_back(*e);
  env_storage.push_back(std::string(kSupervisorVariable) + "=" + std::to_string(::getpid()));
  std::vector<char*> envp, argv;
  for (auto& e : env_storage) envp.push_back(e.data());
  envp.push_back(nullptr);
  std::vector<std::string> copy = args;
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, copy.front().c_str(), nullptr, nullptr, argv.data(), envp.data()) != 0)
    throw Error("cannot start worker process " + copy.front());
  return pid;
}

std::string describe(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    return "killed by signal " + std::to_string(sig) + " (" + ::strsignal(sig) + ")";
  }
  return "exited with status " + std::to_string(WEXITSTATUS(status)) + " outside the run's own error handling";
}

class SignalGuard {
 public:
  SignalGuard() {
    struct sigaction sa {};
    sa.sa_handler = forward_and_stop;
    sigemptyset(&sa.sa_mask);
    for (int s : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(s, &sa, &old_[s]);
  }
  ~SignalGuard() {
    for (auto& [s, old] : old_) ::sigaction(s, &old, nullptr);
  }

 private:
  std::map<int, struct sigaction> old_;
};

}  // namespace

SupervisorResult supervise_workers(int jobs, const std::function<std::vector<std::string>(int)>& argv_of,
                                   const std::function<std::string(int)>& run_in_progress,
                                   const std::function<void(const WorkerCrash&)>& on_crash) {
  FAIRSHAPE_ASSERT(jobs >= 1 && jobs <= kMaxWorkers, "worker count out of range");
  g_signal = 0;
  for (int i = 0; i < kMaxWorkers; ++i) g_workers[i] = 0;
  const SignalGuard guard;
  std::map<pid_t, int> worker_of;
  for (int w = 0; w < jobs; ++w) {
    const pid_t pid = spawn(argv_of(w));
    g_workers[w] = pid;
    worker_of[pid] = w;
  }
  SupervisorResult result;
  while (!worker_of.empty()) {
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;
    }
    const auto it = worker_of.find(pid);
    if (it == worker_of.end()) continue;
    const int w = it->second;
    worker_of.erase(it);
    g_workers[w] = 0;
    const bool clean_exit = WIFEXITED(status) && (WEXITSTATUS(status) == 0 || WEXITSTATUS(status) == 3);
    if (clean_exit) {
      result.status = std::max(result.status, WEXITSTATUS(status));
      continue;
    }
    if (g_signal) continue;  // stopped on purpose: its run is not done and runs again on resume
    // A scheduler cancelling or requeueing a job signals every process of it, so a worker's
    // SIGTERM may come before the supervisor's own: it is the same stop, never a crash row
    // (which a resume would take for a finished run).
    if (WIFSIGNALED(status) && is_stop_signal(WTERMSIG(status))) {
      forward_and_stop(WTERMSIG(status));
      continue;
    }
    const std::string run = run_in_progress(w);
    if (run.empty()) {  // it failed outside any run: starting it again would fail the same way
      std::cerr << "fairshape: worker " << w << " " << describe(status) << " outside any run\n";
      result.status = std::max(result.status, 1);
      continue;
    }
    on_crash({w, run, describe(status)});
    result.status = std::max(result.status, 3);
    const pid_t again = spawn(argv_of(w));
    g_workers[w] = again;
    worker_of[again] = w;
  }
  result.interrupted_by = g_signal;
  return result;
}

void bind_worker_to_supervisor() {
  const char* expected = std::getenv(kSupervisorVariable);
  if (!expected) return;
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != static_cast<pid_t>(std::atoll(expected))) std::_Exit(1);  // it died before we could bind
}

}  // namespace fairshape
