// fairshape's exceptions as Python exceptions of one hierarchy, each carrying fairshape's
// message unchanged:
//   Error (RuntimeError)
//     InvalidInput, InvalidConfig, TopologyError, SolverError,
//     IOError -> ParseError (with .file and .line), OutputError
// A C++ exception outside it (an assertion) stays pybind11's RuntimeError.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "fairshape/core/error.h"

namespace py = pybind11;

namespace fairshape::python {
namespace {

// Classes live as long as the interpreter: the module keeps them as attributes.
PyObject* g_error = nullptr;
PyObject* g_invalid_input = nullptr;
PyObject* g_invalid_config = nullptr;
PyObject* g_topology = nullptr;
PyObject* g_solver = nullptr;
PyObject* g_io = nullptr;
PyObject* g_parse = nullptr;
PyObject* g_output = nullptr;

PyObject* make_class(py::module_& m, const char* name, PyObject* base, const char* doc) {
  const std::string qualified = std::string("fairshape.") + name;
  PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base, nullptr);
  if (!cls) throw py::error_already_set();
  m.add_object(name, py::handle(cls));
  return cls;
}

}  // namespace

void bind_errors(py::module_& m) {
  g_error = make_class(m, "Error", PyExc_RuntimeError, "Base of every error fairshape raises (fairshape::Error).");
  g_invalid_input = make_class(m, "InvalidInput", g_error, "Input that makes the operation impossible: bad ids, sizes, "
                                                             "conflicting constraints, out-of-range parameters.");
  g_invalid_config = make_class(m, "InvalidConfig", g_error, "An invalid config key, value or option (names the valid ones).");
  g_topology = make_class(m, "TopologyError", g_error, "A non-manifold or inconsistently oriented mesh.");
  g_solver = make_class(m, "SolverError", g_error, "A solver failed (singular system, factorization failure).");
  g_io = make_class(m, "IOError", g_error, "A file could not be read or written.");
  g_parse = make_class(m, "ParseError", g_io, "A malformed file; .file and .line say where.");
  g_output = make_class(m, "OutputError", g_io, "An output could not be written (disk full, permissions).");

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ParseError& e) {
      py::object err = py::reinterpret_borrow<py::object>(g_parse)(e.what());
      err.attr("file") = e.file();
      err.attr("line") = e.line();
      PyErr_SetObject(g_parse, err.ptr());
    } catch (const OutputError& e) {
      PyErr_SetString(g_output, e.what());
    } catch (const IOError& e) {
      PyErr_SetString(g_io, e.what());
    } catch (const InvalidInput& e) {
      PyErr_SetString(g_invalid_input, e.what());
    } catch (const InvalidConfig& e) {
      PyErr_SetString(g_invalid_config, e.what());
    } catch (const TopologyError& e) {
      PyErr_SetString(g_topology, e.what());
    } catch (const SolverError& e) {
      PyErr_SetString(g_solver, e.what());
    } catch (const Error& e) {
      PyErr_SetString(g_error, e.what());
    }
  });
}

}  // namespace fairshape::python
