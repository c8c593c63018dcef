// A script that looks at every step calls step(1) once per step, so the cost of the call itself
// is paid per step. pybind11's general dispatch (a record of the arguments, the loop over
// overloads, the casters) took about 0.6 us of the 0.9 us that a call of step(0) cost on the
// 2-core test machine; a METH_FASTCALL method reads its one argument straight from the
// interpreter's stack (python/bench/step_overhead.py measures both, docs/python.md has the
// figures).
#include "python/py_step_method.h"

#include <string_view>

namespace py = pybind11;

namespace periflex::pystep {
namespace {

// n from step(n) or step(n=...); false with a Python TypeError set when the call is malformed
bool read_count(PyObject* const* args, Py_ssize_t nargs, PyObject* kwnames, long& n) {
  const Py_ssize_t nkw = kwnames ? PyTuple_GET_SIZE(kwnames) : 0;
  if (nargs + nkw > 1) {
    PyErr_Format(PyExc_TypeError, "step() takes at most 1 argument (%zd given)", nargs + nkw);
    return false;
  }
  PyObject* value = nullptr;
  if (nargs == 1) value = args[0];
  if (nkw == 1) {
    const char* name = PyUnicode_AsUTF8(PyTuple_GET_ITEM(kwnames, 0));
    if (name == nullptr) return false;
    if (std::string_view(name) != "n") {
      PyErr_Format(PyExc_TypeError, "step() got an unexpected keyword argument '%s'", name);
      return false;
    }
    value = args[0];
  }
  if (value == nullptr) {
    n = 1;
    return true;
  }
  // whole numbers only (__index__), as pybind11 takes them for a C++ long: a float or a string
  // raises TypeError, not a cut value
  n = PyLong_AsLong(value);
  return !(n == -1 && PyErr_Occurred());
}

PyObject* step(PyObject* self, PyObject* const* args, Py_ssize_t nargs, PyObject* kwnames) {
  long n = 0;
  if (!read_count(args, nargs, kwnames, n)) return nullptr;
  // The same handling of errors as pybind11's dispatcher: an error already raised in Python
  // stays as it is (KeyboardInterrupt from a look for Ctrl-C), any other goes through the
  // registered translators (InputError, NumericalError, ValueError).
  try {
    py::handle(self).cast<PySimulation&>().step(n);
  } catch (py::error_already_set& e) {
    e.restore();
    return nullptr;
  } catch (...) {
    if (py::detail::apply_exception_translators(py::detail::get_local_internals().registered_exception_translators))
      return nullptr;
    if (py::detail::apply_exception_translators(py::detail::get_internals().registered_exception_translators))
      return nullptr;
    PyErr_SetString(PyExc_SystemError, "step: an error no translator knows");
    return nullptr;
  }
  Py_RETURN_NONE;
}

// The first lines give inspect.signature() and help() the signature.
PyMethodDef step_definition = {
    "step", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&step)), METH_FASTCALL | METH_KEYWORDS,
    "step($self, /, n=1)\n--\n\n"
    "Take n steps of dt (several sub-steps each when solver.auto_substep needs them).\n\n"
    "Other Python threads run meanwhile. Ctrl-C raises KeyboardInterrupt between two steps; the "
    "simulation stays usable and its time tells how far it got. Raises NumericalError with the "
    "program's diagnostic when the solution fails."};

}  // namespace

void bind(py::class_<PySimulation>& cls) {
  PyObject* method = PyDescr_NewMethod(reinterpret_cast<PyTypeObject*>(cls.ptr()), &step_definition);
  if (method == nullptr) throw py::error_already_set();
  cls.attr("step") = py::reinterpret_steal<py::object>(method);
}

}  // namespace periflex::pystep
