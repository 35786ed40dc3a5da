// Worker processes of a sweep, watched by the process that started them: a worker that dies
// (a signal, an abort) turns its run in progress into a `crashed` row and is started again,
// so the sweep goes on; workers die with the supervisor (PR_SET_PDEATHSIG), and a signal to
// the supervisor stops them all.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace fairshape {

struct WorkerCrash {
  int worker = 0;
  std::string run_id;   // the run it had in progress (empty: none)
  std::string reason;   // "killed by signal 11 (Segmentation fault)"
};

struct SupervisorResult {
  int status = 0;          // the worst worker exit status (0 or 3), 3 after a crashed run
  int interrupted_by = 0;  // the signal that stopped the sweep, or 0
};

//! Starts `jobs` workers with `argv_of(i)`, restarts one whose run crashed after `on_crash`
//! recorded it, and returns when all have finished.
SupervisorResult supervise_workers(int jobs, const std::function<std::vector<std::string>(int)>& argv_of,
                                   const std::function<std::string(int)>& run_in_progress,
                                   const std::function<void(const WorkerCrash&)>& on_crash);

//! Called first by a worker: it gets SIGKILL when its supervisor dies, and exits at once if
//! the supervisor is already gone.
void bind_worker_to_supervisor();

}  // namespace fairshape
