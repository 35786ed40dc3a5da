// fairshape's exceptions as Python exceptions of one hierarchy, each carrying fairshape's
// message unchanged:
//   Error (RuntimeError)
//     InvalidInput (also ValueError) -> InvalidIndex (also IndexError),
//     InvalidConfig (also ValueError), TopologyError, SolverError,
//     FileError (also OSError) -> ParseError (with .file and .line), OutputError,
//                                 MissingFileError (also FileNotFoundError, errno ENOENT)
// The file errors are OSErrors, named so as not to shadow the builtin IOError (an alias of
// OSError): `except OSError` / `except FileNotFoundError` catch them as they catch Python's own.
// A C++ exception outside it (an assertion) stays pybind11's RuntimeError.
#include <pybind11/pybind11.h>

#include <cerrno>

#include "bindings.h"
#include "checks.h"
#include "fairshape/core/error.h"
#include "fairshape/core/input_file.h"

namespace py = pybind11;

namespace fairshape::python {
namespace {

// Classes live as long as the interpreter: the module keeps them as attributes.
PyObject* g_error = nullptr;
PyObject* g_invalid_input = nullptr;
PyObject* g_invalid_index = nullptr;
PyObject* g_invalid_config = nullptr;
PyObject* g_topology = nullptr;
PyObject* g_solver = nullptr;
PyObject* g_file = nullptr;
PyObject* g_missing = nullptr;
PyObject* g_parse = nullptr;
PyObject* g_output = nullptr;

// `second`, when given, is a builtin the class also derives from (ValueError, OSError, ...).
PyObject* make_class(py::module_& m, const char* name, PyObject* base, const char* doc, PyObject* second = nullptr) {
  const std::string qualified = std::string("fairshape.") + name;
  py::object bases = second ? py::object(py::make_tuple(py::handle(base), py::handle(second)))
                            : py::reinterpret_borrow<py::object>(base);
  PyObject* cls = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (!cls) throw py::error_already_set();
  m.add_object(name, py::handle(cls));
  return cls;
}

}  // namespace

void bind_errors(py::module_& m) {
  g_error = make_class(m, "Error", PyExc_RuntimeError, "Base of every error fairshape raises (fairshape::Error).");
  g_invalid_input = make_class(m, "InvalidInput", g_error, "Input that makes the operation impossible: bad ids, sizes, "
                                                             "conflicting constraints, out-of-range or non-finite "
                                                             "parameters (also a ValueError).", PyExc_ValueError);
  g_invalid_index = make_class(m, "InvalidIndex", g_invalid_input, "An index (vertex, level, point) outside its range; "
                                                                   "the message names the valid range (also an IndexError).",
                               PyExc_IndexError);
  g_invalid_config = make_class(m, "InvalidConfig", g_error, "An invalid config key, value or option (names the valid "
                                                               "ones; also a ValueError).", PyExc_ValueError);
  g_topology = make_class(m, "TopologyError", g_error, "A non-manifold or inconsistently oriented mesh.");
  g_solver = make_class(m, "SolverError", g_error, "A solver failed (singular system, factorization failure).");
  g_file = make_class(m, "FileError", g_error, "A file could not be read or written (also an OSError).", PyExc_OSError);
  g_parse = make_class(m, "ParseError", g_file, "A malformed file; .file and .line say where.");
  g_output = make_class(m, "OutputError", g_file, "An output could not be written (disk full, permissions).");
  g_missing = make_class(m, "MissingFileError", g_file, "An input file that does not exist (also a FileNotFoundError; "
                                                        "errno ENOENT).", PyExc_FileNotFoundError);

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
    } catch (const MissingFile& e) {
      // errno without strerror keeps str() the message itself (OSError formats "[Errno 2] ..."
      // only when both are set).
      py::object err = py::reinterpret_borrow<py::object>(g_missing)(e.what());
      err.attr("errno") = ENOENT;
      PyErr_SetObject(g_missing, err.ptr());
    } catch (const IOError& e) {
      PyErr_SetString(g_file, e.what());
    } catch (const InvalidIndex& e) {
      PyErr_SetString(g_invalid_index, e.what());
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
