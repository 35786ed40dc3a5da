// Feature curves of Khodakovsky & Schröder, "Fine level feature editing for subdivision
// surfaces" (src/feature), through the library's FeatureSession (feature/feature_session.h):
// fairshape.FeatureSession is the session itself — set up from keyword options read by the
// feature run's own config reader (FeatureRunSpec::from_config, read_feature_entry: the same
// keys, ranges, defaults and messages; an unknown key is refused naming the valid ones), then
// advanced a step at a time (add, replace, move, set, remove), each step re-evaluating only the
// region it reaches; fairshape.apply_features is one step on a given hierarchy.
// Copies: positions come back as new n×3 arrays; a hierarchy as a new MultiresSurface.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <memory>
#include <set>
#include <sstream>

#include "bindings.h"
#include "checks.h"
#include "convert.h"
#include "fairshape/experiment/kinds/feature/feature_run.h"
#include "fairshape/feature/feature_session.h"
#include "fairshape/feature/profile_measure.h"

namespace py = pybind11;

namespace fairshape::python {
namespace {

// A feature dict's keys as a `features:` entry: fairshape.feature()'s faces + bary become
// surface_points ([face, b0, b1, b2] each).
YAML::Node feature_entry(const py::dict& d, const std::string& where) {
  YAML::Node node = to_yaml(d, where);
  if (!node["faces"] && !node["bary"]) return node;
  const YAML::Node faces = node["faces"], bary = node["bary"];
  if (!faces || !bary || faces.size() != bary.size())
    throw InvalidConfig(where + ".bary: one barycentric triple per face (give faces and bary together)");
  YAML::Node points(YAML::NodeType::Sequence);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    if (!bary[i].IsSequence() || bary[i].size() != 3) throw InvalidConfig(where + ".bary: expected k×3");
    YAML::Node p(YAML::NodeType::Sequence);
    p.push_back(faces[i]);
    for (std::size_t c = 0; c < 3; ++c) p.push_back(bary[i][c]);
    points.push_back(p);
  }
  node.remove("faces");
  node.remove("bary");
  node["surface_points"] = points;
  return node;
}

// One feature through the run's reader. A session's steps are its calls, so the keys that
// schedule design steps in a config are refused here, not ignored.
FeatureSpec read_feature(const YAML::Node& node, const std::string& where, int levels, const feature::FeatureParams& defaults) {
  Config c(node, where);
  FeatureSpec f = read_feature_entry(c, where, {"."}, levels, defaults, false);
  const char* scheduled = f.step > 0 ? "step" : f.until >= 0 ? "until" : !f.moves.empty() ? "moves" : !f.changes.empty() ? "changes" : nullptr;
  if (scheduled)
    throw InvalidConfig(where + "." + scheduled + ": a session's later steps are its calls (add, replace, move, set, "
                        "remove), not a schedule");
  return f;
}

py::dict profile_dict(const feature::ProfileMeasure& m) {
  py::dict d;
  d["height_min"] = m.height_min;
  d["height_max"] = m.height_max;
  d["width_left"] = m.width_left;
  d["width_right"] = m.width_right;
  d["height_error"] = m.height_error;
  d["width_error"] = m.width_error;
  d["profile_error"] = m.profile_error;
  return d;
}

// features.csv's row of each feature.
py::list measure_rows(const FeatureMeasurement& m, const std::map<int, feature::FeatureCurve>& curves) {
  py::list rows;
  for (const feature::FeatureMeasure& f : m.features) {
    const feature::FeatureParams& q = curves.at(f.id).params;
    py::dict d;
    d["name"] = f.name;
    d["level"] = f.level;
    d["height"] = q.height;
    d["radius_left"] = q.radius;
    d["radius_right"] = q.right_radius();
    d["fine"] = profile_dict(f.fine);
    d["limit"] = profile_dict(f.limit);
    d["within_tolerance"] = f.within_tolerance;
    d["why"] = f.why;
    rows.append(d);
  }
  return rows;
}

py::dict measurement_dict(const FeatureMeasurement& m, const std::map<int, feature::FeatureCurve>& curves) {
  py::dict d;
  d["termination"] = std::string(to_string(m.summary.termination));
  d["message"] = m.summary.message;
  d["features"] = measure_rows(m, curves);
  d["within_tolerance"] = std::all_of(m.features.begin(), m.features.end(), [](const auto& f) { return f.within_tolerance; });
  d["flipped_faces"] = static_cast<int>(m.folds.flipped.size());
  d["folds"] = m.folds.describe();
  d["check_s"] = m.check_s;
  return d;
}

// A curve's control points as placed on its level: faces (k) and barycentric coordinates (k×3).
std::pair<Eigen::VectorXi, Eigen::MatrixXd> placed_points(const feature::FeatureCurve& c) {
  Eigen::VectorXi faces(static_cast<Eigen::Index>(c.points.size()));
  Eigen::MatrixXd bary(static_cast<Eigen::Index>(c.points.size()), 3);
  for (std::size_t k = 0; k < c.points.size(); ++k) {
    faces[static_cast<Eigen::Index>(k)] = c.points[k].face;
    bary.row(static_cast<Eigen::Index>(k)) = c.points[k].bary.transpose();
  }
  return {faces, bary};
}

FeatureChecks checks_arg(const std::string& checks) {
  static const NameTable<FeatureChecks> names{{FeatureChecks::Cheap, "cheap"}, {FeatureChecks::Profiles, "profiles"}};
  return names.value(checks, "checks");
}

// The session and what Python names its features by.
class PyFeatureSession {
 public:
  explicit PyFeatureSession(const py::dict& options) {
    YAML::Node config = to_yaml(options, "FeatureSession");
    // A session writes nothing and has no schedule: a run's keys would be ignored, so they are refused.
    static const std::set<std::string> valid{"name", "implementation", "input", "feature_defaults", "features", "profile_on",
                                             "step_evaluation", "edit", "base_edit"};
    for (const auto& kv : config) {
      const std::string key = kv.first.as<std::string>();
      if (!valid.count(key)) {
        std::ostringstream o;
        o << "FeatureSession: '" << key << "' is not a session's key (valid:";
        for (const std::string& k : valid) o << " " << k;
        o << ")";
        throw InvalidConfig(o.str());
      }
    }
    if (!config["name"]) config["name"] = "session";
    // step_evaluation read here: the run's reader refuses it for a config with no later step,
    // and a session's later steps are its calls.
    bool region = true;
    if (config["step_evaluation"]) {
      YAML::Node own;
      own["step_evaluation"] = config["step_evaluation"];
      config.remove("step_evaluation");
      Config c(own, "");
      region = c.get_enum("step_evaluation", true, step_evaluation_names(), "region or whole");
    }
    spec_ = FeatureRunSpec::from_config(config, {"."});
    spec_.region_steps = region;
    if (spec_.adaptive_sparse) throw InvalidConfig("adaptive: a session evaluates the uniform hierarchy");
    for (const FeatureSpec& f : spec_.features)
      if (f.step > 0 || f.until >= 0 || !f.moves.empty() || !f.changes.empty())
        throw InvalidConfig(f.key + ": step, until, moves and changes schedule a run's design steps; a session's later "
                            "steps are its calls (add, replace, move, set, remove)");
    py::gil_scoped_release release;
    OpenedFeatureSession opened = open_feature_session(spec_);
    if (opened.edit && !is_success(opened.edit->termination))
      throw SolverError("the edit: " + opened.edit->message + " (" + std::string(to_string(opened.edit->termination)) + ")");
    session_ = std::move(opened.session);
    for (const FeatureSpec& f : spec_.features) remember(f, f.id);
    first_ = session_->evaluate();
  }

