// The pieces of the extension module fairshape._fairshape, one function per area; module.cpp
// calls them in order (errors first: every later binding may raise them).
#pragma once

#include <pybind11/pybind11.h>

namespace fairshape::python {

void bind_errors(pybind11::module_& m);
void bind_mesh(pybind11::module_& m);
void bind_hierarchy(pybind11::module_& m);
void bind_energy(pybind11::module_& m);
void bind_edit(pybind11::module_& m);
void bind_linear_solve(pybind11::module_& m);
void bind_experiment(pybind11::module_& m);
void bind_remesh(pybind11::module_& m);
void bind_curves(pybind11::module_& m);
void bind_sheets(pybind11::module_& m);
void bind_sheet_session(pybind11::module_& m);  // after bind_sheets: it hands out fairshape.Sheet
void bind_features(pybind11::module_& m);

}  // namespace fairshape::python
