// `fairshape run` in-process: the supervisor of experiment/sweep_runner.h validates the config
// here (an invalid one raises InvalidConfig / InvalidInput with the CLI's message, nothing run)
// and runs the points in worker processes of the command line, so a crashing run is a row,
// not a dead interpreter. The GIL is released while the sweep runs; Ctrl-C stops the workers
// (the supervisor forwards it) and the sweep can be resumed.
#include <pybind11/stl.h>

#include "bindings.h"
#include "fairshape/core/error.h"
#include "fairshape/experiment/sweep_runner.h"

namespace py = pybind11;

namespace fairshape::python {

void bind_experiment(py::module_& m) {
  m.def(
      "_run_sweep",
      [](const std::string& config, const std::string& out, const std::vector<std::string>& sets,
         const std::vector<std::string>& filters, int jobs, bool resume, bool force, bool retry_failed, bool smoke,
         const std::string& executable) {
        if (jobs < 1 || jobs > 256) throw InvalidConfig("jobs=" + std::to_string(jobs) + ": expected 1..256");
        if (retry_failed && !resume) throw InvalidConfig("retry_failed=True needs resume=True");
        SweepOptions opt;
        opt.config_path = config;
        opt.out_dir = out;
        opt.sets = sets;
        opt.filters = filters;
        opt.jobs = jobs;
        opt.resume = resume;
        opt.force = force;
        opt.retry_failed = retry_failed;
        opt.smoke = smoke;
        opt.executable = executable;
        opt.argv = {"python:fairshape.run", config, "--out", out};
        for (const auto& s : sets) opt.argv.insert(opt.argv.end(), {"--set", s});
        for (const auto& f : filters) opt.argv.insert(opt.argv.end(), {"--filter", f});
        py::gil_scoped_release release;
        return run_sweep(opt);
      },
      py::arg("config"), py::arg("out"), py::arg("sets"), py::arg("filters"), py::arg("jobs"), py::arg("resume"),
      py::arg("force"), py::arg("retry_failed"), py::arg("smoke"), py::arg("executable"),
      "The sweep's C++ half; call fairshape.run(). Returns the CLI's exit status (0, 3, 128+signal).");
}

}  // namespace fairshape::python