  py::dict first_step() const { return step_dict(first_); }

  py::dict add(const std::string& checks, const py::kwargs& feature) {
    FeatureSpec f = read_feature(feature_entry(feature, "add"), "add", session_->levels(), spec_.feature_defaults);
    if (names_.count(f.curve.name)) throw InvalidConfig("add.name: a feature '" + f.curve.name + "' exists already (replace it)");
    const FeatureStep step = run([&] { return session_->add(f, checks_arg(checks)); });
    remember(f, step.added.back());
    return step_dict(step);
  }

  py::dict replace(const py::object& which, const std::string& checks, const py::kwargs& feature) {
    const int id = id_of(which);
    YAML::Node node = feature_entry(feature, "replace");
    const FeatureSpec& was = drawings_.at(id);
    if (!node["name"]) node["name"] = was.curve.name;
    if (!node["level"]) node["level"] = was.curve.level;
    FeatureSpec f = read_feature(node, "replace", session_->levels(), was.curve.params);
    if (f.curve.name != was.curve.name && names_.count(f.curve.name))
      throw InvalidConfig("replace.name: a feature '" + f.curve.name + "' exists already");
    const FeatureStep step = run([&] { return session_->replace(id, f, checks_arg(checks)); });
    names_.erase(was.curve.name);
    remember(f, id);
    return step_dict(step);
  }

