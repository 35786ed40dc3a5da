// Boier-Martin et al.'s edit session (design/surface_edit_session.h) bound for Python: built from
// a config's keys through the run kind's own reader (SurfaceEditSpec::from_config, one parser:
// an unknown key or value is refused exactly as in a YAML config), then driven step by step —
// move, scale, add, remove, solve — with the prepared problem kept between steps.
// fairshape.edit and fairshape.SurfaceEditSession (python/fairshape/_edit.py) are thin wrappers.
// Copies: each step's deformation and the vertices come back as new arrays; the hierarchy as a
// new MultiresSurface.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.h"
#include "checks.h"
#include "convert.h"
#include "fairshape/experiment/components.h"
#include "fairshape/experiment/kinds/surface_edit/open_session.h"
#include "fairshape/experiment/kinds/surface_edit/run_one.h"

namespace py = pybind11;

namespace fairshape::python {
namespace {

class PySession {
 public:
  // `config`: a run's keys (name optional); `hierarchy`: the surface to edit in memory (then
  // `input` holds only edit_level), else input.mesh is read and built as a run builds it.
  PySession(const py::dict& config, const MultiresSurface* hierarchy, const std::vector<std::string>& search_dirs) {
    YAML::Node node = to_yaml(config, "config");
    if (!node["name"]) node["name"] = "session";
    spec_ = hierarchy ? SurfaceEditSpec::from_config(node, components(), *hierarchy)
                      : SurfaceEditSpec::from_config(node, components(), search_dirs);
    py::gil_scoped_release release;
    std::shared_ptr<const MultiresSurface> rest;
    if (hierarchy) {
      rest = std::make_shared<const MultiresSurface>(*hierarchy);
    } else {
      RunCache cache;  // the run kind's hierarchy: the mesh read, subdivided or remeshed
      rest = std::make_shared<const MultiresSurface>(cache.hierarchy(spec_));
    }
    session_ = open_session(spec_, rest);
  }

  py::dict solve(const std::optional<std::string>& mode) {
    EditStepSpec step;
    if (mode) {
      AccuracyOptions a;
      a.mode = accuracy_mode_names().value(*mode, "mode");
      step.accuracy = a.mode;
    }
    return solved(step);
  }

  void move(int handle, const Vec3& offset) { session_->move(handle, offset); }
  void scale(double s) { session_->scale(s); }
  void remove(int handle) {
    py::gil_scoped_release release;
    session_->remove(handle);
  }
  int add(const py::dict& constraint) {
    Config k = to_config(constraint, "add");
    ConstraintTerm t = read_constraint_term(k, components(), spec_.implementation);
    py::gil_scoped_release release;
    return session_->add({t.constraint, t.influence});
  }

  // The config's own `steps:` solved in turn, as `fairshape run` solves them.
  py::list replay() {
    py::list out;
    for (const EditStepSpec& step : spec_.steps) {
      {
        py::gil_scoped_release release;
        apply_step(step, *session_);
      }
      out.append(solved(step));
    }
    return out;
  }

  MatrixX3 vertices() const { return session_->current().mesh(session_->current().levels()).positions(); }
  MultiresSurface hierarchy() const { return session_->current(); }
  int level() const { return session_->level(); }
  std::vector<int> handles() const { return session_->handles(); }
  int preparations() const { return session_->preparations(); }
  int scheduled_steps() const { return spec_.scheduled ? static_cast<int>(spec_.steps.size()) : 0; }

 private:
  py::dict solved(const EditStepSpec& step) {
    SurfaceEditStep r;
    {
      py::gil_scoped_release release;
      r = solve_step(step, *session_);
    }
    const std::string outcome = std::string(to_string(r.summary.termination)) + ": " + r.summary.message;
    finite_result(r.solution.delta, "edit: the deformation (" + outcome + ")");
    py::dict d;
    d["termination"] = std::string(to_string(r.summary.termination));
    d["succeeded"] = r.summary.succeeded();
    d["iterations"] = r.summary.iterations;
    d["residual"] = r.summary.residual;
    d["message"] = r.summary.message;
    d["accuracy"] = r.accuracy;
    d["level"] = session_->level();
    d["n_dofs"] = r.regional ? 0 : static_cast<int>(session_->problem().H.rows());
    d["energy"] = r.energy;
    d["constraint_residual"] = r.constraint_residual;
    d["constrained_vertices"] = r.solution.constrained_vertices;
    d["flipped_faces"] = static_cast<int>(r.orientation.folds.flipped.size());
    d["normal_error_deg"] = r.orientation.normal_error_deg;
    d["analyze_s"] = r.solution.analyze_s;
    d["solve_s"] = r.solve_s;
    d["check_s"] = r.check_s;
    d["rotation_rounds"] = r.rotation_rounds;
    d["delta"] = py::cast(std::move(r.solution.delta));  // moved into the array: no copy
    return d;
  }

  static const NameTable<AccuracyMode>& accuracy_mode_names() {
    static const NameTable<AccuracyMode> t{{AccuracyMode::Interactive, "interactive"},
                                           {AccuracyMode::Improved, "improved"},
                                           {AccuracyMode::Converged, "converged"}};
    return t;
  }

  SurfaceEditSpec spec_;
  std::unique_ptr<SurfaceEditSession> session_;
};

}  // namespace

void bind_edit(py::module_& m) {
  py::class_<PySession>(m, "_SurfaceEditSession", "The session's C++ half; use fairshape.SurfaceEditSession.")
      .def(py::init<const py::dict&, const MultiresSurface*, const std::vector<std::string>&>(), py::arg("config"),
           py::arg("hierarchy"), py::arg("search_dirs"))
      .def("solve", &PySession::solve, py::arg("mode"))
      .def("move", &PySession::move, py::arg("handle"), py::arg("offset"))
      .def("scale", &PySession::scale, py::arg("s"))
      .def("add", &PySession::add, py::arg("constraint"))
      .def("remove", &PySession::remove, py::arg("handle"))
      .def("replay", &PySession::replay)
      .def_property_readonly("vertices", &PySession::vertices)
      .def_property_readonly("hierarchy", &PySession::hierarchy)
      .def_property_readonly("level", &PySession::level)
      .def_property_readonly("handles", &PySession::handles)
      .def_property_readonly("preparations", &PySession::preparations)
      .def_property_readonly("scheduled_steps", &PySession::scheduled_steps);
  m.def("constraint_modes", [] { return constraint_mode_names().names(); }, "Names of the edit's constraint modes.");
}

}  // namespace fairshape::python
