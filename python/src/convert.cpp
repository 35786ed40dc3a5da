#include "convert.h"

#include <pybind11/stl.h>

#include <cstdio>

#include "fairshape/core/error.h"

namespace py = pybind11;

namespace fairshape::python {

YAML::Node to_yaml(py::handle value, const std::string& where) {
  if (value.is_none()) return YAML::Node(YAML::NodeType::Null);
  if (py::isinstance<py::bool_>(value)) return YAML::Node(value.cast<bool>());
  // NumPy scalars and arrays first: np.float64 is a float, np.int64 is not an int.
  if (py::hasattr(value, "tolist") && py::hasattr(value, "dtype")) return to_yaml(value.attr("tolist")(), where);
  if (py::isinstance<py::int_>(value)) return YAML::Node(value.cast<long long>());
  if (py::isinstance<py::float_>(value)) {
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", value.cast<double>());
    return YAML::Node(std::string(text));
  }
  if (py::isinstance<py::str>(value)) return YAML::Node(value.cast<std::string>());
  if (py::isinstance<py::dict>(value)) {
    YAML::Node map(YAML::NodeType::Map);
    for (const auto& [k, v] : value.cast<py::dict>()) {
      if (!py::isinstance<py::str>(k)) throw InvalidConfig(where + ": keys must be strings, got " + py::repr(k).cast<std::string>());
      const std::string key = k.cast<std::string>();
      map[key] = to_yaml(v, where + "." + key);
    }
    return map;
  }
  if (py::isinstance<py::sequence>(value)) {
    YAML::Node seq(YAML::NodeType::Sequence);
    const auto s = value.cast<py::sequence>();
    for (std::size_t i = 0; i < s.size(); ++i) seq.push_back(to_yaml(s[i], where + "[" + std::to_string(i) + "]"));
    return seq;
  }
  throw InvalidConfig(where + ": cannot pass a " + py::str(value.get_type().attr("__name__")).cast<std::string>() +
                      " as an option (numbers, strings, booleans, lists, dicts)");
}

Config to_config(const py::dict& options, const std::string& path) {
  return Config(to_yaml(options, path.empty() ? "options" : path), path);
}

void put_summary(py::dict& out, const SolveSummary& s) {
  out["termination"] = std::string(to_string(s.termination));
  out["succeeded"] = is_success(s.termination);
  out["iterations"] = s.iterations;
  out["residual"] = s.residual;
  out["message"] = s.message;
}

PolygonList faces_from_python(py::handle F) {
  PolygonList faces;
  if (py::isinstance<py::array>(F)) {
    const auto a = py::array::ensure(F);
    if (a.ndim() != 2 || (a.dtype().kind() != 'i' && a.dtype().kind() != 'u'))
      throw InvalidInput("F: expected an m×k integer array or a list of vertex-id lists, got an array of shape " +
                         py::str(a.attr("shape")).cast<std::string>() + " and dtype " + py::str(a.dtype()).cast<std::string>());
    const auto ids = py::array_t<long long, py::array::c_style | py::array::forcecast>::ensure(a);
    const auto r = ids.unchecked<2>();
    faces.assign(static_cast<std::size_t>(r.shape(0)), std::vector<int>(static_cast<std::size_t>(r.shape(1))));
    for (py::ssize_t i = 0; i < r.shape(0); ++i)
      for (py::ssize_t j = 0; j < r.shape(1); ++j) {
        const long long v = r(i, j);
        if (v < 0 || v > std::numeric_limits<int>::max())
          throw InvalidInput("F[" + std::to_string(i) + "][" + std::to_string(j) + "]: vertex id " + std::to_string(v) +
                             " out of range");
        faces[i][j] = static_cast<int>(v);
      }
    return faces;
  }
  if (!py::isinstance<py::sequence>(F) || py::isinstance<py::str>(F))
    throw InvalidInput("F: expected an m×k integer array or a list of vertex-id lists");
  for (const auto face : F.cast<py::sequence>()) {
    if (!py::isinstance<py::sequence>(face))
      throw InvalidInput("F[" + std::to_string(faces.size()) + "]: expected a list of vertex ids, got " +
                         py::repr(face).cast<std::string>());
    std::vector<int> ids;
    for (const auto v : face.cast<py::sequence>()) {
      if (!py::isinstance<py::int_>(v) && !(py::hasattr(v, "dtype") && py::hasattr(v, "__index__")))
        throw InvalidInput("F[" + std::to_string(faces.size()) + "]: vertex ids must be integers, got " +
                           py::repr(v).cast<std::string>());
      const long long id = py::int_(v).cast<long long>();
      if (id < 0 || id > std::numeric_limits<int>::max())
        throw InvalidInput("F[" + std::to_string(faces.size()) + "]: vertex id " + std::to_string(id) + " out of range");
      ids.push_back(static_cast<int>(id));
    }
    faces.push_back(std::move(ids));
  }
  return faces;
}

py::object faces_to_python(const PolygonList& faces) {
  const std::size_t k = faces.empty() ? 3 : faces.front().size();
  for (const auto& f : faces)
    if (f.size() != k) {
      py::list out;
      for (const auto& g : faces) out.append(py::cast(g));
      return out;
    }
  py::array_t<int> a({static_cast<py::ssize_t>(faces.size()), static_cast<py::ssize_t>(k)});
  auto w = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (std::size_t j = 0; j < k; ++j) w(i, j) = faces[i][j];
  return a;
}

py::array_t<double> view(const double* data, Eigen::Index rows, Eigen::Index cols, py::handle owner, bool writeable) {
  py::array_t<double> a({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)},
                        {static_cast<py::ssize_t>(cols * sizeof(double)), static_cast<py::ssize_t>(sizeof(double))},
                        data, owner);
  if (!writeable) a.attr("flags").attr("writeable") = false;
  return a;
}

Backend backend_arg(const std::string& name) { return backend_from_string(name); }

SubdivisionOptions subdivision_arg(const std::string& scheme, const std::string& boundary, const std::string& weights,
                                   const std::string& crease) {
  return {scheme_from_string(scheme), boundary_from_string(boundary), loop_weights_from_string(weights),
          crease_method_from_string(crease)};
}

}  // namespace fairshape::python