  // A feature given by world points translated by `by` and placed again (a config's `moves`).
  py::dict move(const py::object& which, const Vec3& by, const std::string& checks) {
    const int id = id_of(which);
    FeatureSpec f = drawings_.at(id);
    if (f.world_points.empty())
      throw InvalidConfig("move: only a feature given by world points is moved (its points are translated and placed "
                          "again); replace '" + f.curve.name + "' instead");
    for (Vec3& p : f.world_points) p += by;
    f.curve.params = session_->features().at(id).params;
    const FeatureStep step = run([&] { return session_->replace(id, f, checks_arg(checks)); });
    drawings_[id] = f;
    return step_dict(step);
  }

  py::dict set(const py::object& which, const std::string& checks, const py::kwargs& params) {
    const int id = id_of(which);
    const feature::FeatureParams now = session_->features().at(id).params;
    Config c = to_config(params, "set");
    const feature::FeatureParams q = read_feature_params(c, now);
    c.check_no_unknown_keys();
    try {
      q.validate("set");
    } catch (const InvalidInput& e) {
      throw InvalidConfig(e.what());
    }
    const FeatureStep step = run([&] { return session_->set_params(id, q, checks_arg(checks)); });
    return step_dict(step);
  }

  py::dict remove(const py::object& which, const std::string& checks) {
    const int id = id_of(which);
    const FeatureStep step = run([&] { return session_->remove(id, checks_arg(checks)); });
    names_.erase(drawings_.at(id).curve.name);
    drawings_.erase(id);
    return step_dict(step);
  }

  py::dict measure() {
    FeatureMeasurement m;
    {
      py::gil_scoped_release release;
      m = session_->measure();
    }
    return measurement_dict(m, session_->features());
  }

  MatrixX3 positions(int level) {
    const int L = session_->levels();
    if (level < -1 || level > L)
      throw InvalidInput("level " + std::to_string(level) + ": the hierarchy has levels 0.." + std::to_string(L) + " (−1: finest)");
    return session_->surface().mesh(level < 0 ? L : level).positions();
  }
  MatrixX3 original_positions(int level) const {
    return session_->original().mesh(level < 0 ? session_->levels() : level).positions();
  }
  MultiresSurface hierarchy() { return session_->surface(); }
  int levels() const { return session_->levels(); }

  py::dict features() const {
    py::dict out;
    for (const auto& [id, c] : session_->features()) {
      const auto [faces, bary] = placed_points(c);
      py::dict d;
      d["id"] = id;
      d["level"] = c.level;
      d["radius"] = c.params.radius;
      d["height"] = c.params.height;
      d["crease"] = c.params.crease;
      d["faces"] = faces;
      d["bary"] = bary;
      out[py::str(c.name)] = d;
    }
    return out;
  }

 private:
  void remember(const FeatureSpec& f, int id) {
    names_[f.curve.name] = id;
    drawings_[id] = f;
  }

