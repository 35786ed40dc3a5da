// fairshape._fairshape: the compiled half of the Python package `fairshape` (python/fairshape/
// holds the other half). Each area binds itself from its own file.
#include "bindings.h"

PYBIND11_MODULE(_fairshape, m) {
  m.doc() = "fairshape's C++ library: meshes, subdivision hierarchies, energies, constrained edits, solvers, runs";
  m.attr("__version__") = FAIRSHAPE_VERSION;
  fairshape::python::bind_errors(m);
  fairshape::python::bind_mesh(m);
  fairshape::python::bind_hierarchy(m);
  fairshape::python::bind_energy(m);
  fairshape::python::bind_edit(m);
  fairshape::python::bind_linear_solve(m);
  fairshape::python::bind_experiment(m);
  fairshape::python::bind_remesh(m);
  fairshape::python::bind_curves(m);
  fairshape::python::bind_sheets(m);
  fairshape::python::bind_sheet_session(m);
  fairshape::python::bind_features(m);
}
