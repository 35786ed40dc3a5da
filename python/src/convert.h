// Conversions between Python values and fairshape's: option keywords to a Config block (the
// same strict reads as a YAML config, so an unknown keyword is an error naming the valid
// ones), face lists, read-only NumPy views of library-owned arrays, back-end names.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <yaml-cpp/yaml.h>

#include <string>

#include "fairshape/core/backend.h"
#include "fairshape/core/config.h"
#include "fairshape/core/summary.h"
#include "fairshape/mesh/surface_mesh.h"
#include "fairshape/subdivision/scheme.h"

namespace fairshape::python {

//! None, bool, int, float, str, sequences (lists, tuples, NumPy arrays) and dicts as YAML.
//! Floats are written with 17 significant digits, so they round-trip exactly.
//! \throw InvalidConfig for anything else, naming `where`.
YAML::Node to_yaml(pybind11::handle value, const std::string& where);
//! A dict (or keyword arguments) as a Config block named `path` ("solver", "constraints[1]").
Config to_config(const pybind11::dict& options, const std::string& path);

//! A summary as the keys fairshape.Summary is made from: termination, succeeded, iterations,
//! residual, message.
void put_summary(pybind11::dict& out, const SolveSummary& s);

//! F as an m×k integer array (any integer dtype) or a sequence of sequences of ints.
//! \throw InvalidInput for anything else.
PolygonList faces_from_python(pybind11::handle F);
//! m×k int32 array when every face has k corners (also m = 0: 0×3), else a list of lists.
pybind11::object faces_to_python(const PolygonList& faces);

//! A NumPy view of `rows`×`cols` row-major doubles owned by `owner` (kept alive by the view).
pybind11::array_t<double> view(const double* data, Eigen::Index rows, Eigen::Index cols, pybind11::handle owner,
                               bool writeable);

//! "reference" | "optimized". \throw InvalidConfig naming the choices.
Backend backend_arg(const std::string& name);
//! The subdivision keywords shared by every scheme-taking function.
SubdivisionOptions subdivision_arg(const std::string& scheme, const std::string& boundary, const std::string& weights,
                                   const std::string& crease);

//! The docstring fragment for those keywords.
inline constexpr const char* kSchemeArgsDoc =
    "scheme: 'catmull-clark' or 'loop'; boundary: 'edge-only' or 'edge-and-corner'; weights (Loop's vertex "
    "weights): 'loop' or 'warren'; crease (semi-sharp decay): 'uniform' or 'chaikin'.";

}  // namespace fairshape::python