  int id_of(const py::object& which) const {
    if (py::isinstance<py::int_>(which)) {
      const int id = which.cast<int>();
      if (!drawings_.count(id)) throw InvalidInput("no feature with id " + std::to_string(id));
      return id;
    }
    const std::string name = py::str(which);
    const auto it = names_.find(name);
    if (it == names_.end()) {
      std::string valid;
      for (const auto& [n, id] : names_) valid += (valid.empty() ? "" : ", ") + n;
      throw InvalidInput("no feature named '" + name + "' (features: " + valid + ")");
    }
    return it->second;
  }

  template <class F>
  FeatureStep run(F&& step) {
    py::gil_scoped_release release;
    return step();
  }

  py::dict step_dict(const FeatureStep& s) const {
    const auto names = [&](const std::vector<int>& ids) {
      py::list out;
      for (int id : ids) out.append(name_of(id));
      return out;
    };
    py::dict d;
    d["termination"] = std::string(to_string(s.summary.termination));
    d["message"] = s.summary.message;
    d["added"] = names(s.added);
    d["moved"] = names(s.moved);
    d["changed"] = names(s.changed);
    d["removed"] = s.removed;  // ids: their names are gone with them
    py::list placed;
    for (const FeaturePlacement& p : s.placed) {
      py::dict q;
      q["name"] = p.name;
      q["level"] = p.level;
      q["points"] = p.points;
      q["farthest"] = p.farthest;
      q["allowed"] = p.allowed;
      placed.append(q);
    }
    d["placed"] = placed;
    d["evaluation"] = s.evaluation.region ? "region" : "whole";
    d["vertices_recomputed"] = s.evaluation.vertices_recomputed;
    d["vertices_changed"] = s.vertices_changed;
    d["max_change"] = s.max_change;
    d["flipped_faces"] = static_cast<int>(s.folds.flipped.size());
    d["folds"] = s.folds.describe();
    d["place_s"] = s.place_s;
    d["solve_s"] = s.solve_s;
    d["check_s"] = s.check_s;
    d["profiles"] = s.profiles ? py::object(measurement_dict(*s.profiles, session_->features())) : py::none();
    return d;
  }

  std::string name_of(int id) const {
    const auto it = drawings_.find(id);
    return it == drawings_.end() ? std::string() : it->second.curve.name;
  }

  FeatureRunSpec spec_;
  std::unique_ptr<FeatureSession> session_;
  FeatureStep first_;
  std::map<std::string, int> names_;
  std::map<int, FeatureSpec> drawings_;  // each feature as drawn (its world points, for move)
};

// The features on a given hierarchy: one session step (every feature added), then measured.
py::dict apply_features(const MultiresSurface& hierarchy, const py::list& features, const std::string& profile_on,
                        const std::string& implementation) {
  FeatureSessionOptions options;
  options.backend = backend_arg(implementation);
  options.profile_target = feature::profile_target_names().value(profile_on, "profile_on");
  if (features.empty()) throw InvalidConfig("features: at least one feature curve");
  std::vector<FeatureEdit> edits;
  for (std::size_t i = 0; i < features.size(); ++i) {
    std::ostringstream where;
    where << "features[" << i << "]";
    if (!py::isinstance<py::dict>(features[i])) throw InvalidConfig(where.str() + ": expected a dict (fairshape.feature(...))");
    edits.push_back(FeatureEdit::add(
        read_feature(feature_entry(features[i].cast<py::dict>(), where.str()), where.str(), hierarchy.levels(), {})));
  }
  py::dict out;
  std::unique_ptr<FeatureSession> session;
  FeatureMeasurement measured;
  {
    py::gil_scoped_release release;
    session = std::make_unique<FeatureSession>(hierarchy, options);
    (void)session->apply(std::move(edits));
    measured = session->measure();
  }
  MultiresSurface result = session->surface();
  finite_result(result, "apply_features: the featured hierarchy");
  // Each feature's surface points as placed (projected world points), for reuse.
  py::list placed;
  for (const auto& [id, c] : session->features()) {
    const auto [faces, bary] = placed_points(c);
    placed.append(py::make_tuple(faces, bary));
  }
  const py::dict m = measurement_dict(measured, session->features());
  out["flipped_faces"] = m["flipped_faces"];
  out["folds"] = m["folds"];
  out["features"] = m["features"];
  out["placed"] = placed;
  out["within_tolerance"] = m["within_tolerance"];
  out["positions"] = py::cast(MatrixX3(result.mesh(result.levels()).positions()));
  out["hierarchy"] = py::cast(std::move(result));
  return out;
}

}  // namespace

