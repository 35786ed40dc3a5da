// Semi-regular remeshing (`fairshape remesh`, input.remesh_base_faces in a config): a dense
// triangle mesh into a MultiresSurface with details, as the demo's cow is made.
#include <pybind11/stl.h>

#include "bindings.h"
#include "checks.h"
#include "convert.h"
#include "fairshape/remesh/remesh.h"

namespace py = pybind11;

namespace fairshape::python {

void bind_remesh(py::module_& m) {
  m.def(
      "remesh",
      [](const SurfaceMesh& dense, int base_faces, int levels, const std::string& scheme, const std::string& boundary,
         const std::string& weights, const std::string& base, const std::string& implementation) {
        RemeshOptions opt;
        opt.subdivision = subdivision_arg(scheme, boundary, weights, "uniform");
        opt.base_faces = base_faces;
        opt.levels = levels;
        opt.backend = backend_arg(implementation);
        if (base == "triangles") opt.base = RemeshBase::Triangles;
        else if (base != "quad-dominant") throw InvalidConfig("base '" + base + "': expected 'quad-dominant' or 'triangles'");
        RemeshReport r;
        std::optional<MultiresSurface> h;
        {
          py::gil_scoped_release release;
          h.emplace(remesh(dense, opt, &r));
        }
        finite_result(*h, "remesh: the hierarchy");
        py::list misses;
        for (const auto& miss : r.misses()) {  // a missed quality target is usable, but never silent
          misses.append(miss);
          if (PyErr_WarnEx(PyExc_UserWarning, ("remesh: " + miss).c_str(), 1) < 0) throw py::error_already_set();
        }
        py::dict report;
        report["base_faces"] = r.base_faces;
        report["fine_vertices"] = r.fine_vertices;
        report["hausdorff_relative"] = r.hausdorff_relative();
        report["edge_ratio"] = r.edge_ratio();
        report["seconds"] = r.seconds;
        report["misses"] = misses;
        return py::make_tuple(std::move(*h), report);
      },
      py::arg("dense"), py::arg("base_faces"), py::arg("levels"), py::arg("scheme") = "catmull-clark",
      py::arg("boundary") = "edge-only", py::arg("weights") = "loop", py::arg("base") = "quad-dominant",
      py::arg("implementation") = "optimized",
      "Semi-regular remesh of a dense triangle Mesh into a MultiresSurface with details (about `base_faces` base "
      "faces, `levels` levels), as a config's input.remesh_base_faces does. Returns (hierarchy, report): report "
      "holds hausdorff_relative, edge_ratio, base_faces, fine_vertices, seconds and the quality targets missed "
      "(each also a UserWarning).");
}

}  // namespace fairshape::python