void bind_features(py::module_& m) {
  m.def("_apply_features", &apply_features, py::arg("hierarchy"), py::arg("features"), py::arg("profile_on"),
        py::arg("implementation"), "The features' C++ half; call fairshape.apply_features().");
  py::class_<PyFeatureSession>(m, "FeatureSession", R"doc(
Khodakovsky & Schröder's editing session (§2.6): a Loop hierarchy with feature curves, advanced one
step at a time, each step re-evaluating only the region it reaches.

FeatureSession(**config): the keys of a feature config (configs/khodakovsky-schroder), read by the
same reader: input={mesh, levels, weights, remesh_base_faces}, features=[{name, level, points |
surface_points | geodesic | section | polyline, radius, height, ...}], feature_defaults, profile_on,
step_evaluation ('region' or 'whole'), edit, base_edit, implementation, name. The hierarchy is
built, the features placed and the surface evaluated once (first_step). A run's keys (output,
adaptive, sweep, ...) and the design-step schedule (step, until, moves, changes) are refused: a
session's steps are its calls.

Each step returns a dict: termination ('converged', or 'folded' with faces turned over; with
checks='profiles' the profile verdict too), message, added / moved / changed (names), removed (ids),
placed (per drawing: points, farthest — the farthest placed world point from where it was asked —
and allowed), evaluation ('region' or 'whole'), vertices_recomputed, vertices_changed (finest
vertices moved; −1 on the first step), max_change, flipped_faces, folds, place_s, solve_s
(evaluating), check_s, profiles (measure()'s dict with checks='profiles', else None). The GIL is
released while a step runs. A step that cannot place its drawing raises and changes nothing.
)doc")
      .def(py::init([](const py::kwargs& config) { return std::make_unique<PyFeatureSession>(config); }))
      .def_property_readonly("first_step", &PyFeatureSession::first_step, "the set-up's evaluation (the run's step 0)")
      .def("add", &PyFeatureSession::add, py::arg("checks") = "cheap",
           "add(checks='cheap', **feature): a `features:` entry's keys (name, level, points | surface_points | geodesic "
           "| section | polyline, radius, height, ...; fairshape.feature()'s faces + bary too)")
      .def("replace", &PyFeatureSession::replace, py::arg("feature"), py::arg("checks") = "cheap",
           "replace(feature, checks='cheap', **feature): redrawn (name or id); name, level and the profile default to "
           "the feature's")
      .def("move", &PyFeatureSession::move, py::arg("feature"), py::arg("by"), py::arg("checks") = "cheap",
           "move(feature, by=[x, y, z], checks='cheap'): a feature given by world points translated and placed again")
      .def("set", &PyFeatureSession::set, py::arg("feature"), py::arg("checks") = "cheap",
           "set(feature, checks='cheap', **params): the same curve with other profile parameters (radius, height, "
           "crease, left_right_ratio, end_height_ratio, ...), the others kept")
      .def("remove", &PyFeatureSession::remove, py::arg("feature"), py::arg("checks") = "cheap")
      .def("measure", &PyFeatureSession::measure,
           "every feature's profile (features.csv's numbers) and the folds, with their verdict (termination, message)")
      .def("positions", &PyFeatureSession::positions, py::arg("level") = -1,
           "a level of the surface with every feature applied (−1: the finest), a new n×3 array")
      .def("original_positions", &PyFeatureSession::original_positions, py::arg("level") = -1,
           "a level of the surface without features")
      .def("hierarchy", &PyFeatureSession::hierarchy, "the featured hierarchy, a new MultiresSurface")
      .def_property_readonly("levels", &PyFeatureSession::levels)
      .def_property_readonly("features", &PyFeatureSession::features,
                             "per name: id, level, radius, height, crease, faces, bary (as placed)");
}

}  // namespace fairshape::python
